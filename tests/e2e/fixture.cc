// Test fixture of the browser test: writes the synthetic demo scene as a scene directory
// and, for one camera, where an object is: the object with the largest visible area, a
// pixel well inside it (where the test clicks) and its bounding box, from the scene's
// ground-truth labels (render of the object's Gaussians, occlusion included).
// Also the same scene with strong view-dependent colour (<out_dir>/sh_scene/: the SH
// coefficients of degrees 1-3 times 15, every other Gaussian's base colour 0.25 brighter),
// for comparing the WebGL view's SH with the server's.
//   isegman_e2e_fixture <out_dir> [camera]  -> <out_dir>/scene/, <out_dir>/sh_scene/, <out_dir>/object.json
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "app/demo_scene.h"
#include "core/sh.h"
#include "io/atomic_file.h"
#include "io/scene_loader.h"
#include "render/rasterizer.h"

using namespace isegman;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: isegman_e2e_fixture <out_dir> [camera]\n");
    return 2;
  }
  const std::filesystem::path out = argv[1];
  const int cam_index = argc > 2 ? std::atoi(argv[2]) : 0;
  DemoScene demo = make_demo_scene();
  const GaussianScene& g = demo.bundle.gaussians;
  if (cam_index < 0 || cam_index >= int(demo.bundle.cameras.size())) {
    std::fprintf(stderr, "no camera %d\n", cam_index);
    return 2;
  }
  const Camera& cam = demo.bundle.cameras[size_t(cam_index)];
  write_scene_dir((out / "scene").string(), g, demo.bundle.cameras);
  {
    GaussianScene shiny = g;
    const int k = shiny.coeffs();
    for (size_t i = 0; i < shiny.size(); ++i) {
      for (int c = 3; c < 3 * k; ++c) shiny.sh_of(i)[c] *= 15.f;
      // Every other Gaussian 0.25 brighter: base colours above 1 that the view-dependent
      // terms bring back into range in some directions (clamped only as a sum).
      if (i % 2)
        for (int c = 0; c < 3; ++c) shiny.sh_of(i)[c] += 0.25f / kShC0;
    }
    write_scene_dir((out / "sh_scene").string(), shiny, demo.bundle.cameras);
  }

  int best = -1;
  size_t best_pixels = 0;
  Image best_cov;
  for (size_t o = 0; o < demo.objects.size(); ++o) {
    std::vector<bool> mask(g.size());
    for (size_t i = 0; i < g.size(); ++i) mask[i] = demo.labels[i] == int(o);
    Image cov = render_selection(g, cam, mask);
    size_t n = 0;
    for (float v : cov.data) n += v > 0.9f;
    if (n > best_pixels) best_pixels = n, best = int(o), best_cov = std::move(cov);
  }
  if (best < 0) {
    std::fprintf(stderr, "no object is visible in camera %d\n", cam_index);
    return 1;
  }
  // Centroid of the solid part, then the solid pixel nearest to it (a point inside).
  double sx = 0, sy = 0, n = 0;
  int x0 = cam.width, y0 = cam.height, x1 = -1, y1 = -1;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const float v = best_cov.at(x, y);
      if (v > 0.5f) x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
      if (v > 0.95f) sx += x, sy += y, n += 1;
    }
  const double cx = sx / n, cy = sy / n;
  double best_d = 1e300;
  int px = 0, py = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x)
      if (best_cov.at(x, y) > 0.95f) {
        const double d = std::hypot(x - cx, y - cy);
        if (d < best_d) best_d = d, px = x, py = y;
      }
  size_t count = 0;
  for (int l : demo.labels) count += l == best;
  nlohmann::json j = {{"scene", (out / "scene").string()},
                      {"sh_scene", (out / "sh_scene").string()},
                      {"camera", cam_index},
                      {"width", cam.width},
                      {"height", cam.height},
                      {"object", demo.objects[size_t(best)].name},
                      {"object_gaussians", count},
                      {"total_gaussians", g.size()},
                      {"visible_pixels", best_pixels},
                      {"click", {(px + 0.5) / cam.width, (py + 0.5) / cam.height}},
                      {"bbox", {double(x0) / cam.width, double(y0) / cam.height, double(x1 + 1) / cam.width,
                                double(y1 + 1) / cam.height}}};
  write_file_atomic((out / "object.json").string(), j.dump(2));
  std::printf("%s\n", j.dump().c_str());
  return 0;
}
