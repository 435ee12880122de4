// isegman serve: the interactive web app on a local HTTP server.
#include <cstdio>
#include <string>

#include "app/args.h"
#include "app/command.h"
#include "app/scene_args.h"
#include "app/segment_args.h"
#include "core/error.h"
#include "edit/colorize.h"
#include "segment/trained_background.h"
#include "server/serve.h"

namespace isegman::app {
namespace {

int run_serve(const std::vector<std::string>& argv) {
  std::set<std::string> values = segment_value_flags(), switches = segment_switch_flags();
  values.insert({"cameras", "images", "port", "host", "out-dir", "data-dir", "preview", "background", "max-seconds",
                 "max-upload-mb", "kept-memory-mb"});
  switches.insert("no-segmentation");
  values.insert(scene_value_flags().begin(), scene_value_flags().end());
  switches.insert(scene_switch_flags().begin(), scene_switch_flags().end());
  Args args(argv, values, switches);
  if (args.has("photos")) throw Error("--photos: the app segments renders (edits change what the photos show)");
  SceneBundle bundle = load_scene_from_args(args);
  SegmentSetup setup = parse_segment_setup(args);

  server::ServeOptions o;
  o.host = args.get("host", "127.0.0.1");
  o.port = args.get_int("port", 8080);
  if (o.port < 0 || o.port > 65535) throw Error("--port must be in [0, 65535] (0: any free port)");
  o.max_seconds = args.get_double("max-seconds", 0);
  if (!(o.max_seconds >= 0 && o.max_seconds <= 1e7)) throw Error("--max-seconds must be in [0, 1e7]");
  o.app.out_dir = args.get("out-dir", "isegman-out");
  o.app.data_dir = args.get("data-dir", "");  // "": the scene's parent folder
  o.app.sam_dir = setup.sam_dir;
  o.app.segmentation = !args.has("no-segmentation");
  o.app.session = setup.session;
  o.app.views = setup.views;
  if (!args.has("max-side")) o.app.views.max_side = 512;  // responsive rounds; SAM works at 1024 anyway
  o.app.settings.tau = setup.session.tau;
  o.app.settings.mode = setup.session.propagation.mode;
  o.app.settings.inspection = setup.session.inspection;
  o.app.settings.views_spec = args.has("views") ? setup.views_spec : "auto";
  o.app.threads = setup.session.threads;
  const double upload_mb = args.get_double("max-upload-mb", 256);
  if (!(upload_mb >= 0 && upload_mb <= 16384)) throw Error("--max-upload-mb must be in [0, 16384]");
  o.app.max_upload_bytes = uint64_t(upload_mb * 1024 * 1024);
  const double kept_mb = args.get_double("kept-memory-mb", 2048);
  if (!(kept_mb >= 0 && kept_mb <= 1 << 20)) throw Error("--kept-memory-mb must be in [0, 1048576]");
  o.app.kept_segmentation_bytes = uint64_t(kept_mb * 1024 * 1024);
  o.app.preview_side = args.get_int("preview", 640);
  if (o.app.preview_side < 64 || o.app.preview_side > 4096) throw Error("--preview must be in [64, 4096]");
  // The colour the scene was trained over, as its photos show it: estimated once, here, for
  // the page (unless --background) and for SAM's views (unless --no-trained-background).
  segment::TrainedBackground trained;
  if (!args.has("background") || o.app.views.trained_background) {
    trained = segment::estimate_trained_background(bundle);
    if (trained.found) std::printf("%s\n", trained.summary().c_str());
  }
  segment::render_over(trained, o.app.views, o.app.session);
  o.app.views.trained_background = false;  // found above: the segmentation need not look again
  if (args.has("background")) {
    const edit::Rgb bg = edit::parse_color(args.get("background"));
    o.app.background[0] = float(bg.r);
    o.app.background[1] = float(bg.g);
    o.app.background[2] = float(bg.b);
  } else if (trained.found) {
    for (int c = 0; c < 3; ++c) o.app.background[c] = trained.rgb[c];
  }
  if (o.host != "127.0.0.1" && o.host != "localhost" && o.host != "::1")
    std::printf("warning: listening on %s: anyone who can reach it can edit the scene and write to %s\n",
                o.host.c_str(), o.app.out_dir.c_str());
  return server::serve_scene(bundle, o);
}

std::string usage() {
  return std::string(
             "usage: isegman serve <scene> [--port 8080] [--host 127.0.0.1] [--out-dir isegman-out]\n"
             "                     [--data-dir DIR] [--max-upload-mb 256] [--preview 640] [--background COLOUR]\n"
             "                     [--no-segmentation] [--max-seconds S] [--kept-memory-mb 2048]\n"
             "                     [--cameras FILE] [--images DIR] [segmentation options]\n"
             "  Opens the scene in the interactive web app: click objects to select them in 3D, see the\n"
             "  per-view evidence, edit (remove, colorize, scale, copy, combine) and export PLY/.splat.\n"
             "  Exports written on the server go below --out-dir only; scenes the page names (combine) are\n"
             "  read from below --data-dir only (default: the scene's parent folder) or uploaded from the page\n"
             "  (at most --max-upload-mb, kept in a temporary folder). --port 0 picks a free port.\n"
             "  After an edit the segmentation of the scene before it is kept (its views, for undo) while\n"
             "  the kept ones together hold at most --kept-memory-mb; the oldest go first.\n"
             "  --views auto (the default): 20 views, spread over the cameras until the first click of a\n"
             "  segmentation, then the 20 that best see the clicked point (built on demand; views no longer\n"
             "  used stay as spares within --kept-memory-mb), so a click's cost does not grow with the\n"
             "  number of cameras. Defaults differ from `segment`: --max-side 512.\n"
             "  --background: the colour the page shows behind the Gaussians (default: the one the scene\n"
             "  was trained over where its photos show it, else black).\n") +
         kSegmentOptionsHelp;
}

RegisterCommand reg("serve", "interactive web app: click to segment, edit, export (local HTTP server)", usage(),
                    run_serve);

}  // namespace
}  // namespace isegman::app
