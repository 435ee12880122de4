// isegman segment: clicks in one view -> a 3D selection of Gaussians.
#include <cstdio>
#include <filesystem>

#include "app/args.h"
#include "app/command.h"
#include "app/scene_args.h"
#include "app/segment_args.h"
#include "core/error.h"
#include "core/output_plan.h"
#include "core/selection.h"
#include "core/spatial_order.h"
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/ply.h"
#include "segment/overlay.h"
#include "segment/pipeline.h"

namespace fs = std::filesystem;

namespace isegman::app {
namespace {

std::vector<Click> parse_clicks(const Args& args) {
  std::vector<Click> clicks;
  for (const std::string& c : args.all("click")) {
    auto v = parse_numbers(c, 2, "--click");
    clicks.push_back(pixel_centre_click(v[0], v[1], 1));  // --click i,j names pixel (i, j)
  }
  for (const std::string& c : args.all("neg")) {
    auto v = parse_numbers(c, 2, "--neg");
    clicks.push_back(pixel_centre_click(v[0], v[1], 0));
  }
  if (clicks.empty()) throw Error("give at least one --click x,y");
  return clicks;
}

int run_segment(const std::vector<std::string>& argv) {
  std::set<std::string> values = segment_value_flags(), switches = segment_switch_flags();
  values.insert({"view", "click", "neg", "out", "ply", "overlays", "larger", "smaller"});
  values.insert(scene_value_flags().begin(), scene_value_flags().end());
  switches.insert(scene_switch_flags().begin(), scene_switch_flags().end());
  Args args(argv, values, switches);
  if (!args.has("out")) throw Error("missing --out FILE (the selection file to write, e.g. sel.isel)");
  if (!args.has("view")) throw Error("missing --view ID|NAME (the camera the clicks are in)");
  SceneBundle b = load_scene_from_args(args);
  const std::string out = args.get("out");
  // Every input and output, checked (and the folders created) before minutes of work.
  OutputPlan plan;
  plan.input(b.ply_path, "scene");
  plan.input(b.cameras_path, "camera file");
  for (const Camera& c : b.cameras) plan.input(c.image_path, "photo of camera '" + c.name + "'");
  plan.output(out, "selection (--out)");
  if (args.has("ply")) plan.output(args.get("ply"), "selected Gaussians (--ply)");
  if (args.has("overlays"))
    for (const Camera& c : b.cameras)
      plan.output((fs::path(args.get("overlays")) / (camera_file_stem(c.name) + ".png")).string(),
                  "overlay of camera '" + c.name + "'");
  plan.prepare();
  const Camera* cam = find_camera(b.cameras, args.get("view"));
  if (!cam) throw Error(b.cameras_path, "no camera with id or name '" + args.get("view") + "'");
  const int camera_index = int(cam - b.cameras.data());
  const std::vector<Click> clicks = parse_clicks(args);
  // --larger N / --smaller N: the last click's mask N steps larger / smaller among SAM's
  // answers at it (the web app's Larger / Smaller), for a click on a part of the object meant.
  const int larger = args.get_int("larger", 0), smaller = args.get_int("smaller", 0);
  if (larger < 0 || larger > 5 || smaller < 0 || smaller > 5) throw Error("--larger and --smaller take a step count from 0 to 5");
  if (larger > 0 && smaller > 0) throw Error("give --larger or --smaller, not both");
  if (larger + smaller > 0 && clicks.back().label != 1)
    throw Error("--larger / --smaller change the last click's mask, and the --neg clicks come last: give them without --neg");
  SegmentSetup setup = parse_segment_setup(args);
  auto sam = load_sam(setup);

  // The session works on the scene in space order (core/spatial_order.h); the selection file
  // names the Gaussians in the file's order, and carries the file's fingerprint.
  const uint64_t file_fingerprint = b.gaussians.fingerprint();
  const SpaceOrder space = put_in_space_order(b.gaussians);

  segment::PipelineTimings t;
  auto session = segment::segment_from_prompts(b, camera_index, clicks, sam, setup.session, setup.views,
                                               setup.views_spec, &t,
                                               [](const std::string& line) { std::printf("  %s\n", line.c_str()); });
  for (int step = 0; step < larger + smaller; ++step) {
    const char* which = larger > 0 ? "larger" : "smaller";
    const segment::RoundReport r = session->change_granularity(larger > 0 ? 1 : -1);
    if (r.no_granularity) {
      std::printf("SAM has no %s mask at the last click after %d step(s): the selection stays\n", which, step);
      break;
    }
    std::printf("%s mask at the last click: %zu Gaussians selected, %d views accepted\n", which, r.selected, r.accepted);
  }
  const std::vector<bool>& sel = session->selection();
  size_t count = 0;
  for (bool s : sel) count += s;
  std::printf("views: %d (%s), clicks: %zu, mode %s, tau %.2f, inspection %s\n", t.views, setup.views_spec.c_str(),
              clicks.size(), segment::mode_name(setup.session.propagation.mode), setup.session.tau,
              setup.session.inspection ? "on" : "off");
  for (size_t k = 0; k < session->views().size(); ++k) {
    const auto& st = session->view_states()[k];
    std::printf("  %-20s clicks %zu  mask %7d px  %s", session->views()[k].name.c_str(), st.clicks.size(),
                st.mask_pixels, segment::status_name(st.status));
    if (st.beyond_part_pixels > 0) std::printf("  (%d px less: the background its part shows)", st.beyond_part_pixels);
    if (!st.not_sent.empty()) std::printf("  (%zu click(s) not sent: %s)", st.not_sent.size(), st.not_sent[0].c_str());
    std::printf("\n");
  }
  std::printf("timings: views %.0f ms (render + embeddings), propagation %.1f ms, SAM %.0f ms, voting %.0f ms\n",
              t.ms_views, t.ms_propagation, t.ms_sam, t.ms_voting);
  std::printf("voting: %s (ms)\n", segment::describe(t.voting).c_str());
  std::printf("interaction time (clicks -> selection, embeddings cached): %.0f ms for %d round(s)\n",
              t.ms_interaction(), t.rounds);
  std::printf("selected %zu of %zu Gaussians\n", count, sel.size());
  if (count == 0) throw Error("nothing was selected; try another click or a lower --tau");

  Selection s = Selection::from_mask(b.gaussians, space.to_file_order(sel), file_fingerprint);
  s.score = space.to_file_order(session->scores());
  write_selection(out, s);
  std::printf("wrote %s\n", out.c_str());
  if (args.has("ply")) {
    write_ply(args.get("ply"), b.gaussians.subset(sel));
    std::printf("wrote %s (the selected Gaussians)\n", args.get("ply").c_str());
  }
  if (args.has("overlays")) {
    const fs::path dir = args.get("overlays");
    for (size_t k = 0; k < session->views().size(); ++k) {
      const auto& v = session->views()[k];
      write_png((dir / (camera_file_stem(v.name) + ".png")).string(),
                segment::make_overlay(v.rgb_image(), session->view_states()[k], session->selection_coverage(int(k))));
    }
    std::printf("wrote overlays to %s (blue: SAM mask, orange: 3D selection, dots: clicks, border: "
                "green accepted / red dropped / grey no click)\n",
                dir.string().c_str());
  }
  return 0;
}

std::string usage() {
  return std::string(
             "usage: isegman segment <scene> --view ID|NAME --click x,y [--click x,y ...] [--neg x,y ...]\n"
             "                       [--larger N | --smaller N]\n"
             "                       --out SELECTION.isel [--ply SELECTED.ply] [--overlays DIR] [options]\n"
             "  --click i,j names pixel (i, j) of that camera's image (x right, y down). Each click is a\n"
             "  round of the interactive method: propagated to every view, segmented by SAM, inspected\n"
             "  and voted into the 3D selection. --larger N / --smaller N: then the last click's mask N\n"
             "  steps larger / smaller among SAM's answers at it (a click on a pot, --larger 1: the potted\n"
             "  plant), as the web app's Larger / Smaller buttons.\n") +
         kSegmentOptionsHelp;
}

RegisterCommand reg("segment", "select an object in 3D from clicks in one view (EIP + SAM + VGV + IIM)", usage(),
                    run_segment);

}  // namespace
}  // namespace isegman::app
