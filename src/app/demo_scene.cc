#include "app/demo_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <numeric>
#include <random>

#include "core/random.h"
#include "core/sh.h"
#include "core/spatial_order.h"
#include "app/scene_builder.h"
#include "render/rasterizer.h"

namespace isegman {
namespace {

using Rng = SplitMix64;  // the demo is identical everywhere

}  // namespace

DemoScene make_demo_scene(const DemoSceneOptions& opt) {
  DemoScene demo;
  GaussianScene& g = demo.bundle.gaussians;
  g.sh_degree = opt.sh_degree;
  Rng rng(opt.seed);
  SceneBuilder b{g, demo.labels, rng, opt.sh_degree};
  const double d = opt.density;

  // Ground: a checkerboard plane of 6 x 6 units.
  const int ground = int(9000 * d);
  for (int i = 0; i < ground; ++i) {
    Vec3 p{rng.range(-3, 3), rng.range(-3, 3), 0};
    bool check = (int(std::floor(p.x * 1.5)) + int(std::floor(p.y * 1.5))) & 1;
    Vec3 col = check ? Vec3{0.78, 0.76, 0.70} : Vec3{0.45, 0.44, 0.42};
    b.splat(p, {0, 0, 1}, 0.06 / std::sqrt(d), col, -1, 0.02);
  }

  auto add_object = [&](const std::string& name, const Vec3& c, float r) {
    demo.objects.push_back({name, c, r});
    return int(demo.objects.size() - 1);
  };
  // Red sphere.
  {
    Vec3 c{-1.2, -0.8, 0.55};
    int label = add_object("red_sphere", c, 0.56f);
    const int n = int(5000 * d);
    for (int i = 0; i < n; ++i) {
      Vec3 nrm = normalized(Vec3{rng.normal(), rng.normal(), rng.normal()});
      double stripe = 0.5 + 0.5 * std::sin(nrm.z * 9);
      b.splat(c + nrm * 0.55, nrm, 0.045 / std::sqrt(d), {0.85, 0.12 + 0.1 * stripe, 0.10}, label, 0.05);
    }
  }
  // Green box.
  {
    Vec3 c{1.1, -0.6, 0.4};
    int label = add_object("green_box", c, 0.7f);
    const double h = 0.4;
    const int n = int(6000 * d);
    for (int i = 0; i < n; ++i) {
      int face = int(rng.uniform() * 5);  // no bottom face
      double u = rng.range(-h, h), v = rng.range(-h, h);
      Vec3 p, nrm;
      switch (face) {
        case 0: p = {h, u, v}; nrm = {1, 0, 0}; break;
        case 1: p = {-h, u, v}; nrm = {-1, 0, 0}; break;
        case 2: p = {u, h, v}; nrm = {0, 1, 0}; break;
        case 3: p = {u, -h, v}; nrm = {0, -1, 0}; break;
        default: p = {u, v, h}; nrm = {0, 0, 1}; break;
      }
      bool dot_mark = std::fmod(std::fabs(u * 5) + std::fabs(v * 5), 1.0) < 0.15;
      b.splat(c + p, nrm, 0.04 / std::sqrt(d), dot_mark ? Vec3{0.9, 0.9, 0.3} : Vec3{0.12, 0.70, 0.22}, label, 0.03);
    }
  }
  // Blue cylinder.
  {
    Vec3 c{0.2, 1.2, 0.0};
    int label = add_object("blue_cylinder", c + Vec3{0, 0, 0.6}, 0.75f);
    const double r = 0.35, height = 1.2;
    const int n = int(5000 * d);
    for (int i = 0; i < n; ++i) {
      if (rng.uniform() < 0.18) {  // top cap
        double rr = r * std::sqrt(rng.uniform()), a = rng.range(0, 2 * M_PI);
        b.splat(c + Vec3{rr * std::cos(a), rr * std::sin(a), height}, {0, 0, 1}, 0.04 / std::sqrt(d),
                {0.15, 0.30, 0.85}, label, 0.03);
      } else {
        double a = rng.range(0, 2 * M_PI), z = rng.range(0, height);
        Vec3 nrm{std::cos(a), std::sin(a), 0};
        double band = std::fmod(z * 4, 1.0) < 0.2 ? 0.25 : 0.0;
        b.splat(c + Vec3{r * nrm.x, r * nrm.y, z}, nrm, 0.04 / std::sqrt(d), {0.12 + band, 0.28 + band, 0.88},
                label, 0.03);
      }
    }
  }
  // Yellow torus lying on the ground.
  {
    Vec3 c{-0.3, 0.1, 0.18};
    int label = add_object("yellow_torus", c, 0.75f);
    const double R = 0.55, r = 0.18;
    const int n = int(5000 * d);
    for (int i = 0; i < n; ++i) {
      double u = rng.range(0, 2 * M_PI), v = rng.range(0, 2 * M_PI);
      Vec3 ring{std::cos(u), std::sin(u), 0};
      Vec3 nrm = ring * std::cos(v) + Vec3{0, 0, std::sin(v)};
      Vec3 p = c + ring * R + nrm * r;
      b.splat(p, nrm, 0.035 / std::sqrt(d), {0.95, 0.80, 0.15}, label, 0.04);
    }
  }

  // Orbit cameras: two rings looking at the scene centre.
  const Vec3 target{0, 0.1, 0.35};
  for (int i = 0; i < opt.cameras; ++i) {
    const bool upper = i % 2 == 1;
    const double a = 2 * M_PI * i / opt.cameras;
    const double radius = upper ? 4.2 : 5.0, height = upper ? 3.2 : 1.6;
    Vec3 eye{radius * std::cos(a), radius * std::sin(a), height};
    Camera cam = Camera::look_at(eye, target, {0, 0, 1}, opt.width, opt.height, 55.0);
    cam.id = i;
    char name[32];
    std::snprintf(name, sizeof name, "orbit_%03d", i);
    cam.name = name;
    demo.bundle.cameras.push_back(cam);
  }
  return demo;
}

std::vector<bool> demo_object_mask(const DemoScene& demo, int object) {
  std::vector<bool> m(demo.labels.size());
  for (size_t i = 0; i < m.size(); ++i) m[i] = demo.labels[i] == object;
  return m;
}

void scatter_gaussian_order(DemoScene& demo, uint64_t seed) {
  std::vector<uint32_t> order(demo.bundle.gaussians.size());
  std::iota(order.begin(), order.end(), 0u);
  std::mt19937_64 rng(seed);
  std::shuffle(order.begin(), order.end(), rng);
  reorder(demo.bundle.gaussians, order);  // Gaussian order[k] goes k-th
  std::vector<int> labels(order.size());
  for (size_t k = 0; k < order.size(); ++k) labels[k] = demo.labels[order[k]];
  demo.labels = std::move(labels);
}

bool demo_click(const DemoScene& demo, int object, int& camera, double& x, double& y, int first_camera) {
  const std::vector<bool> truth = demo_object_mask(demo, object);
  const size_t n = demo.bundle.cameras.size();
  for (size_t k = 0; k < n; ++k) {
    const size_t c = (size_t(std::max(0, first_camera)) + k) % n;
    const Camera& cam = demo.bundle.cameras[c];
    double u, v;
    if (!cam.project(demo.objects[size_t(object)].center, u, v)) continue;
    const double margin = 0.04 * cam.width;
    if (u < margin || v < margin || u > cam.width - margin || v > cam.height - margin) continue;
    RenderSettings s;
    s.color = false;
    s.depth = false;
    if (render_selection(demo.bundle.gaussians, cam, truth, s).at(int(u), int(v)) < 0.9f) continue;
    camera = int(c);
    x = std::floor(u);
    y = std::floor(v);
    return true;
  }
  return false;
}

}  // namespace isegman
