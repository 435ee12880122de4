// isegman demo: builds the synthetic demo scene, writes it as a trainer-style scene
// directory and renders a few views, so every step can be seen without any data.
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "app/args.h"
#include "app/command.h"
#include "app/demo_scene.h"
#include "core/error.h"
#include "io/image_io.h"
#include "io/scene_loader.h"
#include "render/rasterizer.h"

namespace fs = std::filesystem;

namespace isegman::app {
namespace {

int run_demo(const std::vector<std::string>& argv) {
  Args args(argv, {"out", "density", "threads"}, {});
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
  s.threads = args.get_int("threads", 0);
  s.background[0] = s.background[1] = s.background[2] = 1.f;
  for (size_t i = 0; i < demo.bundle.cameras.size(); i += 6) {
    const Camera& cam = demo.bundle.cameras[i];
    RenderOutput r = render(g, cam, s);
    const std::string path = (render_dir / (cam.name + ".png")).string();
    write_png(path, r.color);
    std::printf("rendered %s (%dx%d) in %.1f ms -> %s\n", cam.name.c_str(), cam.width, cam.height,
                r.stats.ms_preprocess + r.stats.ms_sort + r.stats.ms_raster, path.c_str());
  }
  double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("demo finished in %.2f s; try: isegman info %s\n", secs, scene_dir.c_str());
  return 0;
}

RegisterCommand reg("demo", "build a synthetic scene, save it as a scene directory and render views",
                    "usage: isegman demo [--out DIR (default isegman-demo)] [--density D] [--threads N]",
                    run_demo);

}  // namespace
}  // namespace isegman::app
