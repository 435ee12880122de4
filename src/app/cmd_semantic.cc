// isegman semantic <scene> --selection FILE --instruction TEXT (--editor-cmd CMD |
//   --editor-url URL | --editor builtin:NAME) [--steps N] --out FILE
// Instruction-driven editing of a selection (see docs/semantic.md).
#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/args.h"
#include "app/command.h"
#include "app/scene_args.h"
#include "core/error.h"
#include "core/output_plan.h"
#include "core/selection.h"
#include "edit/image_editor.h"
#include "edit/semantic_edit.h"
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/ply.h"
#include "render/rasterizer.h"

namespace fs = std::filesystem;

namespace isegman::app {

namespace {

std::atomic<bool> g_stop{false};
extern "C" void on_interrupt(int) { g_stop = true; }

const char* kUsage =
    "isegman semantic <scene> --selection FILE --instruction TEXT\n"
    "                 (--editor-cmd 'prog {in} {out} {instruction}' | --editor-url http://HOST:PORT/PATH |\n"
    "                  --editor builtin:recolor|builtin:recolor=r,g,b|builtin:grayscale)\n"
    "                 --out FILE.ply [--steps N (1500)] [--refresh-every N (10)] [--refresh-views N (1)]\n"
    "                 [--views N (all that see the selection)] [--width W] [--editor-timeout S (300)]\n"
    "                 [--schedule cosine|linear|constant] [--lambda-dssim L (0.2)] [--lr-scale F (1)]\n"
    "                 [--background r,g,b] [--threads N] [--seed N] [--save-views DIR]\n"
    "                 [--cameras FILE] [--images DIR]\n"
    "Renders the views that see the selection, edits them with the image editor, and optimises only the\n"
    "selected Gaussians toward the edited images; every other Gaussian is written back bit-identical.\n"
    "Ctrl-C stops early and writes the scene as optimised so far. The input is never modified.\n";

}  // namespace

int run_semantic(const std::vector<std::string>& argv) {
  Args args(argv,
            {"cameras", "images", "selection", "instruction", "editor-cmd", "editor-url", "editor", "editor-timeout",
             "steps", "refresh-every", "refresh-views", "views", "width", "schedule", "lambda-dssim", "lr-scale",
             "background", "threads", "seed", "out", "save-views"},
            {});
  if (!args.has("selection")) throw Error("missing --selection FILE (an .isel from `isegman segment`)");
  if (!args.has("instruction")) throw Error("missing --instruction TEXT");
  if (!args.has("out")) throw Error("missing --out FILE.ply");
  const int editors = int(args.has("editor-cmd")) + int(args.has("editor-url")) + int(args.has("editor"));
  if (editors != 1) throw Error("give exactly one of --editor-cmd, --editor-url, --editor builtin:NAME");
  const std::string out = args.get("out");
  if (fs::path(out).extension() != ".ply") throw Error(out, "the output of semantic editing is a .ply file");

  SceneBundle b = load_scene_from_args(args);
  const std::string sel_path = args.get("selection");
  // Check every output now, not after minutes of optimisation.
  OutputPlan plan;
  plan.input(b.ply_path, "scene");
  plan.input(b.cameras_path, "camera file");
  plan.input(sel_path, "selection file");
  plan.output(out, "edited scene (--out)");
  if (args.has("save-views"))
    for (const Camera& c : b.cameras)
      for (const char* kind : {"_before", "_target", "_after"})
        plan.output((fs::path(args.get("save-views")) / (camera_file_stem(c.name) + kind + ".png")).string(),
                    std::string("view") + kind + " of camera '" + c.name + "'");
  plan.prepare();
  Selection sel = read_selection(sel_path);
  sel.check_matches(b.gaussians, sel_path);
  if (sel.empty()) throw Error(sel_path, "the selection is empty");

  const double timeout = args.get_double("editor-timeout", 300);
  std::unique_ptr<edit::ImageEditor> editor;
  if (args.has("editor-cmd")) editor = edit::make_command_editor(args.get("editor-cmd"), timeout);
  else if (args.has("editor-url")) editor = edit::make_http_editor(args.get("editor-url"), timeout);
  else editor = edit::make_builtin_editor(args.get("editor"));

  edit::SemanticEditOptions o;
  o.instruction = args.get("instruction");
  o.steps = args.get_int("steps", 1500);
  if (o.steps < 1 || o.steps > 1000000) throw Error("--steps must be between 1 and 1000000");
  o.refresh_every = args.get_int("refresh-every", 10);
  if (o.refresh_every < 0) throw Error("--refresh-every must be >= 0 (0: never re-edit)");
  o.refresh_views = args.get_int("refresh-views", 1);
  if (o.refresh_views < 1) throw Error("--refresh-views must be >= 1");
  o.max_views = args.get_int("views", 0);
  if (o.max_views < 0) throw Error("--views must be >= 0");
  o.width = args.get_int("width", 0);
  if (args.has("width") && (o.width < 16 || o.width > 16384)) throw Error("--width must be between 16 and 16384");
  o.schedule = edit::parse_schedule(args.get("schedule", "cosine"));
  o.loss.lambda_dssim = args.get_double("lambda-dssim", 0.2);
  if (!(o.loss.lambda_dssim >= 0 && o.loss.lambda_dssim <= 1)) throw Error("--lambda-dssim must be in [0, 1]");
  const double lr_scale = args.get_double("lr-scale", 1.0);
  if (!(lr_scale > 0 && lr_scale < 1000)) throw Error("--lr-scale must be positive");
  o.rates.position *= lr_scale;
  o.rates.sh_dc *= lr_scale;
  o.rates.sh_rest *= lr_scale;
  o.rates.opacity *= lr_scale;
  o.rates.scale *= lr_scale;
  o.rates.rotation *= lr_scale;
  {
    const std::vector<float> bg = background_arg(args, {o.background[0], o.background[1], o.background[2]});
    for (int c = 0; c < 3; ++c) o.background[c] = bg[c];
  }
  o.threads = threads_arg(args);
  o.seed = unsigned(args.get_int("seed", 1));
  o.progress_every = std::max(1, o.steps / 30);
  o.progress = [](const edit::SemanticProgress& p) {
    const double rate = p.seconds > 0 ? p.step / p.seconds : 0;
    std::printf("step %5d/%d  loss %.5f  lr x%.3f  %.1f steps/s  editor calls %d  eta %.0f s\n", p.step, p.steps,
                p.loss, p.lr_factor, rate, p.editor_calls, rate > 0 ? (p.steps - p.step) / rate : 0.0);
    std::fflush(stdout);
  };
  o.stop = &g_stop;

  std::printf("semantic edit: %zu of %zu Gaussians selected, editor %s\ninstruction: \"%s\"\n", sel.count(),
              b.gaussians.size(), editor->describe().c_str(), o.instruction.c_str());
  std::fflush(stdout);
  g_stop = false;
  auto previous = std::signal(SIGINT, on_interrupt);
  edit::SemanticEditResult r;
  try {
    r = edit::semantic_edit(b.gaussians, b.cameras, sel, *editor, o);
  } catch (...) {
    std::signal(SIGINT, previous);
    throw;  // nothing written: the input and any previous output stay as they were
  }
  std::signal(SIGINT, previous);

  write_ply(out, r.scene);
  std::printf("%s %d of %d steps on %zu views (%.1f s optimising, %.1f s in %d editor calls); mean PSNR inside "
              "the selection vs the edited views %.2f dB\nwrote %s\n",
              r.interrupted ? "interrupted after" : "done:", r.steps_done, o.steps, r.views.size(),
              r.seconds_optimising, r.seconds_editing, r.editor_calls, r.mean_mask_psnr, out.c_str());
  if (args.has("save-views")) {
    const std::string dir = args.get("save-views");
    RenderSettings rs;
    for (int c = 0; c < 3; ++c) rs.background[c] = o.background[c];
    rs.threads = o.threads;
    for (const auto& v : r.views) {
      const std::string stem = (fs::path(dir) / camera_file_stem(v.camera.name)).string();
      write_png(stem + "_before.png", v.original);
      write_png(stem + "_target.png", v.target);
      write_png(stem + "_after.png", render(r.scene, v.camera, rs).color);
    }
    std::printf("wrote before/target/after renders of %zu views to %s\n", r.views.size(), dir.c_str());
  }
  return r.interrupted ? 130 : 0;
}

namespace {
RegisterCommand reg("semantic", "instruction-driven editing of a selection (2D editor + optimisation)", kUsage,
                    run_semantic);
}  // namespace

}  // namespace isegman::app
