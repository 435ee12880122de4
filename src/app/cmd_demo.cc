// isegman demo: builds the synthetic demo scene, writes it as a trainer-style scene
// directory and renders a few views, so every step can be seen without any data.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "app/args.h"
#include "app/command.h"
#include "app/demo_edits.h"
#include "app/demo_scene.h"
#include "core/error.h"
#include "io/image_io.h"
#include "io/scene_loader.h"
#include "render/rasterizer.h"
#ifdef ISEGMAN_HAVE_SERVER
#include "server/serve.h"
#endif
#ifdef ISEGMAN_HAVE_SEGMENT
#include "app/segment_args.h"
#include "core/selection.h"
#include "segment/evaluation.h"
#include "segment/overlay.h"
#include "segment/pipeline.h"
#endif

namespace fs = std::filesystem;

namespace isegman::app {
namespace {

#ifdef ISEGMAN_HAVE_SEGMENT
// Segments one object of the demo scene from a single click and scores it against the
// scene's known labels. Returns the selection (empty when SAM is not installed).
std::vector<bool> demo_segmentation(const DemoScene& demo, int object, const fs::path& out, int threads) {
  Args none({}, {}, {});
  SegmentSetup setup = parse_segment_setup(none);
  setup.session.threads = setup.views.threads = threads;
  setup.views_spec = "50%";
  const fs::path enc = fs::path(setup.sam_dir) / "encoder.onnx";
  if (!fs::exists(enc)) {
    std::printf("segmentation skipped: SAM model files not found in %s (run scripts/setup.sh)\n",
                setup.sam_dir.c_str());
    return {};
  }
  int camera = 0;
  double x = 0, y = 0;
  if (!demo_click(demo, object, camera, x, y)) throw Error("demo: no camera sees the object");
  const Camera& cam = demo.bundle.cameras[size_t(camera)];
  std::printf("segmenting '%s' from one click at (%.0f, %.0f) in %s; %s of the views vote\n",
              demo.objects[size_t(object)].name.c_str(), x, y, cam.name.c_str(), setup.views_spec.c_str());
  auto sam = load_sam(setup);
  segment::PipelineTimings t;
  auto session = segment::segment_from_prompts(
      demo.bundle, camera, {{x, y, 1}}, sam, setup.session, setup.views, setup.views_spec, &t,
      [](const std::string& line) { std::printf("  %s\n", line.c_str()); });
  const std::vector<bool>& sel = session->selection();
  const std::vector<bool> truth = demo_object_mask(demo, object);
  double iou = 0;
  int n = 0;
  for (const auto& v : session->views()) {
    const Image gt = segment::selection_mask(demo.bundle.gaussians, v.camera, truth, v.camera.width, v.camera.height);
    const Image pr = segment::selection_mask(demo.bundle.gaussians, v.camera, sel, v.camera.width, v.camera.height);
    const segment::MaskScore sc = segment::score_mask(pr, gt);
    if (std::count(gt.data.begin(), gt.data.end(), 1.f) < 50) continue;
    iou += sc.iou;
    ++n;
  }
  size_t count = size_t(std::count(sel.begin(), sel.end(), true));
  std::printf("selected %zu Gaussians (the object has %zu); mean IoU of the rendered masks vs ground truth: %.2f%%\n",
              count, size_t(std::count(truth.begin(), truth.end(), true)), n ? 100 * iou / n : 0.0);
  std::printf("interaction: propagation %.0f ms, SAM %.0f ms, voting %.0f ms (views + embeddings %.0f ms)\n",
              t.ms_propagation, t.ms_sam, t.ms_voting, t.ms_views);
  const fs::path seg_dir = out / "segmentation";
  fs::create_directories(seg_dir);
  Selection s = Selection::from_mask(demo.bundle.gaussians, sel);
  s.score = session->scores();
  write_selection((out / (demo.objects[size_t(object)].name + ".isel")).string(), s);
  for (size_t k = 0; k < session->views().size(); ++k) {
    const auto& v = session->views()[k];
    write_png((seg_dir / (v.name + ".png")).string(),
              segment::make_overlay(v.rgb_image(), session->view_states()[k], session->selection_coverage(int(k))));
  }
  std::printf("wrote %s and per-view evidence in %s\n",
              (out / (demo.objects[size_t(object)].name + ".isel")).string().c_str(), seg_dir.string().c_str());
  return sel;
}
#endif

int run_demo(const std::vector<std::string>& argv) {
  Args args(argv, {"out", "density", "threads", "port", "host"}, {"serve"});
  const std::string out = args.get("out", "isegman-demo");
  DemoSceneOptions opt;
  opt.density = float(args.get_double("density", 1.0));
  if (!(opt.density > 0.01f && opt.density <= 50.f)) throw Error("--density must be in (0.01, 50]");
  auto t0 = std::chrono::steady_clock::now();
  DemoScene demo = make_demo_scene(opt);
  const GaussianScene& g = demo.bundle.gaussians;
  std::printf("demo scene: %zu Gaussians (SH degree %d), %zu objects, %zu cameras\n", g.size(), g.sh_degree,
              demo.objects.size(), demo.bundle.cameras.size());
  for (size_t o = 0; o < demo.objects.size(); ++o) {
    size_t n = 0;
    for (int l : demo.labels) n += l == int(o);
    std::printf("  object %zu %-14s %6zu Gaussians\n", o, demo.objects[o].name.c_str(), n);
  }
  const std::string scene_dir = (fs::path(out) / "scene").string();
  write_scene_dir(scene_dir, g, demo.bundle.cameras);
  std::printf("wrote %s (point_cloud/iteration_30000/point_cloud.ply + cameras.json)\n", scene_dir.c_str());

  const fs::path render_dir = fs::path(out) / "renders";
  fs::create_directories(render_dir);
  RenderSettings s;
  s.threads = threads_arg(args);
  s.background[0] = s.background[1] = s.background[2] = 1.f;
  for (size_t i = 0; i < demo.bundle.cameras.size(); i += 6) {
    const Camera& cam = demo.bundle.cameras[i];
    RenderOutput r = render(g, cam, s);
    const std::string path = (render_dir / (cam.name + ".png")).string();
    write_png(path, r.color);
    std::printf("rendered %s (%dx%d) in %.1f ms -> %s\n", cam.name.c_str(), cam.width, cam.height,
                r.stats.ms_preprocess + r.stats.ms_sort + r.stats.ms_raster, path.c_str());
  }
#ifdef ISEGMAN_HAVE_SEGMENT
  const std::vector<bool> selection = demo_segmentation(demo, 0, fs::path(out), s.threads);
#endif
  std::printf("editing: box-select the blue cylinder, then remove / recolour / scale / copy it\n");
  run_edit_demo(demo, (fs::path(out) / "edits").string());
  double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("demo finished in %.2f s; try: isegman info %s\n", secs, scene_dir.c_str());
  if (args.has("serve")) {
#ifdef ISEGMAN_HAVE_SERVER
    server::ServeOptions so;
    so.host = args.get("host", "127.0.0.1");
    so.port = args.get_int("port", 8080);
    if (so.port < 0 || so.port > 65535) throw Error("--port must be between 0 and 65535");
    so.app.out_dir = (fs::path(out) / "exports").string();
    so.app.views.cache_dir = default_cache_dir();
    so.app.threads = s.threads;
    return server::serve_scene(demo.bundle, so);
#else
    throw Error("--serve: this build has no web app (src/server)");
#endif
  }
  return 0;
}

RegisterCommand reg("demo", "build a synthetic scene, save it as a scene directory and render views",
                    "usage: isegman demo [--out DIR (default isegman-demo)] [--density D] [--threads N]\n"
                    "                    [--serve [--port 8080] [--host 127.0.0.1]]\n"
                    "  --serve  afterwards open the demo scene in the web app (http://HOST:PORT/)",
                    run_demo);

}  // namespace
}  // namespace isegman::app
