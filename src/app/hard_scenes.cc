#include "app/hard_scenes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "app/scene_builder.h"
#include "core/error.h"
#include "core/sh.h"
#include "core/random.h"
#include "render/rasterizer.h"

namespace isegman {
namespace {

// A stable per-cell colour variation (bricks, planks, tiles).
double cell_noise(int a, int b) {
  uint32_t h = uint32_t(a * 73856093) ^ uint32_t(b * 19349663);
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  h ^= h >> 15;
  return (h & 0xffff) / 65535.0 - 0.5;
}

int add_object(DemoScene& demo, const std::string& name, const Vec3& c, float r) {
  demo.objects.push_back({name, c, r});
  return int(demo.objects.size() - 1);
}

// A vertical cylinder surface (side only, or with a top cap) around (c.x, c.y) from c.z up.
void cylinder(SceneBuilder& b, const Vec3& c, double r0, double r1, double height, int n, double size,
              const Vec3& rgb, int label, bool cap, double band_every = 0) {
  for (int i = 0; i < n; ++i) {
    if (cap && b.rng.uniform() < 0.15) {
      double rr = r1 * std::sqrt(b.rng.uniform()), a = b.rng.range(0, 2 * M_PI);
      b.splat(c + Vec3{rr * std::cos(a), rr * std::sin(a), height}, {0, 0, 1}, size, rgb, label, 0.03);
      continue;
    }
    double a = b.rng.range(0, 2 * M_PI), z = b.rng.range(0, height);
    double r = r0 + (r1 - r0) * z / height;
    Vec3 nrm{std::cos(a), std::sin(a), (r0 - r1) / height};
    nrm = normalized(nrm);
    Vec3 col = rgb;
    if (band_every > 0 && std::fmod(z, band_every) < band_every * 0.2) col = rgb * 0.6;
    b.splat(c + Vec3{r * std::cos(a), r * std::sin(a), z}, nrm, size, col, label, 0.03);
  }
}

// `count` Gaussians on the quad p00, p10, p11, p01 (bilinear), facing n, coloured by colour(u, v).
template <class Colour>
void quad(SceneBuilder& b, const Vec3& p00, const Vec3& p10, const Vec3& p11, const Vec3& p01, const Vec3& n, int count,
          double size, Colour colour, int label, double shine) {
  for (int i = 0; i < count; ++i) {
    const double u = b.rng.uniform(), v = b.rng.uniform();
    const Vec3 p = (p00 * (1 - u) + p10 * u) * (1 - v) + (p01 * (1 - u) + p11 * u) * v;
    b.splat(p, n, size, colour(u, v), label, shine);
  }
}

// An axis-aligned box's five visible faces (no bottom).
void box(SceneBuilder& b, const Vec3& c, double h, double hz, int n, double size, const Vec3& rgb,
         const Vec3& line_rgb, int label) {
  for (int i = 0; i < n; ++i) {
    int face = int(b.rng.uniform() * 5);
    double u = b.rng.range(-h, h), v = b.rng.range(-hz, hz);
    Vec3 p, nrm;
    switch (face) {
      case 0: p = {h, u, v}; nrm = {1, 0, 0}; break;
      case 1: p = {-h, u, v}; nrm = {-1, 0, 0}; break;
      case 2: p = {u, h, v}; nrm = {0, 1, 0}; break;
      case 3: p = {u, -h, v}; nrm = {0, -1, 0}; break;
      default: p = {u, b.rng.range(-h, h), hz}; nrm = {0, 0, 1}; break;
    }
    const bool plank = std::fmod(v + hz + 10, 0.14) < 0.02;
    b.splat(c + p, nrm, size, plank ? line_rgb : rgb, label, 0.03);
  }
}

// A shrub's leaves: `n` leaves of five strips along a random direction, centred in the
// ellipsoid of `radii` around `c` (only its front half towards -y, when `front_half`),
// facing the cameras (-y) within `tilt`, coloured between `lo` and `hi`.
struct Leaves {
  Vec3 radii;
  bool front_half = false;
  double tilt = 0.4, spacing = 0.03, length = 0.026, width = 0.02;
  Vec3 lo, hi;
};

void leaves(SceneBuilder& b, const Vec3& c, const Leaves& l, int n, int label) {
  SplitMix64& rng = b.rng;
  for (int leaf = 0; leaf < n; ++leaf) {
    Vec3 u;
    do u = {rng.range(-1, 1), l.front_half ? rng.range(-1, 0) : rng.range(-1, 1), rng.range(-1, 1)};
    while (dot(u, u) > 1);
    const Vec3 at = c + Vec3{u.x * l.radii.x, u.y * l.radii.y, u.z * l.radii.z};
    const Vec3 dir = normalized(Vec3{rng.normal(), rng.normal() * 0.3, rng.normal()});
    const Vec3 nrm = normalized(Vec3{rng.normal() * l.tilt, -1, rng.normal() * l.tilt});
    const Vec3 col{rng.range(l.lo.x, l.hi.x), rng.range(l.lo.y, l.hi.y), rng.range(l.lo.z, l.hi.z)};
    for (int k = -2; k <= 2; ++k)
      b.strip(at + dir * (k * l.spacing), nrm, dir, l.length, l.width * (1 - std::abs(k) * 0.2), col, label, 0.04);
  }
}

// What each scene's builder starts from: the named scene (SH degree 3), its random stream
// and a builder of labelled Gaussians into it. Built in place (its members refer to each
// other); `auto& [s, demo, g, rng, b] = start;` names the parts, and a builder returns
// std::move(s) (a structured binding is not moved from implicitly).
struct SceneStart {
  EvalScene s;
  DemoScene& demo;
  GaussianScene& g;
  SplitMix64 rng;
  SceneBuilder b;
  SceneStart(const std::string& name, uint64_t seed)
      : demo(s.scene), g(s.scene.bundle.gaussians), rng(seed), b{g, demo.labels, rng, 3} {
    s.name = name;
    g.sh_degree = 3;
  }
  SceneStart(const SceneStart&) = delete;
  SceneStart& operator=(const SceneStart&) = delete;
};

Camera named(Camera cam, int id, const char* prefix) {
  cam.id = id;
  char name[32];
  std::snprintf(name, sizeof name, "%s_%03d", prefix, id);
  cam.name = name;
  return cam;
}

// A grid held by hand: each camera up to `wobble` off the grid (every axis) and aimed up to
// `aim` off (across and up), drawn from its own random stream so the Gaussians do not move
// with it.
struct HandHeld {
  uint64_t seed = 0;
  double wobble = 0.03, aim = 0.05;
};

// A forward-facing capture as LLFF scenes are taken: a 5 x 4 grid of nearly parallel
// cameras, row by row from the bottom (grid_000, ...; hand_000, ... when `hand` is given),
// at `eye` + (column - 2, row - 1.5) steps of `step` (its x across, its z up; its y is not
// used), each looking at `target` moved the same way by `aim`.
void forward_grid(DemoScene& demo, const Vec3& eye, const Vec3& step, const Vec3& target, const Vec3& aim, double fov,
                  const EvalSetOptions& opt, const HandHeld* hand = nullptr) {
  SplitMix64 jitter(hand ? hand->seed : 0);
  int id = 0;
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 5; ++col) {
      Vec3 from{eye.x + (col - 2) * step.x, eye.y, eye.z + (row - 1.5) * step.z};
      Vec3 to{target.x + (col - 2) * aim.x, target.y, target.z + (row - 1.5) * aim.z};
      if (hand) {
        const double w = hand->wobble, a = hand->aim;
        from = from + Vec3{jitter.range(-w, w), jitter.range(-w, w), jitter.range(-w, w)};
        const double ax = jitter.range(-a, a), az = jitter.range(-a, a);
        to = to + Vec3{ax, 0, az};
      }
      demo.bundle.cameras.push_back(
          named(Camera::look_at(from, to, {0, 0, 1}, opt.width, opt.height, fov), id++, hand ? "hand" : "grid"));
    }
}

void add_task(EvalScene& s, const std::string& object, const std::string& kind, int label, const Vec3& anchor,
              int first_camera, double search_px = 12) {
  EvalTaskSpec t;
  t.name = s.name + "/" + object;
  t.kind = kind;
  t.object = label;
  // The radius is for 480 pixels across: the same part of the view at any resolution.
  const double scale = s.scene.bundle.cameras.empty() ? 1.0 : s.scene.bundle.cameras[0].width / 480.0;
  if (!find_click(s.scene, label, anchor, first_camera, search_px * scale, t.camera, t.x, t.y))
    throw Error("evaluation set: no camera shows " + t.name);
  s.tasks.push_back(t);
}

// Forward-facing capture of a garden wall: a bush with gaps in front of a brick wall, its
// pot, a trellis with a vase behind it.
EvalScene garden(const EvalSetOptions& opt) {
  SceneStart start("garden", 11);
  auto& [s, demo, g, rng, b] = start;
  const double d = opt.density, sz = 1 / std::sqrt(d);
  const double wall_y = 2.9;
  for (int i = 0, n = int(9000 * d); i < n; ++i) {  // brick wall
    Vec3 p{rng.range(-3.4, 3.4), wall_y, rng.range(0, 3.4)};
    const int row = int(std::floor(p.z / 0.17));
    const double shifted = p.x + (row & 1) * 0.2;
    const int col = int(std::floor(shifted / 0.4));
    const bool mortar = std::fmod(p.z, 0.17) < 0.022 || std::fmod(shifted + 40, 0.4) < 0.022;
    Vec3 c = mortar ? Vec3{0.80, 0.78, 0.74} : Vec3{0.62, 0.31, 0.22} + Vec3{1, 0.6, 0.5} * (0.12 * cell_noise(row, col));
    b.splat(p, {0, -1, 0}, 0.055 * sz, c, -1, 0.02);
  }
  for (int i = 0, n = int(7000 * d); i < n; ++i) {  // stone floor
    Vec3 p{rng.range(-3.4, 3.4), rng.range(-1.6, wall_y), 0};
    const int a = int(std::floor(p.x / 0.5)), c = int(std::floor(p.y / 0.5));
    b.splat(p, {0, 0, 1}, 0.06 * sz, Vec3{0.55, 0.55, 0.52} + Vec3{1, 1, 1} * (0.15 * cell_noise(a, c)), -1, 0.02);
  }
  // The bush: leaves scattered in an ellipsoid (gaps between them show the wall), a stem.
  const Vec3 bush_c{-1.0, 1.4, 1.15};
  const int bush = add_object(demo, "bush", bush_c, 0.7f);
  for (int leaf = 0, n = int(130 * std::max(1.0, d)); leaf < n; ++leaf) {
    Vec3 u;
    do u = {rng.range(-1, 1), rng.range(-1, 1), rng.range(-1, 1)};
    while (dot(u, u) > 1);
    const Vec3 c = bush_c + Vec3{u.x * 0.6, u.y * 0.35, u.z * 0.55};
    const Vec3 dir = normalized(Vec3{rng.normal(), rng.normal() * 0.3, rng.normal()});
    const Vec3 nrm = normalized(Vec3{rng.normal() * 0.4, -1, rng.normal() * 0.4});
    const Vec3 col{rng.range(0.12, 0.28), rng.range(0.42, 0.62), rng.range(0.08, 0.18)};
    for (int k = -2; k <= 2; ++k) b.strip(c + dir * (k * 0.035), nrm, dir, 0.03, 0.022 * (1 - std::abs(k) * 0.2), col, bush, 0.04);
  }
  for (int i = 0; i < 60; ++i) {  // stem from the pot to the bush
    const double t = i / 59.0;
    const Vec3 p = Vec3{-1.0, 1.4, 0.42} * (1 - t) + (bush_c - Vec3{0, 0, 0.2}) * t;
    b.strip(p, {0, -1, 0}, {0, 0, 1}, 0.02, 0.012, {0.35, 0.24, 0.12}, bush, 0.02);
  }
  const int pot = add_object(demo, "pot", {-1.0, 1.4, 0.21}, 0.3f);
  cylinder(b, {-1.0, 1.4, 0}, 0.17, 0.23, 0.42, int(2500 * d), 0.035 * sz, {0.72, 0.38, 0.20}, pot, false, 0.21);
  // The trellis: a lattice of thin bars in front of the wall.
  const double trellis_y = 2.1;
  const int trellis = add_object(demo, "trellis", {1.25, trellis_y, 1.25}, 1.5f);
  for (int k = 0; k < 7; ++k) {
    const double x = 0.35 + k * 0.3, z = 0.35 + k * 0.3;
    for (double t = 0.2; t < 2.3; t += 0.03) {
      for (double off : {-0.012, 0.012}) {
        b.strip({x + off, trellis_y, t}, {0, -1, 0}, {0, 0, 1}, 0.025, 0.014, {0.86, 0.76, 0.56}, trellis, 0.02);
        b.strip({t, trellis_y - 0.03, z + off}, {0, -1, 0}, {1, 0, 0}, 0.025, 0.014, {0.86, 0.76, 0.56}, trellis, 0.02);
      }
    }
  }
  // A vase behind the trellis, between it and the wall.
  const Vec3 vase_c{1.3, 2.5, 0};
  const int vase = add_object(demo, "vase", vase_c + Vec3{0, 0, 0.45}, 0.5f);
  for (int i = 0, n = int(3500 * d); i < n; ++i) {
    double a = rng.range(0, 2 * M_PI), z = rng.range(0, 0.9);
    double r = 0.16 + 0.09 * std::sin(M_PI * z / 0.9);
    Vec3 nrm = normalized(Vec3{std::cos(a), std::sin(a), -0.09 * M_PI / 0.9 * std::cos(M_PI * z / 0.9)});
    Vec3 col = std::fmod(z, 0.3) < 0.05 ? Vec3{0.92, 0.92, 0.95} : Vec3{0.10, 0.22, 0.72};
    b.splat(vase_c + Vec3{r * std::cos(a), r * std::sin(a), z}, nrm, 0.03 * sz, col, vase, 0.05);
  }
  int id = 0;
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) {
      const Vec3 eye{-0.9 + 0.6 * col, -2.6, 0.8 + 0.3 * row};
      const Vec3 target{eye.x * 0.4, 2.0, 1.1};
      demo.bundle.cameras.push_back(
          named(Camera::look_at(eye, target, {0, 0, 1}, opt.width, opt.height, 62.0), id++, "front"));
    }
  add_task(s, "bush", "gaps in front of a background", bush, bush_c, 5);
  add_task(s, "pot", "compact object below foliage", pot, {-1.0, 1.4 - 0.2, 0.25}, 9);
  add_task(s, "trellis", "thin lattice with gaps", trellis, {0.35 + 3 * 0.3, trellis_y, 0.35 + 3 * 0.3}, 6);
  add_task(s, "vase", "object seen through gaps", vase, vase_c + Vec3{0, -0.24, 0.45}, 10, 20);
  return std::move(s);
}

// Forward-facing capture where the background is close behind what is clicked: a shrub
// planted against a wall (its back leaves a few centimetres from the bricks), slats of a
// screen just in front of the same wall, a hoop lying on the floor (the floor shows in its
// hole). No empty depth range separates these objects from what their gaps show.
EvalScene alcove(const EvalSetOptions& opt) {
  SceneStart start("alcove", 29);
  auto& [s, demo, g, rng, b] = start;
  const double d = opt.density, sz = 1 / std::sqrt(d);
  const double wall_y = 1.6;
  for (int i = 0, n = int(8000 * d); i < n; ++i) {  // plastered wall with faint panels
    Vec3 p{rng.range(-2.6, 2.6), wall_y, rng.range(0, 2.6)};
    const double panel = 0.08 * cell_noise(int(std::floor(p.x / 0.6)), int(std::floor(p.z / 0.6)));
    b.splat(p, {0, -1, 0}, 0.05 * sz, Vec3{0.72, 0.70, 0.62} + Vec3{1, 1, 1} * panel, -1, 0.02);
  }
  for (int i = 0, n = int(7000 * d); i < n; ++i) {  // wooden floor
    Vec3 p{rng.range(-2.6, 2.6), rng.range(-2.2, wall_y), 0};
    const int plank = int(std::floor(p.x / 0.25));
    b.splat(p, {0, 0, 1}, 0.05 * sz, Vec3{0.50, 0.36, 0.22} + Vec3{1, 0.8, 0.6} * (0.15 * cell_noise(plank, 3)), -1,
            0.02);
  }
  // The shrub: leaves in a half-ellipsoid whose back reaches 4 cm from the wall.
  const Vec3 shrub_c{-1.0, wall_y - 0.39, 1.0};
  const int shrub = add_object(demo, "shrub", shrub_c, 0.6f);
  leaves(b, shrub_c, {{0.5, 0.35, 0.5}, true, 0.4, 0.03, 0.026, 0.02, {0.10, 0.38, 0.10}, {0.25, 0.58, 0.20}},
         int(110 * std::max(1.0, d)), shrub);
  for (int i = 0; i < 50; ++i) {  // its stem, down to the floor
    const double t = i / 49.0;
    b.strip(Vec3{-1.0, wall_y - 0.3, 0.0} * (1 - t) + (shrub_c - Vec3{0, 0.05, 0.3}) * t, {0, -1, 0}, {0, 0, 1}, 0.02,
            0.012, {0.30, 0.22, 0.12}, shrub, 0.02);
  }
  // A screen of vertical slats 6 cm in front of the wall, with two cross rails.
  const double screen_y = wall_y - 0.06;
  const int screen = add_object(demo, "screen", {0.9, screen_y, 1.0}, 0.8f);
  for (int k = 0; k < 6; ++k)
    for (double t = 0.35; t < 1.75; t += 0.025)
      for (double off : {-0.014, 0.014})
        b.strip({0.45 + k * 0.17 + off, screen_y, t}, {0, -1, 0}, {0, 0, 1}, 0.022, 0.016, {0.25, 0.16, 0.10}, screen, 0.02);
  for (double z : {0.6, 1.5})
    for (double t = 0.4; t < 1.35; t += 0.025)
      b.strip({t, screen_y - 0.02, z}, {0, -1, 0}, {1, 0, 0}, 0.022, 0.018, {0.25, 0.16, 0.10}, screen, 0.02);
  // A hoop lying on the floor: a torus of tube radius 4 cm around a 22 cm ring.
  const Vec3 hoop_c{-0.1, 0.1, 0.04};
  const int hoop = add_object(demo, "hoop", hoop_c, 0.3f);
  for (int i = 0, n = int(3000 * d); i < n; ++i) {
    const double a = rng.range(0, 2 * M_PI), t = rng.range(0, 2 * M_PI);
    const Vec3 radial{std::cos(a), std::sin(a), 0};
    const Vec3 nrm = radial * std::cos(t) + Vec3{0, 0, std::sin(t)};
    const Vec3 col = std::fmod(a, M_PI / 4) < 0.12 ? Vec3{0.95, 0.95, 0.92} : Vec3{0.15, 0.55, 0.75};
    b.splat(hoop_c + radial * 0.22 + nrm * 0.04, nrm, 0.018 * sz, col, hoop, 0.05);
  }
  int id = 0;
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) {
      const Vec3 eye{-0.9 + 0.6 * col, -2.8, 1.0 + 0.35 * row};
      const Vec3 target{eye.x * 0.3, 0.8, 0.6};
      demo.bundle.cameras.push_back(
          named(Camera::look_at(eye, target, {0, 0, 1}, opt.width, opt.height, 62.0), id++, "front"));
    }
  add_task(s, "shrub", "gaps in front of a near background", shrub, shrub_c + Vec3{0.05, -0.3, 0.05}, 5);
  add_task(s, "screen", "slats just in front of a wall", screen, {0.45 + 2 * 0.17, screen_y, 1.1}, 6);
  add_task(s, "hoop", "ring lying on the floor", hoop, hoop_c + Vec3{0, -0.26, 0.04}, 9);
  return std::move(s);
}

// An orbit capture of a courtyard: a crate behind a post, a thin pillar taller than the
// frame, a tiny die, a lamp of three parts. `coarse` makes it of fewer, larger Gaussians.
EvalScene courtyard(const EvalSetOptions& opt, bool coarse) {
  SceneStart start(coarse ? "courtyard_coarse" : "courtyard", coarse ? 23 : 17);
  auto& [s, demo, g, rng, b] = start;
  const double d = opt.density * (coarse ? 0.2 : 1.0), sz = 1 / std::sqrt(opt.density);
  b.size_scale = coarse ? 2.2 : 1.0;
  for (int i = 0, n = int(9000 * d); i < n; ++i) {
    Vec3 p{rng.range(-3, 3), rng.range(-3, 3), 0};
    bool check = (int(std::floor(p.x * 1.5)) + int(std::floor(p.y * 1.5))) & 1;
    b.splat(p, {0, 0, 1}, 0.06 * sz, check ? Vec3{0.74, 0.72, 0.66} : Vec3{0.48, 0.47, 0.45}, -1, 0.02);
  }
  const Vec3 crate_c{0.9, -0.2, 0.35};
  const int crate = add_object(demo, "crate", crate_c, 0.6f);
  box(b, crate_c, 0.35, 0.35, int(6000 * d), 0.04 * sz, {0.66, 0.46, 0.24}, {0.40, 0.26, 0.12}, crate);
  const int post = add_object(demo, "post", {0.9, -1.25, 0.9}, 1.0f);
  cylinder(b, {0.9, -1.25, 0}, 0.12, 0.12, 1.8, int(2200 * d), 0.035 * sz, {0.30, 0.32, 0.36}, post, true, 0.3);
  const int pillar = add_object(demo, "pillar", {-1.7, 1.4, 1.4}, 1.5f);
  cylinder(b, {-1.7, 1.4, 0}, 0.07, 0.06, 2.9, int(2600 * d), 0.028 * sz, {0.93, 0.92, 0.88}, pillar, true, 0.5);
  const int die = add_object(demo, "die", {-0.3, -1.2, 0.05}, 0.1f);
  box(b, {-0.3, -1.2, 0.05}, 0.05, 0.05, int(500 * std::max(d, 0.4)), 0.012 * sz, {0.85, 0.10, 0.10},
      {0.95, 0.95, 0.95}, die);
  const Vec3 lamp_c{-0.5, 0.5, 0};
  const int lamp = add_object(demo, "lamp", lamp_c + Vec3{0, 0, 0.6}, 0.7f);
  cylinder(b, lamp_c, 0.22, 0.2, 0.06, int(900 * d), 0.03 * sz, {0.18, 0.18, 0.20}, lamp, true);
  cylinder(b, lamp_c, 0.025, 0.025, 0.9, int(700 * d), 0.015 * sz, {0.75, 0.75, 0.78}, lamp, false);
  cylinder(b, lamp_c + Vec3{0, 0, 0.85}, 0.30, 0.16, 0.32, int(2200 * d), 0.03 * sz, {0.95, 0.90, 0.70}, lamp, true);
  const Vec3 target{0, 0.1, 0.45};
  for (int i = 0; i < 24; ++i) {
    const bool upper = i % 2 == 1;
    const double a = 2 * M_PI * i / 24;
    const double radius = upper ? 4.2 : 5.0, height = upper ? 3.0 : 1.5;
    const Vec3 eye{radius * std::cos(a), radius * std::sin(a), height};
    demo.bundle.cameras.push_back(named(Camera::look_at(eye, target, {0, 0, 1}, opt.width, opt.height, 55.0), i, "orbit"));
  }
  add_task(s, "crate", "object behind an occluder", crate, crate_c + Vec3{0, -0.35, 0.1}, 18);
  add_task(s, "pillar", "thin object leaving the frame", pillar, {-1.7 + 0.06, 1.4, 2.3}, 0);
  add_task(s, "die", "tiny object", die, {-0.3, -1.25, 0.05}, 18);
  add_task(s, "lamp", "compound object", lamp, lamp_c + Vec3{0, -0.25, 1.0}, 20);
  return std::move(s);
}

// A patio seen from a half orbit in front of a house wall, built after the other scenes'
// additions were tuned, as a check on objects they were not tuned on: a chair with a slatted
// back, a picket fence with a ball behind it, a potted plant (the truth: plant and pot), a
// thin pole taller than the frame, a round table with a cup standing on it.
EvalScene patio(const EvalSetOptions& opt) {
  SceneStart start("patio", 29);
  auto& [s, demo, g, rng, b] = start;
  const double d = opt.density, sz = 1 / std::sqrt(d);
  const double wall_y = 2.6;
  for (int i = 0, n = int(8000 * d); i < n; ++i) {  // rendered house wall with panels
    Vec3 p{rng.range(-3.6, 3.6), wall_y, rng.range(0, 3.2)};
    const int panel = int(std::floor((p.x + 10) / 0.9));
    const bool seam = std::fmod(p.x + 10, 0.9) < 0.03;
    Vec3 c = seam ? Vec3{0.55, 0.55, 0.58} : Vec3{0.86, 0.84, 0.76} + Vec3{1, 1, 1} * (0.06 * cell_noise(panel, 3));
    b.splat(p, {0, -1, 0}, 0.06 * sz, c, -1, 0.02);
  }
  for (int i = 0, n = int(8000 * d); i < n; ++i) {  // wooden deck
    Vec3 p{rng.range(-3.6, 3.6), rng.range(-3.2, wall_y), 0};
    const int board = int(std::floor((p.y + 10) / 0.18));
    const bool gap = std::fmod(p.y + 10, 0.18) < 0.02;
    Vec3 c = gap ? Vec3{0.22, 0.16, 0.10} : Vec3{0.58, 0.44, 0.30} + Vec3{1, 0.8, 0.6} * (0.1 * cell_noise(board, 5));
    b.splat(p, {0, 0, 1}, 0.06 * sz, c, -1, 0.02);
  }
  const Vec3 wood{0.42, 0.26, 0.14};
  // The chair: a seat, four thin legs, a back of five slats under a top rail.
  const Vec3 chair_c{-1.4, 1.5, 0};
  const int chair = add_object(demo, "chair", chair_c + Vec3{0, 0, 0.5}, 0.6f);
  box(b, chair_c + Vec3{0, 0, 0.45}, 0.22, 0.025, int(1800 * d), 0.03 * sz, wood, wood * 0.8, chair);
  for (double lx : {-0.19, 0.19})
    for (double ly : {-0.19, 0.19})
      cylinder(b, chair_c + Vec3{lx, ly, 0}, 0.022, 0.022, 0.43, int(160 * d) + 40, 0.014 * sz, wood * 0.9, chair, false);
  for (int k = 0; k < 5; ++k)
    for (double z = 0.5; z < 0.93; z += 0.025)
      b.strip(chair_c + Vec3{-0.18 + k * 0.09, 0.2, z}, {0, -1, 0}, {0, 0, 1}, 0.022, 0.016, wood, chair, 0.02);
  for (double x = -0.22; x <= 0.22; x += 0.02)
    for (double z : {0.94, 0.97})
      b.strip(chair_c + Vec3{x, 0.2, z}, {0, -1, 0}, {1, 0, 0}, 0.02, 0.02, wood * 1.1, chair, 0.02);
  // A picket fence (pickets 8 cm wide, 8 cm apart, on two rails) and a ball behind it.
  const double fence_y = 0.9;
  const int fence = add_object(demo, "fence", {1.5, fence_y, 0.45}, 1.1f);
  for (int k = 0; k < 13; ++k) {
    const double x = 0.5 + k * 0.16;
    for (double z = 0.03; z < 0.9; z += 0.025)
      for (double off : {-0.022, 0.022})
        b.strip({x + off, fence_y, z}, {0, -1, 0}, {0, 0, 1}, 0.022, 0.018, {0.93, 0.93, 0.90}, fence, 0.02);
  }
  for (double x = 0.45; x < 2.5; x += 0.02)
    for (double z : {0.22, 0.68})
      b.strip({x, fence_y + 0.03, z}, {0, -1, 0}, {1, 0, 0}, 0.02, 0.03, {0.85, 0.85, 0.82}, fence, 0.02);
  const Vec3 ball_c{1.45, 1.45, 0.24};
  const int ball = add_object(demo, "ball", ball_c, 0.3f);
  for (int i = 0, n = int(2500 * d); i < n; ++i) {
    Vec3 u;
    do u = {rng.normal(), rng.normal(), rng.normal()};
    while (norm(u) < 1e-6);
    u = normalized(u);
    const bool stripe = std::abs(u.z) < 0.2;
    b.splat(ball_c + u * 0.24, u, 0.03 * sz, stripe ? Vec3{0.95, 0.85, 0.10} : Vec3{0.85, 0.15, 0.45}, ball, 0.08);
  }
  // A potted plant: pot and foliage are one object (what a user means by "the plant").
  const Vec3 plant_c{0.1, 2.0, 0};
  const int plant = add_object(demo, "plant", plant_c + Vec3{0, 0, 0.6}, 0.6f);
  cylinder(b, plant_c, 0.15, 0.19, 0.36, int(1500 * d), 0.03 * sz, {0.66, 0.33, 0.20}, plant, false, 0.12);
  for (int leaf = 0, n = int(90 * std::max(1.0, d)); leaf < n; ++leaf) {
    Vec3 u;
    do u = {rng.range(-1, 1), rng.range(-1, 1), rng.range(-1, 1)};
    while (dot(u, u) > 1);
    const Vec3 c = plant_c + Vec3{u.x * 0.38, u.y * 0.3, 0.78 + u.z * 0.36};
    const Vec3 dir = normalized(Vec3{rng.normal(), rng.normal() * 0.3, rng.normal() + 0.8});
    const Vec3 nrm = normalized(Vec3{rng.normal() * 0.4, -1, rng.normal() * 0.4});
    const Vec3 col{rng.range(0.10, 0.22), rng.range(0.36, 0.55), rng.range(0.10, 0.20)};
    for (int k = -2; k <= 2; ++k) b.strip(c + dir * (k * 0.03), nrm, dir, 0.028, 0.02 * (1 - std::abs(k) * 0.2), col, plant, 0.04);
  }
  // A thin pole taller than the frame.
  const int pole = add_object(demo, "pole", {2.6, 2.0, 1.7}, 1.8f);
  cylinder(b, {2.6, 2.0, 0}, 0.04, 0.035, 3.4, int(1800 * d), 0.02 * sz, {0.16, 0.30, 0.22}, pole, true);
  // A round table (top and a central leg) with a cup standing on it.
  const Vec3 table_c{-0.4, -0.3, 0};
  const int table = add_object(demo, "table", table_c + Vec3{0, 0, 0.5}, 0.5f);
  cylinder(b, table_c + Vec3{0, 0, 0.66}, 0.36, 0.36, 0.04, int(2400 * d), 0.03 * sz, {0.20, 0.36, 0.52}, table, true);
  cylinder(b, table_c, 0.05, 0.04, 0.66, int(500 * d), 0.02 * sz, {0.20, 0.36, 0.52}, table, false);
  const Vec3 cup_c = table_c + Vec3{0.12, -0.1, 0.70};
  const int cup = add_object(demo, "cup", cup_c + Vec3{0, 0, 0.05}, 0.08f);
  cylinder(b, cup_c, 0.04, 0.045, 0.1, int(400 * std::max(d, 0.5)), 0.012 * sz, {0.95, 0.95, 0.95}, cup, true);
  // A half orbit in front of the wall, two heights.
  const Vec3 target{0.3, 0.8, 0.55};
  int id = 0;
  for (int row = 0; row < 2; ++row)
    for (int k = 0; k < 10; ++k) {
      const double a = (-75 + 150.0 * k / 9) * M_PI / 180;
      const Vec3 eye{target.x + 4.3 * std::sin(a), target.y - 4.3 * std::cos(a), row ? 2.0 : 1.1};
      demo.bundle.cameras.push_back(named(Camera::look_at(eye, target, {0, 0, 1}, opt.width, opt.height, 60.0), id++, "arc"));
    }
  add_task(s, "chair", "compound object with gaps in front of a wall", chair, chair_c + Vec3{0, 0.19, 0.955}, 4);
  add_task(s, "fence", "pickets with gaps in front of a ball", fence, {0.5 + 6 * 0.16, fence_y - 0.01, 0.45}, 4);
  add_task(s, "ball", "object seen through a fence", ball, ball_c + Vec3{0, -0.24, 0.0}, 4, 20);
  add_task(s, "plant", "compound object: a plant with its pot", plant, plant_c + Vec3{0, -0.3, 0.85}, 13);
  add_task(s, "pole", "thin pole taller than the frame", pole, {2.6, 2.0 - 0.04, 2.3}, 6);
  add_task(s, "cup", "tiny object on a table", cup, cup_c + Vec3{0, -0.045, 0.05}, 14);
  add_task(s, "table", "compound object with a smaller one on it", table, table_c + Vec3{0, -0.36, 0.68}, 3);
  return std::move(s);
}

// Forward-facing handheld capture of a study, as LLFF scenes are taken (a 5 x 4 grid of
// nearly parallel cameras): a picture hanging flat on the wall, a row of books standing
// side by side, a mug with a handle on a desk, a hanging plant in front of a window whose
// far view shows through its leaves, and a floor lamp (thin stem, shade) at the frame's edge.
EvalScene study(const EvalSetOptions& opt) {
  SceneStart start("study", 41);
  auto& [s, demo, g, rng, b] = start;
  const double d = opt.density, sz = 1 / std::sqrt(d);
  const double wall_y = 2.4;
  const double win_x0 = 0.7, win_x1 = 1.7, win_z0 = 1.0, win_z1 = 2.0;
  for (int i = 0, n = int(9000 * d); i < n; ++i) {  // papered wall with a window opening
    Vec3 p{rng.range(-2.6, 2.8), wall_y, rng.range(0, 2.7)};
    if (p.x > win_x0 && p.x < win_x1 && p.z > win_z0 && p.z < win_z1) continue;
    const bool stripe = std::fmod(p.x + 10, 0.2) < 0.1;
    b.splat(p, {0, -1, 0}, 0.05 * sz, stripe ? Vec3{0.80, 0.76, 0.66} : Vec3{0.74, 0.70, 0.62}, -1, 0.02);
  }
  for (double x = win_x0 - 0.04; x < win_x1 + 0.04; x += 0.02)  // the window frame
    for (double z : {win_z0 - 0.02, win_z1 + 0.02, (win_z0 + win_z1) / 2})
      b.strip({x, wall_y - 0.01, z}, {0, -1, 0}, {1, 0, 0}, 0.02, 0.04, {0.95, 0.95, 0.93}, -1, 0.02);
  for (double z = win_z0; z < win_z1; z += 0.02)
    for (double x : {win_x0 - 0.02, win_x1 + 0.02, (win_x0 + win_x1) / 2})
      b.strip({x, wall_y - 0.01, z}, {0, -1, 0}, {0, 0, 1}, 0.02, 0.04, {0.95, 0.95, 0.93}, -1, 0.02);
  for (int i = 0, n = int(2500 * d); i < n; ++i) {  // the view outside: trees and sky, 6 m away
    Vec3 p{rng.range(-1.5, 4.5), 8.0, rng.range(-0.5, 4.5)};
    const double tree = 0.5 + 0.5 * std::sin(p.x * 3.1) * std::cos(p.z * 2.3);
    const Vec3 c = p.z < 1.6 + tree ? Vec3{0.25, 0.45, 0.20} + Vec3{0.1, 0.1, 0.05} * cell_noise(int(p.x * 4), int(p.z * 4))
                                     : Vec3{0.70, 0.82, 0.95};
    b.splat(p, {0, -1, 0}, 0.14 * sz, c, -1, 0.0);
  }
  for (int i = 0, n = int(7000 * d); i < n; ++i) {  // carpet
    Vec3 p{rng.range(-2.6, 2.8), rng.range(-1.2, wall_y), 0};
    b.splat(p, {0, 0, 1}, 0.05 * sz, Vec3{0.36, 0.30, 0.34} + Vec3{1, 1, 1} * (0.05 * cell_noise(int(p.x * 8), int(p.y * 8))), -1, 0.01);
  }
  // A picture hanging flat on the wall: a canvas 1 cm in front of it inside a dark frame.
  const int picture = add_object(demo, "picture", {-0.55, wall_y - 0.01, 1.55}, 0.4f);
  for (int i = 0, n = int(1600 * d); i < n; ++i) {
    const double x = rng.range(-0.9, -0.2), z = rng.range(1.3, 1.8);
    const bool frame = x < -0.86 || x > -0.24 || z < 1.34 || z > 1.76;
    const Vec3 c = frame ? Vec3{0.20, 0.13, 0.08}
                         : Vec3{0.55 + 0.4 * cell_noise(int(x * 9), 1), 0.45 + 0.4 * cell_noise(int(z * 9), 2), 0.6};
    b.splat({x, wall_y - 0.01, z}, {0, -1, 0}, 0.025 * sz, c, picture, 0.03);
  }
  // A low shelf against the wall holding a row of books standing side by side.
  const Vec3 shelf_c{-1.25, wall_y - 0.25, 0};
  box(b, shelf_c + Vec3{0, 0, 0.2}, 0.24, 0.2, int(1500 * d), 0.03 * sz, {0.55, 0.40, 0.26}, {0.45, 0.32, 0.2}, -1);
  const Vec3 book_colours[] = {{0.15, 0.25, 0.55}, {0.62, 0.12, 0.12}, {0.15, 0.25, 0.55}, {0.20, 0.45, 0.25},
                               {0.60, 0.55, 0.20}, {0.15, 0.25, 0.55}};
  int book = -1;
  for (int k = 0; k < 6; ++k) {
    const double x0 = shelf_c.x - 0.21 + k * 0.07, height = 0.26 + 0.04 * ((k * 7) % 3);
    const int label = k == 1 ? add_object(demo, "book", {x0 + 0.033, shelf_c.y, 0.4 + height / 2}, 0.2f) : -1;
    if (k == 1) book = label;
    for (int i = 0, n = int(300 * d); i < n; ++i) {  // spine (facing the cameras), top, sides
      const int face = int(rng.uniform() * 4);
      Vec3 p, nrm;
      if (face <= 1) p = {rng.range(x0, x0 + 0.066), shelf_c.y - 0.1, 0.4 + rng.range(0, height)}, nrm = {0, -1, 0};
      else if (face == 2) p = {rng.range(x0, x0 + 0.066), shelf_c.y + rng.range(-0.1, 0.1), 0.4 + height}, nrm = {0, 0, 1};
      else p = {x0 + (rng.uniform() < 0.5 ? 0.0 : 0.066), shelf_c.y + rng.range(-0.1, 0.1), 0.4 + rng.range(0, height)},
           nrm = {p.x > x0 ? 1.0 : -1.0, 0, 0};
      const Vec3 c = std::fmod(p.z, 0.1) < 0.012 ? book_colours[k] * 1.6 : book_colours[k];
      b.splat(p, nrm, 0.014 * sz, c, label, 0.03);
    }
  }
  // A desk (top and four legs) with a mug on it.
  const Vec3 desk_c{0.2, 1.6, 0};
  box(b, desk_c + Vec3{0, 0, 0.74}, 0.5, 0.02, int(2200 * d), 0.03 * sz, {0.30, 0.22, 0.16}, {0.30, 0.22, 0.16}, -1);
  for (double lx : {-0.46, 0.46})
    for (double ly : {-0.3, 0.3})
      cylinder(b, desk_c + Vec3{lx, ly * 0.9, 0}, 0.025, 0.025, 0.72, int(150 * d) + 40, 0.015 * sz, {0.2, 0.2, 0.2}, -1, false);
  const Vec3 mug_c = desk_c + Vec3{0.25, -0.2, 0.76};
  const int mug = add_object(demo, "mug", mug_c + Vec3{0, 0, 0.05}, 0.1f);
  cylinder(b, mug_c, 0.04, 0.04, 0.1, int(500 * std::max(d, 0.5)), 0.012 * sz, {0.85, 0.35, 0.15}, mug, true);
  for (int i = 0; i < 36; ++i) {  // the handle: a half ring beside the mug
    const double a = -M_PI / 2 + M_PI * i / 35;
    const Vec3 p = mug_c + Vec3{0.04 + 0.03 * std::cos(a), 0, 0.05 + 0.03 * std::sin(a)};
    b.strip(p, {0, -1, 0}, {-std::sin(a), 0, std::cos(a)}, 0.01, 0.012, {0.85, 0.35, 0.15}, mug, 0.03);
  }
  // A hanging plant in front of the window: a pot on three cords, trailing leaves.
  const Vec3 hang_c{1.2, wall_y - 0.45, 1.75};
  const int hanging = add_object(demo, "hanging_plant", hang_c + Vec3{0, 0, -0.15}, 0.5f);
  cylinder(b, hang_c, 0.09, 0.12, 0.16, int(700 * d), 0.02 * sz, {0.82, 0.80, 0.74}, hanging, false);
  for (int cord = 0; cord < 3; ++cord) {
    const double a = cord * 2 * M_PI / 3;
    const Vec3 from = hang_c + Vec3{0.11 * std::cos(a), 0.11 * std::sin(a), 0.16}, to = hang_c + Vec3{0, 0, 0.75};
    for (double t = 0; t < 1; t += 0.02)
      b.strip(from + (to - from) * t, {0, -1, 0}, normalized(to - from), 0.02, 0.006, {0.6, 0.55, 0.45}, hanging, 0.01);
  }
  for (int leaf = 0, n = int(70 * std::max(1.0, d)); leaf < n; ++leaf) {
    const double a = rng.range(0, 2 * M_PI), r = rng.range(0.08, 0.3), drop = rng.range(-0.55, 0.1);
    const Vec3 c = hang_c + Vec3{r * std::cos(a), 0.6 * r * std::sin(a), 0.12 + drop};
    const Vec3 dir = normalized(Vec3{rng.normal() * 0.4, rng.normal() * 0.2, -1});
    const Vec3 nrm = normalized(Vec3{rng.normal() * 0.5, -1, rng.normal() * 0.3});
    const Vec3 col{rng.range(0.12, 0.25), rng.range(0.40, 0.60), rng.range(0.12, 0.22)};
    for (int k = -1; k <= 1; ++k) b.strip(c + dir * (k * 0.025), nrm, dir, 0.024, 0.018, col, hanging, 0.04);
  }
  // A floor lamp at the right: a round base, a thin stem, a conical shade.
  const Vec3 lamp_c{1.45, 1.2, 0};
  const int lamp = add_object(demo, "floor_lamp", lamp_c + Vec3{0, 0, 0.9}, 1.0f);
  cylinder(b, lamp_c, 0.16, 0.14, 0.03, int(500 * d), 0.02 * sz, {0.15, 0.15, 0.15}, lamp, true);
  cylinder(b, lamp_c + Vec3{0, 0, 0.03}, 0.012, 0.012, 1.45, int(700 * d), 0.01 * sz, {0.15, 0.15, 0.15}, lamp, false);
  cylinder(b, lamp_c + Vec3{0, 0, 1.4}, 0.22, 0.12, 0.28, int(1200 * d), 0.025 * sz, {0.92, 0.86, 0.70}, lamp, false);
  // The capture: a 5 x 4 grid of cameras 3.4 m from the wall, all looking nearly straight ahead.
  forward_grid(demo, {0.25, -1.0, 1.15}, {0.22, 0, 0.16}, {0.25, wall_y, 1.1}, {0.08, 0, 0.05}, 62.0, opt);
  add_task(s, "picture", "flat object hanging on a wall", picture, {-0.5, wall_y - 0.01, 1.6}, 7);
  add_task(s, "book", "one of a row of touching objects", book, {shelf_c.x - 0.14 + 0.033, shelf_c.y - 0.1, 0.55}, 12);
  add_task(s, "mug", "small object with a handle", mug, mug_c + Vec3{0, -0.04, 0.05}, 2);
  add_task(s, "hanging_plant", "sparse leaves in front of a window", hanging, hang_c + Vec3{0, -0.12, 0.08}, 17);
  add_task(s, "floor_lamp", "thin stem under a shade at the frame edge", lamp, lamp_c + Vec3{0, -0.2, 1.55}, 9);
  return std::move(s);
}

// A kitchen counter filmed on a handheld arc in front of it (cameras at two heights, some
// nearer), built after every other scene's additions were tuned and reported as its first
// run: a bottle standing behind a jar (hidden in the low views), a wire basket whose gaps
// show the tiles and the counter, a kettle with a handle and a spout, a salt shaker (tiny),
// and a ladle hanging 2 cm in front of the tiles near the frame's edge.
EvalScene kitchen(const EvalSetOptions& opt) {
  SceneStart start("kitchen", 57);
  auto& [s, demo, g, rng, b] = start;
  const double d = opt.density, sz = 1 / std::sqrt(d);
  const double wall_y = 0.6, top = 0.9;
  for (int i = 0, n = int(13000 * d); i < n; ++i) {  // tiled backsplash: 10 cm tiles, grey grout
    const double x = rng.range(-2.4, 2.4), z = rng.range(top, 2.3);
    const bool grout = std::fmod(x + 10, 0.1) < 0.008 || std::fmod(z, 0.1) < 0.008;
    const Vec3 c = grout ? Vec3{0.55, 0.55, 0.52}
                         : Vec3{0.78, 0.86, 0.84} + Vec3{1, 1, 1} * (0.06 * cell_noise(int((x + 10) * 10), int(z * 10)));
    b.splat({x, wall_y, z}, {0, -1, 0}, 0.03 * sz, c, -1, 0.04);
  }
  for (int i = 0, n = int(9000 * d); i < n; ++i) {  // speckled stone counter top
    const Vec3 p{rng.range(-2.4, 2.4), rng.range(-0.05, wall_y), top};
    const double speck = cell_noise(int((p.x + 10) * 40), int((p.y + 10) * 40));
    b.splat(p, {0, 0, 1}, 0.03 * sz, Vec3{0.30, 0.28, 0.27} + Vec3{1, 1, 1} * (speck > 0.3 ? 0.3 : 0.05 * speck), -1, 0.05);
  }
  for (int i = 0, n = int(6000 * d); i < n; ++i) {  // cabinet doors under it
    const Vec3 p{rng.range(-2.4, 2.4), -0.05, rng.range(0, top)};
    const bool gap = std::fmod(p.x + 10, 0.5) < 0.01 || p.z > top - 0.05;
    b.splat(p, {0, -1, 0}, 0.04 * sz, gap ? Vec3{0.15, 0.12, 0.1} : Vec3{0.62, 0.50, 0.36}, -1, 0.02);
  }
  for (int i = 0, n = int(3000 * d); i < n; ++i)  // floor
    b.splat({rng.range(-2.4, 2.4), rng.range(-1.8, -0.05), 0}, {0, 0, 1}, 0.06 * sz,
            Vec3{0.55, 0.52, 0.48} + Vec3{1, 1, 1} * (0.05 * cell_noise(int(rng.uniform() * 9), 3)), -1, 0.01);
  // A jar with a lid in front of a bottle.
  const Vec3 jar_c{-0.5, 0.12, top};
  cylinder(b, jar_c, 0.075, 0.075, 0.17, int(900 * d), 0.014 * sz, {0.80, 0.58, 0.20}, -1, true);
  cylinder(b, jar_c + Vec3{0, 0, 0.17}, 0.078, 0.078, 0.025, int(250 * d), 0.012 * sz, {0.85, 0.85, 0.85}, -1, true);
  const Vec3 bottle_c{-0.47, 0.34, top};
  const int bottle = add_object(demo, "bottle", bottle_c + Vec3{0, 0, 0.16}, 0.2f);
  cylinder(b, bottle_c, 0.04, 0.04, 0.2, int(700 * d), 0.012 * sz, {0.12, 0.42, 0.22}, bottle, false);
  cylinder(b, bottle_c + Vec3{0, 0, 0.2}, 0.04, 0.015, 0.05, int(150 * d) + 40, 0.01 * sz, {0.12, 0.42, 0.22}, bottle, false);
  cylinder(b, bottle_c + Vec3{0, 0, 0.25}, 0.015, 0.015, 0.07, int(120 * d) + 40, 0.008 * sz, {0.12, 0.42, 0.22}, bottle, true);
  // A wire basket: 18 upright wires and three rings, the counter and tiles seen between them.
  const Vec3 basket_c{0.08, 0.3, top};
  const int basket = add_object(demo, "basket", basket_c + Vec3{0, 0, 0.07}, 0.15f);
  const Vec3 wire{0.18, 0.18, 0.2};
  for (int k = 0; k < 18; ++k) {
    const double a = 2 * M_PI * k / 18;
    const Vec3 nrm{std::cos(a), std::sin(a), 0};
    for (double z = 0.005; z < 0.14; z += 0.008)
      b.strip(basket_c + Vec3{0.12 * nrm.x, 0.12 * nrm.y, z}, nrm, {0, 0, 1}, 0.01, 0.005, wire, basket, 0.06);
  }
  for (double z : {0.005, 0.07, 0.14})
    for (int k = 0; k < 90; ++k) {
      const double a = 2 * M_PI * k / 90;
      const Vec3 nrm{std::cos(a), std::sin(a), 0};
      b.strip(basket_c + Vec3{0.12 * nrm.x, 0.12 * nrm.y, z}, nrm, {-nrm.y, nrm.x, 0}, 0.01, 0.005, wire, basket, 0.06);
    }
  // A kettle: body, lid, a handle arching over it and a spout.
  const Vec3 kettle_c{0.62, 0.25, top};
  const int kettle = add_object(demo, "kettle", kettle_c + Vec3{0, 0, 0.12}, 0.2f);
  const Vec3 steel{0.70, 0.70, 0.73};
  cylinder(b, kettle_c, 0.095, 0.08, 0.16, int(1400 * d), 0.014 * sz, steel, kettle, true);
  for (int i = 0; i < 50; ++i) {
    const double a = M_PI * i / 49;
    const Vec3 p = kettle_c + Vec3{0.07 * std::cos(a), 0, 0.17 + 0.08 * std::sin(a)};
    b.strip(p, {0, -1, 0}, {-std::sin(a), 0, std::cos(a)}, 0.012, 0.007, {0.1, 0.1, 0.1}, kettle, 0.03);
  }
  for (double t = 0; t < 1; t += 0.05) {
    const Vec3 p = kettle_c + Vec3{-0.09 - 0.08 * t, -0.02, 0.06 + 0.07 * t};
    b.strip(p, {0, -1, 0}, normalized(Vec3{-0.08, 0, 0.07}), 0.014, 0.02 - 0.008 * t, steel, kettle, 0.05);
  }
  // A salt shaker: 2 cm across, a silver cap.
  const Vec3 salt_c{-0.12, 0.08, top};
  const int salt = add_object(demo, "salt", salt_c + Vec3{0, 0, 0.03}, 0.04f);
  cylinder(b, salt_c, 0.018, 0.018, 0.05, int(160 * d) + 60, 0.006 * sz, {0.95, 0.95, 0.93}, salt, false);
  cylinder(b, salt_c + Vec3{0, 0, 0.05}, 0.018, 0.012, 0.015, 80, 0.005 * sz, {0.6, 0.6, 0.62}, salt, true);
  // A rail on the tiles and a wooden ladle hanging from it, 2 cm in front of them.
  for (double x = -1.4; x < -0.6; x += 0.01)
    b.strip({x, wall_y - 0.03, 1.55}, {0, -1, 0}, {1, 0, 0}, 0.012, 0.012, {0.5, 0.5, 0.52}, -1, 0.05);
  const Vec3 ladle_c{-1.05, wall_y - 0.02, 1.2};
  const int ladle = add_object(demo, "ladle", ladle_c + Vec3{0, 0, 0.15}, 0.2f);
  for (double z = 0.08; z < 0.36; z += 0.006)
    b.strip(ladle_c + Vec3{0, 0, z}, {0, -1, 0}, {0, 0, 1}, 0.01, 0.014, {0.55, 0.36, 0.18}, ladle, 0.03);
  for (int i = 0, n = int(300 * d) + 60; i < n; ++i) {  // the bowl: a half sphere opening up
    const double a = rng.range(0, 2 * M_PI), e = rng.range(0, M_PI / 2);
    const Vec3 nrm{std::cos(a) * std::cos(e), std::sin(a) * std::cos(e), -std::sin(e)};
    b.splat(ladle_c + Vec3{0, 0, 0.06} + nrm * 0.05, nrm, 0.01 * sz, {0.55, 0.36, 0.18}, ladle, 0.03);
  }
  // The capture: a handheld arc, 22 cameras alternating between two heights, every third nearer.
  const Vec3 focus{0.0, 0.3, top + 0.2};
  for (int id = 0; id < 22; ++id) {
    const double a = (-0.9 + 1.8 * id / 21.0), r = id % 3 == 0 ? 1.15 : 1.5;
    const Vec3 eye{focus.x + r * std::sin(a), focus.y - r * std::cos(a), id % 2 ? 1.62 : 1.3};
    const Vec3 target = focus + Vec3{0.25 * std::sin(id * 1.7), 0, 0.12 * std::cos(id * 2.3)};
    demo.bundle.cameras.push_back(named(Camera::look_at(eye, target, {0, 0, 1}, opt.width, opt.height, 60.0), id, "arc"));
  }
  add_task(s, "bottle", "bottle partly hidden behind a jar", bottle, bottle_c + Vec3{0, -0.015, 0.29}, 4);
  add_task(s, "basket", "wire basket: the counter and tiles through its gaps", basket, basket_c + Vec3{0, -0.12, 0.07}, 11);
  add_task(s, "kettle", "kettle with a handle and a spout", kettle, kettle_c + Vec3{0, -0.09, 0.08}, 8);
  add_task(s, "salt", "tiny object", salt, salt_c + Vec3{0, -0.018, 0.025}, 14);
  add_task(s, "ladle", "thin hanging object close to the wall near the frame edge", ladle, ladle_c + Vec3{0, -0.05, 0.05}, 2);
  return std::move(s);
}

// A tube along a segment: `n` flat Gaussians on its surface, the radius going from r0 to r1.
void tube(SceneBuilder& b, const Vec3& p0, const Vec3& p1, double r0, double r1, int n, double size, const Vec3& rgb,
          int label) {
  const Vec3 axis = normalized(p1 - p0);
  const Vec3 side = normalized(cross(axis, std::abs(axis.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0}));
  const Vec3 up = cross(side, axis);
  for (int i = 0; i < n; ++i) {
    const double t = b.rng.uniform(), a = b.rng.range(0, 2 * M_PI), r = r0 + (r1 - r0) * t;
    const Vec3 radial = side * std::cos(a) + up * std::sin(a);
    b.splat(p0 + (p1 - p0) * t + radial * r, radial, size, rgb, label, 0.03);
  }
}

// Forward-facing capture of a museum hall, as the NVOS scenes are taken (a 5 x 4 grid of
// nearly parallel cameras), built after everything else was tuned, as a check on objects
// nothing was tuned on: a skeleton of thin bones whose ribs show the far ribs and the wall
// through their gaps (NVOS's trex), a spike of orchids on a thin stem beside a second one,
// in front of a large-leaved plant (orchids), and a skull mounted on the wall with long horns reaching towards the cameras
// (horns).
EvalScene museum(const EvalSetOptions& opt) {
  SceneStart start("museum", 73);
  auto& [s, demo, g, rng, b] = start;
  const double d = opt.density, sz = 1 / std::sqrt(d);
  const double wall_y = 1.6;
  for (int i = 0, n = int(11000 * d); i < n; ++i) {  // plastered wall with a dado rail
    const Vec3 p{rng.range(-2.8, 2.8), wall_y, rng.range(0, 2.8)};
    const double z = p.z;
    const Vec3 c = z < 0.9 ? Vec3{0.42, 0.46, 0.50} : (z < 0.94 ? Vec3{0.85, 0.84, 0.80} : Vec3{0.80, 0.74, 0.62});
    b.splat(p, {0, -1, 0}, 0.05 * sz, c + Vec3{1, 1, 1} * (0.04 * cell_noise(int((p.x + 10) * 6), int(z * 6))), -1, 0.02);
  }
  for (int i = 0, n = int(8000 * d); i < n; ++i) {  // parquet floor
    const Vec3 p{rng.range(-2.8, 2.8), rng.range(-1.4, wall_y), 0};
    const int plank = int(std::floor((p.x + 10) / 0.12));
    b.splat(p, {0, 0, 1}, 0.05 * sz, Vec3{0.52, 0.36, 0.22} + Vec3{1, 0.8, 0.6} * (0.1 * cell_noise(plank, int(p.y * 2))), -1,
            0.04);
  }
  // The skeleton, 1 m before the wall: a spine along x, ribs around it, neck and skull, a
  // tail, four thin legs; ivory bones.
  const Vec3 bone{0.86, 0.82, 0.70};
  const double body_y = 0.6, spine_z = 1.15;
  const int skeleton = add_object(demo, "skeleton", {-0.55, body_y, 0.8}, 1.1f);
  tube(b, {-1.25, body_y, spine_z}, {0.05, body_y, spine_z + 0.05}, 0.035, 0.035, int(900 * d), 0.012 * sz, bone, skeleton);
  for (double x = -1.1; x <= -0.05; x += 0.09) {  // ribs: rings around the spine, open at the top
    const double r = 0.2 + 0.08 * std::sin((x + 1.1) / 1.05 * M_PI);
    for (int i = 0, n = int(160 * d) + 40; i < n; ++i) {
      const double a = rng.range(0.35, 2 * M_PI - 0.35);  // from the top around
      const Vec3 radial{0, std::sin(a), std::cos(a)};
      b.strip(Vec3{x, body_y, spine_z - r} + radial * r, radial, {0, std::cos(a), -std::sin(a)}, 0.03, 0.008, bone, skeleton,
              0.03);
    }
  }
  tube(b, {0.05, body_y, spine_z + 0.05}, {0.3, body_y, spine_z + 0.3}, 0.03, 0.025, int(250 * d), 0.012 * sz, bone, skeleton);
  for (int i = 0, n = int(700 * d); i < n; ++i) {  // skull: an elongated box
    const Vec3 u{rng.range(-1, 1), rng.range(-1, 1), rng.range(-1, 1)};
    const int face = int(rng.uniform() * 3);
    Vec3 p = u, nrm{0, 0, 0};
    if (face == 0) p.x = u.x < 0 ? -1 : 1, nrm = {p.x, 0, 0};
    else if (face == 1) p.y = u.y < 0 ? -1 : 1, nrm = {0, p.y, 0};
    else p.z = u.z < 0 ? -1 : 1, nrm = {0, 0, p.z};
    b.splat(Vec3{0.45, body_y, spine_z + 0.33} + Vec3{p.x * 0.16, p.y * 0.07, p.z * 0.07}, nrm, 0.014 * sz, bone, skeleton, 0.03);
  }
  tube(b, {-1.25, body_y, spine_z}, {-1.9, body_y, 0.55}, 0.03, 0.01, int(300 * d), 0.01 * sz, bone, skeleton);
  for (double lx : {-0.95, -0.1})
    for (double ly : {-0.12, 0.12})
      tube(b, {lx, body_y + ly, spine_z - 0.05}, {lx + 0.05, body_y + ly, 0.0}, 0.025, 0.018, int(260 * d), 0.01 * sz, bone,
           skeleton);
  // A low dark plinth under it (not part of it).
  for (int i = 0, n = int(1500 * d); i < n; ++i)
    b.splat({rng.range(-1.6, 0.4), rng.range(body_y - 0.35, body_y + 0.35), 0.02}, {0, 0, 1}, 0.04 * sz, {0.2, 0.2, 0.22}, -1,
            0.02);
  // A large-leaved plant against the wall, and orchids on thin arching stems before it.
  const Vec3 plant_c{0.95, 1.25, 0};
  cylinder(b, plant_c, 0.2, 0.24, 0.45, int(900 * d), 0.02 * sz, {0.55, 0.30, 0.20}, -1, true);
  for (int leaf = 0; leaf < 26; ++leaf) {
    const double a = rng.range(0, 2 * M_PI), tilt = rng.range(0.3, 1.1);
    const Vec3 dir{std::cos(a) * std::sin(tilt), std::sin(a) * std::sin(tilt) * 0.5, std::cos(tilt)};
    const Vec3 base = plant_c + Vec3{0, 0, 0.45};
    const Vec3 nrm = normalized(cross(dir, Vec3{-std::sin(a), std::cos(a), 0}));
    const Vec3 col{rng.range(0.08, 0.16), rng.range(0.30, 0.42), rng.range(0.10, 0.16)};
    for (double t = 0.15; t < 0.75; t += 0.012)
      b.strip(base + dir * t, nrm, dir, 0.03, 0.06 * std::sin((t - 0.1) / 0.65 * M_PI) + 0.02, col, -1, 0.06);
  }
  const Vec3 orchid_c{0.7, 0.55, 0.0};
  box(b, orchid_c + Vec3{0, 0, 0.35}, 0.16, 0.35, int(1400 * d), 0.02 * sz, {0.9, 0.9, 0.88}, {0.9, 0.9, 0.88}, -1);  // stand
  cylinder(b, orchid_c + Vec3{0, 0, 0.7}, 0.07, 0.09, 0.13, int(500 * d), 0.012 * sz, {0.25, 0.35, 0.55}, -1, true);  // pot
  const int orchid = add_object(demo, "orchid", orchid_c + Vec3{0.15, -0.1, 1.2}, 0.3f);
  Vec3 p_orchid_anchor;  // on the right spike's second flower
  for (int stem = 0; stem < 2; ++stem) {  // two spikes leaning apart: the right one is the target
    const int label = stem == 1 ? orchid : -1;
    const Vec3 lean{stem ? 0.14 : -0.14, -0.08, 0};
    const Vec3 root = orchid_c + Vec3{stem ? 0.015 : -0.015, 0, 0.83};
    Vec3 p = root;
    for (double t = 0; t < 1; t += 0.02) {  // the stem, 5 mm thick, arching over
      const Vec3 q = root + lean * (t * t * 2.2) + Vec3{0, 0, 0.55 * t};
      b.strip(q, {0, -1, 0}, normalized(q - p + Vec3{0, 0, 1e-6}), 0.02, 0.005, {0.30, 0.45, 0.18}, label, 0.02);
      p = q;
    }
    for (int flower = 0; flower < 4; ++flower) {  // flowers along the stem's end
      const Vec3 fc = p - lean * (0.25 * flower) - Vec3{0, 0, 0.07 * flower} + Vec3{0, -0.03, 0};
      if (stem == 1 && flower == 1) p_orchid_anchor = fc + Vec3{0, -0.01, 0};
      for (int petal = 0; petal < 5; ++petal) {
        const double pa = petal * 2 * M_PI / 5 + flower;
        const Vec3 dir{std::cos(pa), 0.15, std::sin(pa)};
        for (double t = 0.005; t < 0.04; t += 0.007)
          b.strip(fc + normalized(dir) * t, {0, -1, 0.1}, normalized(dir), 0.012, 0.016 * std::sin(t / 0.045 * M_PI) + 0.004,
                  petal % 2 ? Vec3{0.86, 0.55, 0.78} : Vec3{0.93, 0.70, 0.86}, label, 0.05);
      }
      b.splat(fc + Vec3{0, -0.005, 0}, {0, -1, 0}, 0.008, {0.95, 0.85, 0.3}, label, 0.03);
    }
  }
  // A skull mounted on the wall, high up, with long horns reaching towards the cameras.
  const Vec3 skull_c{-0.35, wall_y - 0.06, 2.05};
  SplitMix64 horn_rng(5);  // its own stream: the objects before it do not move it
  SceneBuilder hb{g, demo.labels, horn_rng, 3};
  const int horns = add_object(demo, "horns", skull_c + Vec3{0, -0.2, 0.05}, 0.6f);
  for (int i = 0, n = int(900 * d); i < n; ++i) {  // the skull: a half ellipsoid off the wall
    Vec3 u;
    do u = {horn_rng.range(-1, 1), horn_rng.range(-1, 0), horn_rng.range(-1, 1)};
    while (dot(u, u) > 1);
    const Vec3 nrm = normalized(u);
    hb.splat(skull_c + Vec3{nrm.x * 0.11, nrm.y * 0.07, nrm.z * 0.17}, nrm, 0.012 * sz, {0.80, 0.76, 0.66}, horns, 0.03);
  }
  for (double side : {-1.0, 1.0}) {  // each horn: segments curving out, forward and up
    Vec3 p = skull_c + Vec3{side * 0.09, -0.03, 0.1};
    for (int k = 0; k < 8; ++k) {
      const double t = (k + 1) / 8.0;
      const Vec3 q = skull_c + Vec3{side * (0.09 + 0.35 * t), -0.03 - 0.3 * t * t, 0.1 + 0.25 * t - 0.12 * t * t * t};
      tube(hb, p, q, 0.035 * (1 - 0.8 * (t - 0.125)), 0.035 * (1 - 0.8 * t), int(120 * d) + 20, 0.009 * sz,
           {0.30, 0.26, 0.20}, horns);
      p = q;
    }
  }
  // The capture: a 5 x 4 grid of cameras 3 m from the wall, all looking nearly straight ahead.
  forward_grid(demo, {-0.2, -1.4, 1.25}, {0.25, 0, 0.18}, {-0.2, wall_y, 1.2}, {0.08, 0, 0.05}, 66.0, opt);
  add_task(s, "skeleton", "thin bones with gaps in front of a wall (NVOS trex)", skeleton, {-0.6, body_y - 0.2, spine_z - 0.15},
           7);
  add_task(s, "orchid", "a flower spike on a thin stem beside another, before foliage", orchid, p_orchid_anchor, 12, 20);
  add_task(s, "horns", "mounted skull with long horns reaching out (NVOS horns)", horns, skull_c + Vec3{0, -0.07, 0}, 2);
  return std::move(s);
}

// A living room on a half orbit, built after the museum as a further check on objects
// nothing was tuned on: a bicycle leaning on the wall (a thin frame, two wheels of spokes
// that show the wall through them), a rug lying flat on the floor, a dark television on a
// low cabinet, and a vase of flowers on a coffee table.
EvalScene lounge(const EvalSetOptions& opt) {
  SceneStart start("lounge", 91);
  auto& [s, demo, g, rng, b] = start;
  const double d = opt.density, sz = 1 / std::sqrt(d);
  const double wall_y = 2.2;
  for (int i = 0, n = int(10000 * d); i < n; ++i) {  // painted wall with a skirting board
    const Vec3 p{rng.range(-3.4, 3.4), wall_y, rng.range(0, 2.8)};
    const Vec3 c = p.z < 0.1 ? Vec3{0.92, 0.92, 0.90} : Vec3{0.55, 0.63, 0.58} + Vec3{1, 1, 1} * (0.03 * cell_noise(int((p.x + 10) * 3), int(p.z * 3)));
    b.splat(p, {0, -1, 0}, 0.055 * sz, c, -1, 0.02);
  }
  for (int i = 0, n = int(9000 * d); i < n; ++i) {  // light oak floor
    const Vec3 p{rng.range(-3.4, 3.4), rng.range(-2.6, wall_y), 0};
    const int board = int(std::floor((p.x + 10) / 0.16));
    b.splat(p, {0, 0, 1}, 0.055 * sz, Vec3{0.70, 0.56, 0.40} + Vec3{1, 0.8, 0.6} * (0.08 * cell_noise(board, int(p.y))), -1, 0.04);
  }
  // A bicycle leaning on the wall, 6 cm from it: two spoked wheels and a thin frame.
  const double bike_y = wall_y - 0.08;
  const Vec3 rear{-1.9, bike_y, 0.34}, front{-0.85, bike_y, 0.34};
  const int bike = add_object(demo, "bicycle", {-1.37, bike_y, 0.5}, 0.8f);
  const Vec3 metal{0.75, 0.12, 0.10}, tyre{0.08, 0.08, 0.08}, spoke{0.7, 0.7, 0.72};
  for (const Vec3& hub : {rear, front}) {
    for (int i = 0; i < 160; ++i) {  // the tyre: a ring of strips
      const double a = 2 * M_PI * i / 160;
      const Vec3 r{std::cos(a), 0, std::sin(a)};
      b.strip(hub + r * 0.33, {0, -1, 0}, {-std::sin(a), 0, std::cos(a)}, 0.018, 0.03, tyre, bike, 0.03);
    }
    for (int k = 0; k < 16; ++k) {  // spokes, 3 mm
      const double a = 2 * M_PI * k / 16;
      const Vec3 r{std::cos(a), 0, std::sin(a)};
      for (double t = 0.03; t < 0.31; t += 0.02) b.strip(hub + r * t, {0, -1, 0}, r, 0.022, 0.003, spoke, bike, 0.08);
    }
  }
  const Vec3 crank{-1.4, bike_y, 0.36}, seat{-1.55, bike_y, 0.85}, head{-0.98, bike_y, 0.88};
  for (const auto& [a, c] : std::vector<std::pair<Vec3, Vec3>>{{rear, crank}, {rear, seat}, {crank, seat}, {crank, head},
                                                               {seat, head}, {head, front}, {seat, seat + Vec3{-0.03, 0, 0.1}},
                                                               {head, head + Vec3{0.04, 0, 0.12}}})
    tube(b, a, c, 0.016, 0.016, int(120 * d) + 30, 0.008 * sz, metal, bike);
  tube(b, seat + Vec3{-0.12, 0, 0.11}, seat + Vec3{0.08, 0, 0.11}, 0.035, 0.025, int(80 * d) + 20, 0.01 * sz, tyre, bike);
  tube(b, head + Vec3{0.04, -0.25, 0.12}, head + Vec3{0.04, 0.2, 0.12}, 0.012, 0.012, int(80 * d) + 20, 0.008 * sz, tyre, bike);
  // A rug lying flat on the floor, patterned, 1 cm thick.
  const Vec3 rug_c{0.4, 0.3, 0.01};
  const int rug = add_object(demo, "rug", rug_c, 1.0f);
  for (int i = 0, n = int(9000 * d); i < n; ++i) {
    const double x = rng.range(-0.9, 0.9), y = rng.range(-0.6, 0.6);
    const bool border = std::abs(x) > 0.8 || std::abs(y) > 0.5;
    const bool diamond = std::fmod(std::abs(x) + std::abs(y) + 10, 0.3) < 0.1;
    const Vec3 c = border ? Vec3{0.25, 0.12, 0.30} : (diamond ? Vec3{0.80, 0.62, 0.30} : Vec3{0.55, 0.18, 0.16});
    b.splat(rug_c + Vec3{x, y, 0}, {0, 0, 1}, 0.035 * sz, c, rug, 0.01);
  }
  // A low cabinet against the wall with a dark television standing on it.
  const Vec3 cab_c{1.55, wall_y - 0.25, 0};
  box(b, cab_c + Vec3{0, 0, 0.25}, 0.22, 0.25, int(1500 * d), 0.03 * sz, {0.90, 0.88, 0.84}, {0.7, 0.68, 0.64}, -1);
  box(b, cab_c + Vec3{0.44, 0, 0.25}, 0.22, 0.25, int(1500 * d), 0.03 * sz, {0.90, 0.88, 0.84}, {0.7, 0.68, 0.64}, -1);
  const Vec3 tv_c = cab_c + Vec3{0.22, 0.05, 0.5};
  const int tv = add_object(demo, "television", tv_c + Vec3{0, 0, 0.35}, 0.6f);
  for (int i = 0, n = int(2000 * d); i < n; ++i) {  // the screen: a thin dark slab, a glossy face
    const double x = rng.range(-0.5, 0.5), z = rng.range(0.08, 0.64);
    const int face = int(rng.uniform() * 6);
    if (face < 4) b.splat(tv_c + Vec3{x, -0.03, z}, {0, -1, 0}, 0.02 * sz, {0.05, 0.05, 0.07}, tv, 0.3);
    else if (face == 4) b.splat(tv_c + Vec3{x, 0.0, z}, {0, 1, 0}, 0.025 * sz, {0.12, 0.12, 0.12}, tv, 0.02);
    else b.splat(tv_c + Vec3{x < 0 ? -0.5 : 0.5, rng.range(-0.03, 0.0), z}, {x < 0 ? -1.0 : 1.0, 0, 0}, 0.01 * sz, {0.1, 0.1, 0.1}, tv, 0.02);
  }
  tube(b, tv_c + Vec3{0, 0, 0.0}, tv_c + Vec3{0, 0, 0.1}, 0.03, 0.03, 80, 0.01 * sz, {0.1, 0.1, 0.1}, tv);
  for (int i = 0; i < 200; ++i)  // its foot
    b.splat(tv_c + Vec3{rng.range(-0.15, 0.15), rng.range(-0.08, 0.08), 0.005}, {0, 0, 1}, 0.015 * sz, {0.1, 0.1, 0.1}, tv, 0.02);
  // A coffee table on the rug with a vase of flowers on it.
  const Vec3 table_c{0.4, 0.2, 0};
  for (int i = 0, n = int(1800 * d); i < n; ++i)
    b.splat(table_c + Vec3{rng.range(-0.45, 0.45), rng.range(-0.28, 0.28), 0.42}, {0, 0, 1}, 0.03 * sz, {0.30, 0.20, 0.12}, -1, 0.05);
  for (double lx : {-0.4, 0.4})
    for (double ly : {-0.23, 0.23})
      cylinder(b, table_c + Vec3{lx, ly, 0}, 0.02, 0.02, 0.42, int(100 * d) + 30, 0.012 * sz, {0.25, 0.17, 0.1}, -1, false);
  const Vec3 vase_c = table_c + Vec3{0.15, 0.0, 0.42};
  const int vase = add_object(demo, "vase", vase_c + Vec3{0, 0, 0.2}, 0.25f);
  cylinder(b, vase_c, 0.05, 0.07, 0.2, int(600 * d) + 100, 0.01 * sz, {0.20, 0.35, 0.65}, vase, false, 0.05);
  for (int f = 0; f < 7; ++f) {  // stems and flower heads above it
    const double a = f * 0.9, lean = 0.06 + 0.02 * (f % 3);
    const Vec3 top = vase_c + Vec3{lean * std::cos(a), lean * std::sin(a), 0.38 + 0.03 * (f % 2)};
    tube(b, vase_c + Vec3{0, 0, 0.18}, top, 0.004, 0.004, 40, 0.004, {0.3, 0.5, 0.2}, vase);
    for (int k = 0; k < 60; ++k) {
      Vec3 u{rng.normal(), rng.normal(), rng.normal()};
      u = normalized(u);
      b.splat(top + u * 0.025, u, 0.012, f % 2 ? Vec3{0.95, 0.85, 0.2} : Vec3{0.95, 0.95, 0.92}, vase, 0.03);
    }
  }
  // The capture: a half orbit at two heights around the room's middle.
  const Vec3 target{0.0, 0.9, 0.5};
  int id = 0;
  for (int row = 0; row < 2; ++row)
    for (int k = 0; k < 11; ++k) {
      const double a = (-70 + 140.0 * k / 10) * M_PI / 180;
      const Vec3 eye{target.x + 3.6 * std::sin(a), target.y - 3.6 * std::cos(a), row ? 1.9 : 1.2};
      demo.bundle.cameras.push_back(named(Camera::look_at(eye, target, {0, 0, 1}, opt.width, opt.height, 64.0), id++, "orbit"));
    }
  add_task(s, "bicycle", "a thin frame and spoked wheels leaning on a wall", bike, crank + Vec3{0.12, -0.03, 0.2}, 5);
  add_task(s, "rug", "a flat rug lying on the floor, partly under a table", rug, rug_c + Vec3{-0.6, -0.3, 0.0}, 16);
  add_task(s, "television", "a dark screen on a cabinet against the wall", tv, tv_c + Vec3{0, -0.04, 0.35}, 8);
  add_task(s, "vase", "a vase of flowers on a table", vase, vase_c + Vec3{0, -0.07, 0.1}, 13);
  return std::move(s);
}

// A front porch filmed forward-facing by hand (a 5 x 4 grid of nearly parallel cameras,
// each a little off the grid and off its aim), built after every other scene's additions
// were tuned and reported as its first run, as a check of how they generalise to surfaces
// as a trainer leaves them: the wall's and floor's Gaussians lie up to 1.5 cm off the
// surface, vary in size, thickness and tilt, and semi-transparent floaters hang in the
// air. A boxwood shrub 12 cm in front of the rendered wall, a watering can partly hidden
// behind a storage box of the same grey, a porch post in the wall's colour that leaves the
// frame, a potted geranium clicked on its pot (the truth: pot, saucer and plant), and a
// clock whose face is the wall's colour 3.5 cm off the wall.
EvalScene porch(const EvalSetOptions& opt) {
  SceneStart start("porch", 103);
  auto& [s, demo, g, rng, b] = start;
  const double d = opt.density, sz = 1 / std::sqrt(d);
  const double wall_y = 2.3;
  const Vec3 render_rgb{0.84, 0.80, 0.70};
  b.depth_jitter = 0.006;  // large plain surfaces: the loosest
  b.shape_jitter = 0.35;
  for (int i = 0, n = int(10000 * d); i < n; ++i) {  // rendered wall: blotchy, fine grain
    const Vec3 p{rng.range(-2.6, 2.8), wall_y, rng.range(0, 2.9)};
    if (p.x > 0.25 && p.x < 1.1 && p.z < 2.1) continue;  // the door's opening
    const double blotch = 0.05 * cell_noise(int(std::floor((p.x + 10) / 0.5)), int(std::floor(p.z / 0.5)));
    b.splat(p, {0, -1, 0}, 0.05 * sz, render_rgb + Vec3{1, 1, 1} * (blotch + 0.03 * rng.normal()), -1, 0.02);
  }
  b.depth_jitter = 0.004;
  for (int i = 0, n = int(7000 * d); i < n; ++i) {  // stone paving, 45 cm slabs
    const Vec3 p{rng.range(-2.6, 2.8), rng.range(-1.6, wall_y), 0};
    const bool joint = std::fmod(p.x + 10, 0.45) < 0.015 || std::fmod(p.y + 10, 0.45) < 0.015;
    const Vec3 c = joint ? Vec3{0.36, 0.34, 0.31}
                         : Vec3{0.62, 0.58, 0.52} + Vec3{1, 1, 1} * (0.08 * cell_noise(int((p.x + 10) / 0.45), int((p.y + 10) / 0.45)));
    b.splat(p, {0, 0, 1}, 0.05 * sz, c, -1, 0.02);
  }
  b.depth_jitter = 0.003;
  b.shape_jitter = 0.15;
  for (int i = 0, n = int(2500 * d); i < n; ++i) {  // a dark green panelled door in its opening, white frame
    const double x = rng.range(0.25, 1.1), z = rng.range(0, 2.1);
    const bool frame = x < 0.3 || x > 1.05 || z > 2.05;
    const bool groove = std::abs(std::fmod(z, 0.5) - 0.25) < 0.012 || std::abs(x - 0.675) < 0.012;
    const Vec3 c = frame ? Vec3{0.92, 0.91, 0.88} : (groove ? Vec3{0.10, 0.20, 0.16} : Vec3{0.16, 0.30, 0.24});
    b.splat({x, wall_y - 0.015, z}, {0, -1, 0}, 0.03 * sz, c, -1, 0.05);
  }
  // The shrub: small leaves in an ellipsoid whose back is 12 cm from the wall, a short trunk.
  b.depth_jitter = 0.004;
  b.shape_jitter = 0.3;
  const Vec3 shrub_c{-1.05, wall_y - 0.12 - 0.3, 0.62};
  const int shrub = add_object(demo, "shrub", shrub_c, 0.6f);
  leaves(b, shrub_c, {{0.45, 0.3, 0.45}, false, 0.5, 0.028, 0.024, 0.018, {0.10, 0.30, 0.08}, {0.22, 0.48, 0.16}},
         int(150 * std::max(1.0, d)), shrub);
  for (int i = 0; i < 40; ++i) {  // the trunk, up from the paving
    const double t = i / 39.0;
    b.strip(Vec3{shrub_c.x, shrub_c.y + 0.05, 0.0} * (1 - t) + (shrub_c - Vec3{0, 0, 0.25}) * t, {0, -1, 0}, {0, 0, 1}, 0.02,
            0.02, {0.32, 0.24, 0.15}, shrub, 0.02);
  }
  // A storage box of weathered grey boards, a galvanised watering can behind it, to its left.
  b.depth_jitter = 0.002;
  b.shape_jitter = 0.2;
  const Vec3 grey{0.55, 0.56, 0.55};
  box(b, {0.65, 1.2, 0.26}, 0.3, 0.26, int(3500 * d), 0.03 * sz, grey * 0.95, grey * 0.7, -1);
  const Vec3 can_c{0.3, 1.78, 0};
  const int can = add_object(demo, "watering_can", can_c + Vec3{-0.05, 0, 0.2}, 0.35f);
  cylinder(b, can_c, 0.12, 0.11, 0.32, int(1600 * d), 0.016 * sz, grey, can, true, 0.16);
  tube(b, can_c + Vec3{-0.09, 0, 0.06}, can_c + Vec3{-0.34, 0, 0.38}, 0.018, 0.01, int(200 * d) + 40, 0.008 * sz, grey, can);
  for (int i = 0; i < 60; ++i) {  // the rose at the spout's end
    const double a = rng.range(0, 2 * M_PI), r = 0.03 * std::sqrt(rng.uniform());
    const Vec3 nrm = normalized(Vec3{-0.8, 0, 0.6});
    const Vec3 side{0, 1, 0}, up = cross(nrm, side);
    b.splat(can_c + Vec3{-0.35, 0, 0.39} + side * (r * std::cos(a)) + up * (r * std::sin(a)), nrm, 0.008, grey * 0.85, can, 0.05);
  }
  for (int i = 0; i < 50; ++i) {  // the handle arching over the top
    const double a = M_PI * i / 49;
    const Vec3 p = can_c + Vec3{0.02 + 0.08 * std::cos(a), 0, 0.32 + 0.11 * std::sin(a)};
    b.strip(p, {0, -1, 0}, {-std::sin(a), 0, std::cos(a)}, 0.014, 0.014, grey, can, 0.05);
  }
  // A porch post, 9 cm square and off-white like the wall, up past the top of every view.
  const Vec3 post_c{1.3, 0.7, 0};
  const int post = add_object(demo, "post", post_c + Vec3{0, 0, 1.3}, 1.6f);
  for (int i = 0, n = int(2400 * d); i < n; ++i) {
    const int face = int(rng.uniform() * 4);
    const double u = rng.range(-0.045, 0.045), z = rng.range(0, 3.2);
    const Vec3 nrm = face == 0 ? Vec3{0, -1, 0} : face == 1 ? Vec3{1, 0, 0} : face == 2 ? Vec3{-1, 0, 0} : Vec3{0, 1, 0};
    const Vec3 tangent{std::abs(nrm.y), std::abs(nrm.x), 0};
    b.splat(post_c + nrm * 0.045 + tangent * u + Vec3{0, 0, z}, nrm, 0.02 * sz, Vec3{0.90, 0.88, 0.80}, post, 0.02);
  }
  // A potted geranium: a terracotta pot on a saucer, leaves and red flower heads.
  const Vec3 pot_c{-0.35, 1.7, 0.03};
  const int geranium = add_object(demo, "geranium", pot_c + Vec3{0, 0, 0.3}, 0.35f);
  const Vec3 terracotta{0.70, 0.38, 0.24};
  cylinder(b, pot_c - Vec3{0, 0, 0.03}, 0.16, 0.16, 0.03, int(400 * d), 0.015 * sz, terracotta * 0.9, geranium, true);
  cylinder(b, pot_c, 0.11, 0.14, 0.24, int(1300 * d), 0.016 * sz, terracotta, geranium, false, 0.2);
  for (int i = 0, n = int(200 * d); i < n; ++i) {  // the soil inside the rim
    const double r = 0.13 * std::sqrt(rng.uniform()), a = rng.range(0, 2 * M_PI);
    b.splat(pot_c + Vec3{r * std::cos(a), r * std::sin(a), 0.22}, {0, 0, 1}, 0.015 * sz, {0.22, 0.16, 0.11}, geranium, 0.01);
  }
  for (int leaf = 0, n = int(70 * std::max(1.0, d)); leaf < n; ++leaf) {  // round leaves
    Vec3 u;
    do u = {rng.range(-1, 1), rng.range(-1, 1), rng.range(-1, 1)};
    while (dot(u, u) > 1);
    const Vec3 c = pot_c + Vec3{u.x * 0.22, u.y * 0.18, 0.4 + u.z * 0.15};
    const Vec3 nrm = normalized(Vec3{rng.normal() * 0.5, -0.7, 0.7 + rng.normal() * 0.3});
    const Vec3 col{rng.range(0.15, 0.25), rng.range(0.40, 0.55), rng.range(0.12, 0.20)};
    for (int k = 0; k < 4; ++k)
      b.splat(c + Vec3{rng.range(-0.02, 0.02), rng.range(-0.02, 0.02), rng.range(-0.02, 0.02)}, nrm, 0.022, col, geranium, 0.03);
  }
  for (int f = 0; f < 6; ++f) {  // flower heads on stalks
    const double a = f * 1.05 + 0.3, r = 0.05 + 0.04 * (f % 3);
    const Vec3 top = pot_c + Vec3{r * std::cos(a), 0.7 * r * std::sin(a), 0.6 + 0.04 * (f % 2)};
    tube(b, pot_c + Vec3{0, 0, 0.3}, top, 0.004, 0.004, 40, 0.004, {0.3, 0.45, 0.2}, geranium);
    for (int k = 0; k < 70; ++k) {
      const Vec3 u = normalized(Vec3{rng.normal(), rng.normal(), rng.normal() + 1e-9});
      b.splat(top + u * 0.035, u, 0.012, Vec3{0.82, 0.12, 0.14} * rng.range(0.85, 1.1), geranium, 0.03);
    }
  }
  // A clock on the wall: its face the wall's cream, 3.5 cm off the wall, a dark rim and hands.
  b.depth_jitter = 0.0015;
  b.shape_jitter = 0.2;
  const Vec3 clock_c{-0.45, wall_y - 0.035, 1.6};
  const int clock = add_object(demo, "clock", clock_c, 0.2f);
  for (int i = 0, n = int(900 * d); i < n; ++i) {  // the face and its hour marks
    const double r = 0.15 * std::sqrt(rng.uniform()), a = rng.range(0, 2 * M_PI);
    const double hour = std::fmod(a + 2 * M_PI + M_PI / 12, M_PI / 6);
    const bool mark = r > 0.12 && r < 0.14 && hour < 0.05;
    b.splat(clock_c + Vec3{r * std::cos(a), 0, r * std::sin(a)}, {0, -1, 0}, 0.01 * sz,
            mark ? Vec3{0.12, 0.12, 0.12} : Vec3{0.86, 0.82, 0.72}, clock, 0.03);
  }
  for (int i = 0; i < 200; ++i) {  // the rim, and the body's side back to the wall
    const double a = 2 * M_PI * i / 200;
    const Vec3 r{std::cos(a), 0, std::sin(a)};
    b.strip(clock_c + r * 0.16 - Vec3{0, 0.002, 0}, {0, -1, 0}, {-std::sin(a), 0, std::cos(a)}, 0.01, 0.02, {0.2, 0.2, 0.22}, clock,
            0.05);
    b.strip(clock_c + r * 0.17 + Vec3{0, 0.017, 0}, r, {0, 1, 0}, 0.02, 0.008, {0.2, 0.2, 0.22}, clock, 0.05);
  }
  for (const auto& [a, len] : std::vector<std::pair<double, double>>{{1.2, 0.08}, {0.3, 0.12}})  // hands
    for (double t = 0; t < len; t += 0.008)
      b.strip(clock_c + Vec3{t * std::cos(a), -0.003, t * std::sin(a)}, {0, -1, 0}, {std::cos(a), 0, std::sin(a)}, 0.01, 0.008,
              {0.1, 0.1, 0.1}, clock, 0.03);
  // Floaters: faint blobs in the air, more of them near the foliage, where views disagree.
  b.depth_jitter = 0;
  b.shape_jitter = 0;
  for (int i = 0, n = int(160 * d); i < n; ++i) {
    const bool near_shrub = i % 4 == 0;
    Vec3 p{rng.range(-1.8, 2.2), rng.range(-0.3, 2.1), rng.range(0.1, 2.5)};
    if (near_shrub) {  // in the air around the shrub, outside its leaves' ellipsoid, not behind it
      Vec3 u;
      do u = {rng.range(-1.6, 1.6), rng.range(-1.8, 0.3), rng.range(-1.3, 1.6)};
      while (dot(u, u) < 1.15 * 1.15 || dot(u, u) > 1.8 * 1.8);
      p = shrub_c + Vec3{u.x * 0.45, u.y * 0.3, u.z * 0.45};
    }
    const Vec3 c = near_shrub ? Vec3{0.25, 0.38, 0.18} : render_rgb * rng.range(0.6, 1.05);
    b.floater(p, rng.range(0.02, 0.07) * sz, c, rng.range(0.05, 0.3));
  }
  // The capture: a 5 x 4 grid 4 m from the wall, held by hand.
  const HandHeld hand{9, 0.03, 0.06};
  forward_grid(demo, {0.25, -1.7, 1.15}, {0.2, 0, 0.15}, {0.25, wall_y, 0.8}, {0.07, 0, 0.05}, 62.0, opt, &hand);
  add_task(s, "shrub", "shrub with gaps 12 cm in front of a noisy wall", shrub, shrub_c + Vec3{0.05, -0.3, 0.05}, 7);
  add_task(s, "watering_can", "object partly behind an occluder of the same grey", can, can_c + Vec3{-0.1, -0.06, 0.2}, 12);
  add_task(s, "post", "part of a thin post leaving the frame, the wall's colour behind it", post, post_c + Vec3{0, -0.046, 1.5}, 9);
  add_task(s, "geranium", "compound object: a potted plant clicked on its pot", geranium, pot_c + Vec3{0, -0.135, 0.12}, 6);
  add_task(s, "clock", "object 3.5 cm off a noisy wall, its face the wall's colour", clock, clock_c + Vec3{0.07, -0.002, -0.07}, 2);
  return std::move(s);
}

// Gives the last Gaussian added a mirror-like gloss: for each light (its direction, the
// colour it adds) the colour changes with how the view direction d, mirrored about the
// normal n, meets the light: lin * (r.L) + quad * ((r.L)^2 - 1/3), where r.L = d.m with
// m = L - 2 (n.L) n. Both are exact in degree-1 and degree-2 SH (the quadratic term has
// no constant part, so the colour averaged over all directions stays the base colour).
void gloss(GaussianScene& g, const Vec3& n, const std::vector<std::pair<Vec3, Vec3>>& lights, double lin, double quad) {
  float* sh = g.sh.data() + g.sh.size() - 3 * sh_coeff_count(g.sh_degree);
  for (const auto& [to_light, rgb] : lights) {
    const Vec3 L = normalized(to_light), m = L - n * (2 * dot(n, L));
    const double band1[3] = {-m.y / kShC1, m.z / kShC1, -m.x / kShC1};
    const double band2[5] = {2 * m.x * m.y / kShC2[0], 2 * m.y * m.z / kShC2[1], 0.5 * (m.z * m.z - 1.0 / 3) / kShC2[2],
                             2 * m.x * m.z / kShC2[3], 0.5 * (m.x * m.x - m.y * m.y) / kShC2[4]};
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < 3; ++k) sh[3 * (1 + k) + c] += float(band1[k] * lin * rgb[c]);
      for (int k = 0; k < 5; ++k) sh[3 * (4 + k) + c] += float(band2[k] * quad * rgb[c]);
    }
  }
}

// A full 360-degree orbit (as the Mip-NeRF 360 scenes are taken: 28 cameras around the
// middle at two heights, each a little off its ring and its aim) around a cluttered
// workbench in a workshop, built after every other scene's additions were tuned and
// reported as its first run. Every surface is left as a trainer leaves a real capture
// (off the surface by a few mm, uneven sizes and tilts, floaters; the room's walls and
// floor of coarse Gaussians). The bench itself, filmed close, runs past the image's
// borders; the middle one of three identical mugs touching in a row; a helmet of
// pearlescent paint whose colour changes with the view; a bottle standing behind a
// toolbox (half the orbit sees only its top); a wooden rule lying flat on the bench.
EvalScene workshop(const EvalSetOptions& opt) {
  SceneStart start("workshop", 127);
  auto& [s, demo, g, rng, b] = start;
  const double d = opt.density, sz = 1 / std::sqrt(d);
  const double half = 2.6, wall_h = 2.5;
  // The room: painted block walls and a concrete floor of coarse, loose Gaussians.
  b.size_scale = 1.7;
  b.depth_jitter = 0.006;
  b.shape_jitter = 0.35;
  for (int wall = 0; wall < 4; ++wall) {
    const Vec3 nrm = wall == 0 ? Vec3{0, -1, 0} : wall == 1 ? Vec3{0, 1, 0} : wall == 2 ? Vec3{-1, 0, 0} : Vec3{1, 0, 0};
    for (int i = 0, n = int(2800 * d); i < n; ++i) {
      const double u = rng.range(-half, half), z = rng.range(0, wall_h);
      const Vec3 p = nrm * -half + Vec3{std::abs(nrm.y) * u, std::abs(nrm.x) * u, z};
      const bool joint = std::fmod(z, 0.2) < 0.012 || std::fmod(u + 10 + (int(z / 0.2) & 1) * 0.2, 0.4) < 0.012;
      Vec3 c = Vec3{0.80, 0.80, 0.76} + Vec3{1, 1, 1} * (0.04 * cell_noise(int((u + 10) / 0.4), int(z / 0.2) + 7 * wall));
      if (joint) c = c * 0.85;
      if (wall == 0 && std::abs(u) < 0.9 && z > 0.95 && z < 1.95)  // a pegboard behind the bench
        c = std::fmod(u + 10, 0.05) < 0.012 && std::fmod(z, 0.05) < 0.012 ? Vec3{0.25, 0.18, 0.12} : Vec3{0.62, 0.47, 0.32};
      if (wall == 3 && u > -0.8 && u < 0.6 && z > 1.0 && z < 2.1)  // a window: a bright sky, a white frame
        c = u < -0.75 || u > 0.55 || z < 1.05 || z > 2.05 || std::abs(u + 0.1) < 0.025 ? Vec3{0.93, 0.93, 0.92}
                                                                                      : Vec3{0.78, 0.86, 0.95};
      if (wall == 2 && u > -0.4 && u < 0.5 && z < 2.05)  // a dark wooden door
        c = u < -0.35 || u > 0.45 || z > 2.0 ? Vec3{0.90, 0.90, 0.88} : Vec3{0.36, 0.24, 0.16};
      b.splat(p, nrm, 0.055 * sz, c, -1, 0.02);
    }
  }
  for (int i = 0, n = int(5500 * d); i < n; ++i) {  // concrete floor with stains
    const Vec3 p{rng.range(-half, half), rng.range(-half, half), 0};
    const double stain = 0.06 * cell_noise(int((p.x + 10) / 0.6), int((p.y + 10) / 0.6));
    b.splat(p, {0, 0, 1}, 0.055 * sz, Vec3{0.52, 0.51, 0.49} + Vec3{1, 1, 1} * stain, -1, 0.02);
  }
  b.size_scale = 1.0;
  // The workbench: a beech block top 1.6 x 0.76 m, 5 cm thick, at 0.9 m; four pine legs,
  // 7 cm square; a shelf 16 cm above the floor between them; a cabinet of three drawers
  // on the shelf under the right half. The truth is all of it.
  b.depth_jitter = 0.002;
  b.shape_jitter = 0.2;
  const double top = 0.9, hx = 0.8, hy = 0.38, leg_x = 0.71, leg_y = 0.29;
  const int bench = add_object(demo, "workbench", {0, 0, 0.5}, 0.95f);
  const Vec3 beech{0.74, 0.57, 0.38}, pine{0.58, 0.43, 0.28};
  // Where the rule lies (below): no top under it, as a trainer leaves none where nothing
  // shows, and round it eight times as many, smaller ones held closer to the surface, as a
  // trainer sharpens an edge that shows (else the top's loose splats cover the 4 mm rule).
  const Vec3 rule_c{-0.08, 0.2, top + 0.004}, rule_dir = normalized(Vec3{1, 0.36, 0}), rule_side{-rule_dir.y, rule_dir.x, 0};
  for (int i = 0, n = int(8000 * d); i < n; ++i) {  // the top face, strips of beech along x
    const Vec3 p{rng.range(-hx, hx), rng.range(-hy, hy), top};
    const double along = std::abs(dot(p - rule_c, rule_dir)), across = std::abs(dot(p - rule_c, rule_side));
    if (along < 0.145 && across < 0.012) continue;
    const int strip = int(std::floor((p.y + 10) / 0.045));
    const Vec3 c = beech + Vec3{1, 0.8, 0.6} * (0.10 * cell_noise(strip, int((p.x + 10) / 0.5)));
    if (along < 0.19 && across < 0.055) {
      b.depth_jitter = 0.0006;
      for (int k = 0; k < 8; ++k) {
        const Vec3 q = p + Vec3{rng.range(-0.007, 0.007), rng.range(-0.007, 0.007), 0};
        if (std::abs(dot(q - rule_c, rule_dir)) < 0.145 && std::abs(dot(q - rule_c, rule_side)) < 0.014) continue;
        b.splat(q, {0, 0, 1}, 0.005 * sz, c, bench, 0.04);
      }
      b.depth_jitter = 0.002;
      continue;
    }
    b.splat(p, {0, 0, 1}, 0.014 * sz, c, bench, 0.04);
  }
  for (int i = 0, n = int(2000 * d); i < n; ++i) {  // the top's four edges, end grain darker
    const int side = int(rng.uniform() * 4);
    const double z = rng.range(top - 0.05, top);
    Vec3 p, nrm;
    if (side < 2) { p = {rng.range(-hx, hx), side ? hy : -hy, z}; nrm = {0, side ? 1.0 : -1.0, 0}; }
    else { p = {side == 3 ? hx : -hx, rng.range(-hy, hy), z}; nrm = {side == 3 ? 1.0 : -1.0, 0, 0}; }
    b.splat(p, nrm, 0.009 * sz, side < 2 ? beech * 0.95 : beech * 0.8, bench, 0.03);
  }
  for (double lx : {-leg_x, leg_x})
    for (double ly : {-leg_y, leg_y})
      for (int i = 0, n = int(2000 * d); i < n; ++i) {  // the legs
        const int face = int(rng.uniform() * 4);
        const double u = rng.range(-0.035, 0.035), z = rng.range(0, top - 0.05);
        const Vec3 nrm = face == 0 ? Vec3{0, -1, 0} : face == 1 ? Vec3{1, 0, 0} : face == 2 ? Vec3{-1, 0, 0} : Vec3{0, 1, 0};
        const Vec3 tangent{std::abs(nrm.y), std::abs(nrm.x), 0};
        b.splat(Vec3{lx, ly, z} + nrm * 0.035 + tangent * u, nrm, 0.011 * sz, pine, bench, 0.03);
      }
  for (int i = 0, n = int(3500 * d); i < n; ++i) {  // the shelf: its top and its front and back edges
    const bool edge = rng.uniform() < 0.15;
    const double x = rng.range(-leg_x + 0.035, leg_x - 0.035);
    if (edge) {
      const double side = rng.uniform() < 0.5 ? -1 : 1;
      b.splat({x, side * 0.3, rng.range(0.16, 0.185)}, {0, side, 0}, 0.01 * sz, pine * 0.85, bench, 0.03);
    } else {
      b.splat({x, rng.range(-0.3, 0.3), 0.185}, {0, 0, 1}, 0.018 * sz, pine * 1.05, bench, 0.03);
    }
  }
  const double cab_x0 = 0.12, cab_x1 = leg_x - 0.035, cab_z0 = 0.185, cab_z1 = top - 0.05;
  for (int i = 0, n = int(8000 * d); i < n; ++i) {  // the cabinet: drawer fronts, back, sides
    const int face = int(rng.uniform() * 4);
    const double z = rng.range(cab_z0, cab_z1);
    Vec3 p, nrm;
    Vec3 c = pine * 0.95;
    if (face < 2) {
      p = {rng.range(cab_x0, cab_x1), face ? 0.3 : -0.3, z};
      nrm = {0, face ? 1.0 : -1.0, 0};
      const double dz = std::fmod(z - cab_z0, (cab_z1 - cab_z0) / 3);
      if (!face && (dz < 0.008 || p.x < cab_x0 + 0.008 || p.x > cab_x1 - 0.008)) c = pine * 0.5;  // the gaps round the drawers
      else if (!face) c = Vec3{0.64, 0.49, 0.32};
      if (!face && std::abs(dz - 0.17) < 0.01 && std::abs(p.x - 0.5 * (cab_x0 + cab_x1)) < 0.06) c = {0.15, 0.15, 0.16};  // a pull
    } else {
      p = {face == 2 ? cab_x0 : cab_x1, rng.range(-0.3, 0.3), z};
      nrm = {face == 2 ? -1.0 : 1.0, 0, 0};
    }
    b.splat(p, nrm, 0.016 * sz, c, bench, 0.03);
  }
  // On the shelf, a cardboard box (scenery).
  box(b, {-0.32, 0.0, 0.185 + 0.07}, 0.16, 0.07, int(1200 * d), 0.018 * sz, {0.66, 0.50, 0.32}, {0.55, 0.42, 0.26}, -1);
  // Three identical glazed mugs touching in a row along x, handles to the front.
  b.depth_jitter = 0.0015;
  b.shape_jitter = 0.2;
  const double mug_r = 0.041, mug_h = 0.095;
  const Vec3 glaze{0.16, 0.42, 0.48};
  int mugs[3];
  for (int m = 0; m < 3; ++m) {
    const Vec3 c{-0.52 + 2 * mug_r * m, -0.12, top};
    mugs[m] = add_object(demo, m == 0 ? "mug_left" : m == 1 ? "mug" : "mug_right", c + Vec3{0, 0, 0.05}, 0.08f);
    for (int i = 0, n = int(1500 * d); i < n; ++i) {
      const double a = rng.range(0, 2 * M_PI), t = rng.uniform();
      const Vec3 radial{std::cos(a), std::sin(a), 0};
      if (t < 0.6) {  // the outside, shaded by the window's light (-x), darker where two mugs touch
        const bool crease = (m > 0 && radial.x < -0.96) || (m < 2 && radial.x > 0.96);
        const double shade = (0.6 + 0.4 * std::max(0.0, dot(radial, normalized(Vec3{-0.8, -0.6, 0})))) * (crease ? 0.6 : 1.0);
        b.splat(c + radial * mug_r + Vec3{0, 0, rng.range(0, mug_h)}, radial, 0.005 * sz, glaze * shade, mugs[m], 0.06);
      } else if (t < 0.85)  // the inside
        b.splat(c + radial * (mug_r - 0.004) + Vec3{0, 0, rng.range(0.008, mug_h)}, -radial, 0.005 * sz, glaze * 1.1, mugs[m], 0.06);
      else if (t < 0.92)  // the rim
        b.splat(c + radial * (mug_r - 0.002) + Vec3{0, 0, mug_h}, {0, 0, 1}, 0.004, glaze * 1.2, mugs[m], 0.06);
      else  // the bottom inside
        b.splat(c + radial * ((mug_r - 0.004) * std::sqrt(rng.uniform())) + Vec3{0, 0, 0.008}, {0, 0, 1}, 0.005 * sz, glaze * 0.9,
                mugs[m], 0.04);
    }
    const Vec3 hc = c + Vec3{0, -(mug_r + 0.005), 0.05}, e1{0, -1, 0}, e2{0, 0, 1}, ex{1, 0, 0};
    for (int i = 0; i < 300; ++i) {  // the handle: part of a torus standing out in front
      const double u = rng.range(-0.53 * M_PI, 0.53 * M_PI), v = rng.range(0, 2 * M_PI);
      const Vec3 ring = e1 * std::cos(u) + e2 * std::sin(u), nrm = ring * std::cos(v) + ex * std::sin(v);
      b.splat(hc + ring * 0.028 + nrm * 0.006, nrm, 0.004, glaze, mugs[m], 0.06);
    }
  }
  // A bicycle helmet (a dome 28 x 21 x 14 cm) of pearlescent paint: mirror-like lobes of a
  // warm window light and a cool lamp make it gold from one side, teal-blue from the other.
  b.depth_jitter = 0.002;
  const Vec3 helmet_c{0.02, -0.1, top};
  const Vec3 helmet_r{0.14, 0.105, 0.14};
  const int helmet = add_object(demo, "helmet", helmet_c + Vec3{0, 0, 0.07}, 0.16f);
  const std::vector<std::pair<Vec3, Vec3>> lights = {{{-1, 0.1, 0.35}, {0.40, 0.34, 0.02}}, {{0.7, 0.7, 0.4}, {-0.12, 0.22, 0.34}}};
  for (int i = 0, n = int(4500 * d); i < n; ++i) {
    Vec3 u;
    do u = {rng.normal(), rng.normal(), std::abs(rng.normal())};
    while (norm(u) < 1e-6);
    u = normalized(u);
    const Vec3 nrm = normalized(Vec3{u.x / helmet_r.x, u.y / helmet_r.y, u.z / helmet_r.z});
    const Vec3 p = helmet_c + Vec3{u.x * helmet_r.x, u.y * helmet_r.y, u.z * helmet_r.z};
    const bool vent = u.z > 0.35 && std::abs(std::fmod(std::atan2(u.y, u.x) + 2 * M_PI, M_PI / 3) - M_PI / 6) < 0.08;
    if (u.z < 0.12 || vent) {  // the black rim and vents: matte
      b.splat(p, nrm, 0.006 * sz, {0.06, 0.06, 0.07}, helmet, 0.02);
      continue;
    }
    b.splat(p, nrm, 0.007 * sz, {0.44, 0.32, 0.52}, helmet, 0.04);
    gloss(g, nrm, lights, 1.0, 0.7);
  }
  // A red steel toolbox (40 x 19 x 17 cm, a handle on top) and, 3.5 cm behind it, a
  // green bottle 32 cm tall: the front half of the orbit sees only its shoulder and neck.
  b.depth_jitter = 0.002;
  const Vec3 tb_c{0.42, 0.085, top}, tb_h{0.20, 0.095, 0.17};
  const int toolbox = add_object(demo, "toolbox", tb_c + Vec3{0, 0, 0.09}, 0.25f);
  const Vec3 red{0.72, 0.10, 0.08};
  for (int i = 0, n = int(4500 * d); i < n; ++i) {
    const int face = int(rng.uniform() * 6);
    Vec3 p, nrm;
    const double z = rng.range(0, tb_h.z);
    switch (face) {
      case 0: case 1: p = {rng.range(-tb_h.x, tb_h.x), face ? tb_h.y : -tb_h.y, z}; nrm = {0, face ? 1.0 : -1.0, 0}; break;
      case 2: p = {tb_h.x, rng.range(-tb_h.y, tb_h.y), z}; nrm = {1, 0, 0}; break;
      case 3: p = {-tb_h.x, rng.range(-tb_h.y, tb_h.y), z}; nrm = {-1, 0, 0}; break;
      default: p = {rng.range(-tb_h.x, tb_h.x), rng.range(-tb_h.y, tb_h.y), tb_h.z}; nrm = {0, 0, 1}; break;
    }
    const bool seam = face < 4 && std::abs(p.z - 0.12) < 0.004;
    b.splat(tb_c + p, nrm, 0.009 * sz, seam ? red * 0.35 : red, toolbox, 0.08);
  }
  for (const double x : {-0.11, 0.11})
    tube(b, tb_c + Vec3{x, 0, tb_h.z}, tb_c + Vec3{x, 0, tb_h.z + 0.035}, 0.008, 0.008, 60, 0.004, {0.1, 0.1, 0.1}, toolbox);
  tube(b, tb_c + Vec3{-0.12, 0, tb_h.z + 0.04}, tb_c + Vec3{0.12, 0, tb_h.z + 0.04}, 0.012, 0.012, 300, 0.005, {0.1, 0.1, 0.1}, toolbox);
  const Vec3 bottle_c{0.42, tb_c.y + tb_h.y + 0.035 + 0.036, top};
  const int bottle = add_object(demo, "bottle", bottle_c + Vec3{0, 0, 0.16}, 0.17f);
  for (int i = 0, n = int(2500 * d); i < n; ++i) {
    const double a = rng.range(0, 2 * M_PI), z = rng.range(0, 0.32);
    double r = 0.036, slope = 0;
    if (z > 0.2 && z < 0.25) { r = 0.036 - (z - 0.2) / 0.05 * 0.022; slope = 0.022 / 0.05; }  // the shoulder
    else if (z >= 0.25 && z < 0.295) r = 0.014;                                              // the neck
    else if (z >= 0.295) r = 0.016;                                                          // the cap
    const Vec3 nrm = normalized(Vec3{std::cos(a), std::sin(a), slope});
    Vec3 c = z >= 0.295 ? Vec3{0.9, 0.9, 0.88} : Vec3{0.12, 0.36, 0.18};
    if (z > 0.05 && z < 0.14) c = std::abs(z - 0.095) < 0.015 ? Vec3{0.8, 0.15, 0.1} : Vec3{0.92, 0.90, 0.84};  // its label
    b.splat(bottle_c + Vec3{r * std::cos(a), r * std::sin(a), z}, nrm, 0.005 * sz, c, bottle, 0.06);
  }
  for (int i = 0; i < 60; ++i) {  // the cap's top
    const double r = 0.016 * std::sqrt(rng.uniform()), a = rng.range(0, 2 * M_PI);
    b.splat(bottle_c + Vec3{r * std::cos(a), r * std::sin(a), 0.32}, {0, 0, 1}, 0.005, {0.9, 0.9, 0.88}, bottle, 0.03);
  }
  // A wooden rule (30 x 3 cm, 4 mm thick) lying flat on the bench, black ticks along one edge.
  b.depth_jitter = 0.0008;
  const int rule = add_object(demo, "ruler", rule_c, 0.16f);
  for (int i = 0, n = int(1300 * d); i < n; ++i) {
    const double t = rng.range(-0.15, 0.15);
    if (rng.uniform() < 0.2) {  // its long edges
      const double side = rng.uniform() < 0.5 ? -1 : 1;
      b.splat(rule_c + rule_dir * t + rule_side * (0.015 * side) - Vec3{0, 0, rng.range(0, 0.004)}, rule_side * side, 0.002,
              Vec3{0.80, 0.66, 0.40}, rule, 0.02);
      continue;
    }
    const double w = rng.range(-0.015, 0.015);
    const bool tick = w > (std::fmod(t + 0.15, 0.05) < 0.0012 ? 0.002 : 0.009) && std::fmod(t + 0.15, 0.01) < 0.0012;
    b.splat(rule_c + rule_dir * t + rule_side * w, {0, 0, 1}, 0.004, tick ? Vec3{0.08, 0.08, 0.08} : Vec3{0.90, 0.80, 0.52}, rule, 0.02);
  }
  // Scenery on the bench: an offcut of plywood and a tape measure.
  b.depth_jitter = 0.002;
  for (int i = 0, n = int(700 * d); i < n; ++i) {
    const bool side = rng.uniform() < 0.2;
    const double x = rng.range(-0.62, -0.30), y = rng.range(0.17, 0.30);
    if (side) b.splat({x, rng.uniform() < 0.5 ? 0.17 : 0.30, top + rng.range(0, 0.018)}, {0, rng.uniform() < 0.5 ? -1.0 : 1.0, 0}, 0.006,
                      {0.72, 0.62, 0.45}, -1, 0.02);
    else b.splat({x, y, top + 0.018}, {0, 0, 1}, 0.012 * sz, Vec3{0.86, 0.74, 0.55} + Vec3{1, 1, 1} * (0.04 * cell_noise(int(y * 40), 3)), -1,
                 0.02);
  }
  box(b, {0.62, -0.25, top + 0.035}, 0.035, 0.035, 400, 0.008, {0.95, 0.80, 0.10}, {0.1, 0.1, 0.1}, -1);
  // Floaters: faint blobs in the air around the bench and in the room, none by the cameras.
  b.depth_jitter = 0;
  b.shape_jitter = 0;
  for (int i = 0, n = int(150 * d); i < n; ++i) {
    Vec3 p;
    if (i % 3 == 0) p = {rng.range(-0.8, 0.8), rng.range(-0.45, 0.45), rng.range(1.28, 1.6)};  // above the bench
    else {
      do p = {rng.range(-2.4, 2.4), rng.range(-2.4, 2.4), rng.range(0.2, 2.3)};
      while ((std::hypot(p.x, p.y) > 1.25 && std::hypot(p.x, p.y) < 2.2) || (std::abs(p.x) < 0.85 && std::abs(p.y) < 0.5 && p.z < 1.3));
    }
    b.floater(p, rng.range(0.02, 0.07) * sz, Vec3{0.78, 0.76, 0.72} * rng.range(0.6, 1.05), rng.range(0.05, 0.3));
  }
  // The capture: 14 cameras a ring, 1.45 m out at 1.15 m and 1.9 m out at 1.75 m, looking
  // at the bench, held by hand (their own random stream: the Gaussians do not move with it).
  SplitMix64 hand(17);
  int id = 0;
  for (int ring = 0; ring < 2; ++ring)
    for (int k = 0; k < 14; ++k) {
      const double a = 2 * M_PI * (k + 0.5 * ring) / 14, r = ring ? 1.9 : 1.45;
      const Vec3 wobble{hand.range(-0.03, 0.03), hand.range(-0.03, 0.03), hand.range(-0.03, 0.03)};
      const Vec3 aim{hand.range(-0.05, 0.05), hand.range(-0.05, 0.05), hand.range(-0.05, 0.05)};
      const Vec3 eye = Vec3{r * std::sin(a), -r * std::cos(a), ring ? 1.75 : 1.15} + wobble;
      demo.bundle.cameras.push_back(
          named(Camera::look_at(eye, Vec3{0, 0, ring ? 0.85 : 0.8} + aim, {0, 0, 1}, opt.width, opt.height, 62.0), id++, "orbit"));
    }
  const Vec3 mug_c{-0.52 + 2 * mug_r, -0.12, top};
  add_task(s, "workbench", "a large object filmed close, past two image borders, things standing on it", bench,
           {-0.2, -0.3, top}, 0);
  add_task(s, "mug", "the middle one of three identical mugs touching in a row", mugs[1], mug_c + Vec3{0.02, -0.036, 0.06}, 14);
  add_task(s, "helmet", "a glossy helmet whose pearlescent colour changes with the view direction", helmet,
           helmet_c + Vec3{0.05, -0.06, 0.11}, 2);
  add_task(s, "bottle", "an orbit object hidden below its shoulder behind a toolbox in half the views", bottle,
           bottle_c + Vec3{0, -0.03, 0.23}, 14);
  add_task(s, "ruler", "a thin wooden rule lying flat on the bench", rule, rule_c + rule_side * -0.004, 20);
  return std::move(s);
}

// Forward-facing capture of an atrium, as LLFF's fern is taken (a 5 x 4 grid of nearly
// parallel cameras), with coarse, jittered Gaussians as a short training leaves them, built
// after everything else was tuned and reported as its first run: a cycad whose arching fronds
// fan out in front of a grey cabinet that shows only between them (failure 1 of real
// captures: the fern plant and the panels under its fronds), the concrete planter it stands
// in with fronds hanging over its front, and a round column at the frame's right edge.
EvalScene atrium(const EvalSetOptions& opt) {
  SceneStart start("atrium", 211);
  auto& [s, demo, g, rng, b] = start;
  const double d = opt.density, sz = 1 / std::sqrt(d);
  const double wall_y = 1.6;
  b.size_scale = 1.4;
  b.depth_jitter = 0.004;
  b.shape_jitter = 0.3;
  for (int i = 0, n = int(9000 * d); i < n; ++i) {  // the back wall: grey panels, a lit ledge, a window above
    const Vec3 p{rng.range(-3.0, 3.0), wall_y, rng.range(0, 2.8)};
    Vec3 c;
    if (p.z < 0.9) c = std::fmod(p.x + 10, 0.7) < 0.02 ? Vec3{0.30, 0.30, 0.30} : Vec3{0.55, 0.53, 0.50};
    else if (p.z < 0.96) c = {0.92, 0.90, 0.84};
    else if (std::fmod(p.x + 10, 0.6) < 0.05) c = {0.26, 0.26, 0.28};  // mullions
    else c = Vec3{0.14, 0.15, 0.17} + Vec3{0.6, 0.4, 0.2} * std::max(0.0, 2 * cell_noise(int((p.x + 10) * 3), int(p.z * 3)));
    b.splat(p, {0, -1, 0}, 0.05 * sz, c + Vec3{1, 1, 1} * (0.02 * rng.normal()), -1, 0.03);
  }
  for (int i = 0, n = int(7000 * d); i < n; ++i) {  // beige stone floor
    const Vec3 p{rng.range(-3.0, 3.0), rng.range(-1.5, wall_y), 0};
    const bool joint = std::fmod(p.x + 10, 0.6) < 0.012 || std::fmod(p.y + 10, 0.6) < 0.012;
    b.splat(p, {0, 0, 1}, 0.05 * sz, joint ? Vec3{0.36, 0.31, 0.25} : Vec3{0.58, 0.50, 0.40}, -1, 0.08);
  }
  // A grey cabinet against the wall, right behind the plant: seen only between its fronds.
  box(b, {-0.15, 1.15, 0.55}, 0.4, 0.55, int(3000 * d), 0.035 * sz, {0.42, 0.43, 0.45}, {0.30, 0.30, 0.32}, -1);
  cylinder(b, {0.55, 1.25, 0}, 0.05, 0.05, 2.8, int(700 * d), 0.02 * sz, {0.20, 0.20, 0.22}, -1, false);  // a post
  // The planter: a long concrete box, small ferns in its left end.
  const Vec3 planter_c{-0.4, 0, 0.22};
  const int planter = add_object(demo, "planter", planter_c, 0.9f);
  for (int i = 0, n = int(7000 * d); i < n; ++i) {
    const int face = int(rng.uniform() * 5);
    const double u = rng.uniform(), v = rng.uniform();
    Vec3 p, nrm;
    switch (face) {
      case 0: p = {-1.4 + 2.0 * u, -0.35, 0.44 * v}; nrm = {0, -1, 0}; break;
      case 1: p = {-1.4 + 2.0 * u, 0.35, 0.44 * v}; nrm = {0, 1, 0}; break;
      case 2: p = {-1.4, -0.35 + 0.7 * u, 0.44 * v}; nrm = {-1, 0, 0}; break;
      case 3: p = {0.6, -0.35 + 0.7 * u, 0.44 * v}; nrm = {1, 0, 0}; break;
      default: {  // the rim around the soil
        const double a = rng.uniform() * 4;
        p = a < 1 ? Vec3{-1.4 + 2.0 * u, -0.35 + 0.05 * v, 0.44} : a < 2 ? Vec3{-1.4 + 2.0 * u, 0.30 + 0.05 * v, 0.44}
          : a < 3 ? Vec3{-1.4 + 0.05 * v, -0.35 + 0.7 * u, 0.44} : Vec3{0.55 + 0.05 * v, -0.35 + 0.7 * u, 0.44};
        nrm = {0, 0, 1};
      }
    }
    b.splat(p, nrm, 0.035 * sz, Vec3{0.80, 0.80, 0.78} + Vec3{1, 1, 1} * (0.05 * cell_noise(int((p.x + 10) * 8), int(p.z * 8))),
            planter, 0.03);
  }
  for (int i = 0, n = int(900 * d); i < n; ++i)  // dark soil
    b.splat({rng.range(-1.35, 0.55), rng.range(-0.3, 0.3), 0.42}, {0, 0, 1}, 0.04 * sz, {0.16, 0.12, 0.09}, -1, 0.01);
  leaves(b, {-1.1, 0, 0.55}, {{0.25, 0.2, 0.12}, false, 0.6, 0.025, 0.02, 0.012, {0.25, 0.35, 0.15}, {0.45, 0.55, 0.25}},
         int(60 * std::max(1.0, d)), -1);
  // The cycad: a scaly trunk, and fronds of paired leaflets arching out of its crown in a fan.
  const Vec3 crown{-0.2, 0, 0.85};
  const int plant = add_object(demo, "plant", crown + Vec3{0, 0, 0.2}, 1.2f);
  cylinder(b, {crown.x, crown.y, 0.44}, 0.08, 0.06, 0.42, int(700 * d), 0.016 * sz, {0.45, 0.33, 0.20}, plant, false, 0.04);
  const int fronds = 16;
  for (int f = 0; f < fronds; ++f) {
    const double az = M_PI * (0.02 + 0.96 * f / (fronds - 1)) + rng.range(-0.06, 0.06);
    const Vec3 dir = normalized(Vec3{std::cos(az), rng.range(-0.6, 0.3), 0.9 * std::sin(az) + 0.15});
    const double length = rng.range(0.9, 1.3), droop = rng.range(0.35, 0.6);
    const Vec3 green{rng.range(0.18, 0.26), rng.range(0.42, 0.52), rng.range(0.30, 0.36)};
    for (double t = 0.04; t <= 1.0; t += 0.045 / length) {
      const Vec3 p = crown + dir * (length * t) + Vec3{0, 0, -droop * length * t * t};
      const Vec3 along = normalized(dir * length + Vec3{0, 0, -2 * droop * length * t});
      Vec3 side = normalized(cross(along, Vec3{0, 1, 0}));
      Vec3 nrm = normalized(cross(side, along));
      if (nrm.y > 0) nrm = nrm * -1.0;
      b.strip(p, nrm, along, 0.02, 0.006, green * 0.8, plant, 0.04);  // the rachis
      const double leaflet = 0.13 * (1 - 0.7 * t) + 0.03;
      for (double sign : {-1.0, 1.0}) {
        const Vec3 out = normalized(side * sign + along * 0.6 + nrm * 0.25);
        for (int k = 0; k < 3; ++k)
          b.strip(p + out * (leaflet * (k + 0.5) / 3), nrm, out, leaflet / 6, 0.005, green * rng.range(0.9, 1.1), plant, 0.05);
      }
    }
  }
  // A round column at the right, leaving the frame in the right-hand cameras.
  const int column = add_object(demo, "column", {1.4, 0.8, 1.4}, 1.5f);
  cylinder(b, {1.4, 0.8, 0}, 0.12, 0.12, 2.8, int(2200 * d), 0.025 * sz, {0.86, 0.81, 0.70}, column, false);
  b.size_scale = 1.0;
  for (int i = 0; i < 120; ++i)  // floaters a short training leaves in the air
    b.floater({rng.range(-1.6, 1.6), rng.range(-0.8, 1.4), rng.range(0.2, 2.3)}, rng.range(0.03, 0.08),
              Vec3{0.5, 0.5, 0.5} + Vec3{1, 1, 1} * (0.2 * rng.normal()), rng.range(0.05, 0.25));
  // The capture: a 5 x 4 grid of cameras 2 m from the plant, looking nearly straight ahead.
  forward_grid(demo, {0.1, -2.0, 1.25}, {0.1, 0, 0.08}, {0.1, wall_y, 0.45}, {0.04, 0, 0.03}, 64.0, opt);
  add_task(s, "plant", "arching fronds before a cabinet seen only between them (LLFF fern)", plant, crown + Vec3{0.1, -0.1, 0.2},
           12, 20);
  add_task(s, "planter", "a long box with fronds hanging over its front, the floor between it and the frame", planter,
           {0.3, -0.35, 0.36}, 12);
  add_task(s, "column", "a column at the frame's edge, its top out of view", column, {1.4 - 0.04, 0.8 - 0.12, 1.1}, 14);
  return std::move(s);
}

// Wooden floor boards on z = 0 over [x0, x1] x [y0, y1]: boards `width` wide running along y,
// each board's end joints every `length`, shifted by `stagger` x its index; `seam` wide dark
// seams; each board's colour varies along `tint` by up to half of `variation`, each
// Gaussian's by a little grey noise.
struct FloorBoards {
  double x0, x1, y0, y1, width, stagger, length, seam;
  Vec3 seam_rgb, rgb, tint;
  double variation, size, shine;
};

// A back wall facing the cameras (-y) at wall_y: n Gaussians spread over x in [-half_width,
// half_width] and z in [0, height], none inside its openings (a window, a mirror), coloured by
// colour(x, z).
struct Opening {
  double x0, x1, z0, z1;
};
template <class Colour>
void back_wall(SceneBuilder& b, double half_width, double wall_y, double height, int n, double size, double shine,
               const std::vector<Opening>& openings, Colour colour) {
  for (int i = 0; i < n; ++i) {
    const Vec3 p{b.rng.range(-half_width, half_width), wall_y, b.rng.range(0, height)};
    if (std::any_of(openings.begin(), openings.end(),
                    [&](const Opening& o) { return p.x > o.x0 && p.x < o.x1 && p.z > o.z0 && p.z < o.z1; }))
      continue;
    b.splat(p, {0, -1, 0}, size, colour(p.x, p.z), -1, shine);
  }
}

void floor_boards(SceneBuilder& b, const FloorBoards& f, int n) {
  for (int i = 0; i < n; ++i) {
    const Vec3 p{b.rng.range(f.x0, f.x1), b.rng.range(f.y0, f.y1), 0};
    const int board = int(std::floor((p.x + 10) / f.width));
    const double along = p.y + 10 + f.stagger * board;
    const bool seam = std::fmod(p.x + 10, f.width) < f.seam || std::fmod(along, f.length) < f.seam;
    const Vec3 c = seam ? f.seam_rgb : f.rgb + f.tint * (f.variation * cell_noise(board, int(along / f.length)));
    b.splat(p, {0, 0, 1}, f.size, c + Vec3{1, 1, 1} * (0.015 * b.rng.normal()), -1, f.shine);
  }
}

// An ellipsoid's surface of radii r around c: n Gaussians facing out, coloured by
// colour(local point) (uniform in direction, so a little denser at its narrow ends).
template <class Colour>
void ellipsoid(SceneBuilder& b, const Vec3& c, const Vec3& r, int n, double size, Colour colour, int label,
               double shine = 0.03) {
  for (int i = 0; i < n; ++i) {
    Vec3 u{b.rng.normal(), b.rng.normal(), b.rng.normal()};
    if (norm(u) < 1e-9) continue;
    u = normalized(u);
    const Vec3 local{u.x * r.x, u.y * r.y, u.z * r.z};
    b.splat(c + local, normalized(Vec3{u.x / r.x, u.y / r.y, u.z / r.z}), size, colour(local), label, shine);
  }
}

// A colour(local point, normal) for cuboid: one colour all over.
auto one_colour(const Vec3& c) {
  return [c](const Vec3&, const Vec3&) { return c; };
}

// An axis-aligned cuboid of half sizes h around c, its five faces but the bottom, sampled
// by area, coloured by colour(local point, normal). (`box` above samples its faces evenly
// and stays as it is: the older scenes are built from its random draws.)
template <class Colour>
void cuboid(SceneBuilder& b, const Vec3& c, const Vec3& h, int n, double size, Colour colour, int label) {
  const double ax = h.y * h.z, ay = h.x * h.z, az = h.x * h.y, total = 2 * ax + 2 * ay + az;
  for (int i = 0; i < n; ++i) {
    const double pick = b.rng.uniform() * total, u = b.rng.range(-1, 1), v = b.rng.range(-1, 1);
    Vec3 p, nrm;
    if (pick < ax) p = {h.x, u * h.y, v * h.z}, nrm = {1, 0, 0};
    else if (pick < 2 * ax) p = {-h.x, u * h.y, v * h.z}, nrm = {-1, 0, 0};
    else if (pick < 2 * ax + ay) p = {u * h.x, h.y, v * h.z}, nrm = {0, 1, 0};
    else if (pick < 2 * ax + 2 * ay) p = {u * h.x, -h.y, v * h.z}, nrm = {0, -1, 0};
    else p = {u * h.x, v * h.y, h.z}, nrm = {0, 0, 1};
    b.splat(c + p, nrm, size, colour(p, nrm), label, 0.03);
  }
}

// Forward-facing hand-held capture of a children's playroom (a 5 x 4 grid as LLFF scenes
// are taken, each camera a little off the grid and off its aim), with coarse, jittered
// Gaussians as a short training leaves them and faint floaters, built by a session that had
// not seen the method's tuning, as a check on objects nothing was tuned on: a wooden
// climbing triangle whose rungs show the wallpaper and its far rungs between them, a
// rocking horse standing behind a toy chest (only its back, neck and head above the lid;
// the clicked flank is hidden from the lower views), a plush rabbit sitting in a playpen,
// seen through its bars, a broom leaning on the wall near the frame's right edge, and a doll's
// house (walls, windows, door, roof, chimney) on a low shelf, clicked on its roof.
EvalScene playroom(const EvalSetOptions& opt) {
  SceneStart start("playroom", 233);
  auto& [s, demo, g, rng, b] = start;
  const double d = opt.density, sz = 1 / std::sqrt(d);
  const double wall_y = 1.55;
  auto noise = [&](double a) { return Vec3{1, 1, 1} * (a * rng.normal()); };
  b.size_scale = 1.4;
  b.depth_jitter = 0.005;
  b.shape_jitter = 0.3;
  for (int i = 0, n = int(16000 * d); i < n; ++i) {  // sage striped wallpaper with coral motifs, lit from above
    const Vec3 p{rng.range(-2.9, 3.1), wall_y, rng.range(0, 2.7)};
    const int band = int(std::floor((p.x + 10) / 0.3));
    const double across = std::fmod(p.x + 10, 0.3);
    Vec3 c = across < 0.1 ? Vec3{0.60, 0.67, 0.56} : Vec3{0.77, 0.80, 0.70};
    const double dx = across - 0.2, dz = std::fmod(p.z + (band & 1) * 0.15, 0.3) - 0.15;
    if (dx * dx + dz * dz < 0.035 * 0.035) c = {0.86, 0.55, 0.45};
    b.splat(p, {0, -1, 0}, 0.035 * sz, c * (0.9 + 0.04 * p.z) + noise(0.02), -1, 0.02);
  }
  for (int i = 0, n = int(900 * d); i < n; ++i) {  // white skirting board
    const double x = rng.range(-2.9, 3.1), z = rng.range(0, 0.1);
    b.strip({x, wall_y - 0.015, z}, {0, -1, 0}, {1, 0, 0}, 0.03, 0.02, Vec3{0.92, 0.91, 0.87} + noise(0.02), -1, 0.04);
  }
  for (int i = 0, n = int(1200 * d); i < n; ++i) {  // a framed picture-book poster: sky, hills, a sun
    const double x = rng.range(-0.75, -0.05), z = rng.range(1.35, 1.85);
    const bool frame = x < -0.72 || x > -0.08 || z < 1.38 || z > 1.82;
    const bool sun = (x + 0.25) * (x + 0.25) + (z - 1.7) * (z - 1.7) < 0.06 * 0.06;
    const double hill = 1.5 + 0.07 * std::sin(x * 9);
    const Vec3 c = frame ? Vec3{0.95, 0.95, 0.93} : sun ? Vec3{0.96, 0.80, 0.25} : z < hill ? Vec3{0.40, 0.62, 0.30} : Vec3{0.55, 0.75, 0.92};
    b.splat({x, wall_y - 0.01, z}, {0, -1, 0}, 0.02 * sz, c + noise(0.02), -1, 0.03);
  }
  b.depth_jitter = 0.004;
  floor_boards(b, {-2.9, 3.1, -2.0, wall_y, 0.14, 0.37, 1.2, 0.008, {0.25, 0.17, 0.10}, {0.56, 0.40, 0.25},
                   {1, 0.8, 0.6}, 0.12, 0.04 * sz, 0.06},
               int(11000 * d));  // oak, 14 cm wide
  for (int i = 0, n = int(4500 * d); i < n; ++i) {  // a cream rug with a teal border and dots
    const Vec3 p{rng.range(-1.4, 1.4), rng.range(-1.2, 0.2), 0.006};
    const bool border = p.x < -1.28 || p.x > 1.28 || p.y < -1.08 || p.y > 0.08;
    const double fx = std::fmod(p.x + 10, 0.3) - 0.15, fy = std::fmod(p.y + 10, 0.3) - 0.15;
    const Vec3 c = border ? Vec3{0.18, 0.45, 0.48} : fx * fx + fy * fy < 0.04 * 0.04 ? Vec3{0.85, 0.62, 0.30} : Vec3{0.88, 0.84, 0.74};
    b.splat(p, {0, 0, 1}, 0.04 * sz, c + noise(0.02), -1, 0.01);
  }
  b.depth_jitter = 0.002;
  b.shape_jitter = 0.25;
  // Wooden blocks left on the rug.
  const Vec3 block_rgb[] = {{0.80, 0.20, 0.15}, {0.95, 0.75, 0.20}, {0.20, 0.45, 0.70}, {0.30, 0.60, 0.30}};
  for (int k = 0; k < 7; ++k) {
    const Vec3 c{rng.range(-0.9, 0.9), rng.range(-0.9, -0.2), 0.03};
    const Vec3 col = block_rgb[k % 4];
    cuboid(b, c, {0.03, 0.03, 0.03}, 120, 0.008, [&](const Vec3&, const Vec3&) { return col; }, -1);
  }
  // The climbing triangle: two A-frames of round rails, 14 rungs between them.
  const Vec3 birch{0.88, 0.76, 0.56};
  const double tri_x0 = -1.45, tri_x1 = -0.85, tri_y = 1.05, tri_h = 0.85, tri_half = 0.3;
  const int triangle = add_object(demo, "climbing_triangle", {(tri_x0 + tri_x1) / 2, tri_y, tri_h / 2}, 0.6f);
  for (double x : {tri_x0, tri_x1})
    for (double side : {-1.0, 1.0})
      tube(b, {x, tri_y + side * tri_half, 0}, {x, tri_y + side * 0.02, tri_h + 0.02}, 0.022, 0.022, int(900 * d) + 60, 0.008 * sz,
           birch * 0.95, triangle);
  for (int k = 1; k <= 7; ++k)
    for (double side : {-1.0, 1.0}) {
      const double t = k / 8.0;
      const Vec3 at{0, tri_y + side * tri_half * (1 - t), tri_h * t};
      tube(b, Vec3{tri_x0, 0, 0} + at, Vec3{tri_x1, 0, 0} + at, 0.016, 0.016, int(650 * d) + 40, 0.0065 * sz,
           birch * rng.range(0.95, 1.05), triangle);
    }
  // The playpen: white bars on four sides, rails top and bottom, a padded mat inside.
  const double pen_x0 = -0.72, pen_x1 = -0.02, pen_y0 = 0.35, pen_y1 = 1.05, pen_h = 0.66;
  const Vec3 white{0.93, 0.92, 0.89};
  for (int side = 0; side < 4; ++side) {
    const Vec3 a = side == 0 ? Vec3{pen_x0, pen_y0, 0} : side == 1 ? Vec3{pen_x1, pen_y0, 0} : side == 2 ? Vec3{pen_x1, pen_y1, 0} : Vec3{pen_x0, pen_y1, 0};
    const Vec3 e = side == 0 ? Vec3{pen_x1, pen_y0, 0} : side == 1 ? Vec3{pen_x1, pen_y1, 0} : side == 2 ? Vec3{pen_x0, pen_y1, 0} : Vec3{pen_x0, pen_y0, 0};
    for (double z : {0.04, pen_h}) tube(b, a + Vec3{0, 0, z}, e + Vec3{0, 0, z}, 0.02, 0.02, int(1400 * d) + 60, 0.008 * sz, white, -1);
    for (int k = 0; k < 9; ++k) {  // bars 2 cm thick, 8 cm apart
      const Vec3 foot = a + (e - a) * (k / 9.0);
      tube(b, foot + Vec3{0, 0, 0.04}, foot + Vec3{0, 0, pen_h}, 0.01, 0.01, int(450 * d) + 30, 0.0035 * sz, white, -1);
    }
  }
  for (int i = 0, n = int(1500 * d); i < n; ++i)
    b.splat({rng.range(pen_x0, pen_x1), rng.range(pen_y0, pen_y1), 0.05}, {0, 0, 1}, 0.025 * sz, Vec3{0.62, 0.70, 0.78} + noise(0.02), -1,
            0.02);
  // A plush rabbit sitting on the mat: body, head, long ears (pink inside), feet, a nose.
  const Vec3 rabbit_c{-0.37, 0.75, 0.05};
  const int rabbit = add_object(demo, "rabbit", rabbit_c + Vec3{0, 0, 0.25}, 0.3f);
  const Vec3 fur{0.70, 0.56, 0.42};
  auto plush = [&](const Vec3&) { return fur + noise(0.03); };
  ellipsoid(b, rabbit_c + Vec3{0, 0, 0.13}, {0.11, 0.10, 0.13}, int(2400 * d), 0.012 * sz, plush, rabbit, 0.01);
  ellipsoid(b, rabbit_c + Vec3{0, -0.02, 0.31}, {0.075, 0.07, 0.07}, int(1200 * d), 0.01 * sz, plush, rabbit, 0.01);
  for (double side : {-1.0, 1.0}) {
    ellipsoid(b, rabbit_c + Vec3{side * 0.035, -0.01, 0.44}, {0.024, 0.014, 0.09}, int(350 * d), 0.007 * sz,
              [&](const Vec3& l) { return l.y < 0 && std::abs(l.x) < 0.012 ? Vec3{0.90, 0.68, 0.66} : fur; }, rabbit, 0.01);
    ellipsoid(b, rabbit_c + Vec3{side * 0.06, -0.1, 0.03}, {0.035, 0.055, 0.03}, int(300 * d), 0.008 * sz, plush, rabbit, 0.01);
  }
  ellipsoid(b, rabbit_c + Vec3{0, -0.09, 0.31}, {0.012, 0.008, 0.01}, 40, 0.004, [&](const Vec3&) { return Vec3{0.55, 0.35, 0.35}; },
            rabbit, 0.01);
  // A toy chest: blue boards with a pale panel border, a blue lid.
  const Vec3 chest_c{0.4, 0.35, 0.22};
  cuboid(b, chest_c, {0.3, 0.2, 0.22}, int(7000 * d), 0.018 * sz,
         [&](const Vec3& p, const Vec3& n) {
           const double u = std::abs(n.x) > 0.5 ? p.y / 0.2 : p.x / 0.3, v = p.z / 0.22;
           const bool trim = n.z < 0.5 && (std::abs(u) > 0.88 || std::abs(v) > 0.85);
           return (trim ? Vec3{0.58, 0.70, 0.82} : Vec3{0.22, 0.38, 0.58}) + noise(0.02);
         },
         -1);
  cuboid(b, chest_c + Vec3{0, 0, 0.235}, {0.315, 0.215, 0.015}, int(2500 * d), 0.015 * sz,
         [&](const Vec3&, const Vec3&) { return Vec3{0.26, 0.44, 0.64} + noise(0.02); }, -1);
  // A rocking horse behind it: dappled body on four legs, neck, head, ears, saddle, mane,
  // tail, handles, on a pair of wooden rockers.
  const double horse_y = 1.05;
  const int horse = add_object(demo, "rocking_horse", {0.5, horse_y, 0.43}, 0.5f);
  const Vec3 cream{0.90, 0.87, 0.80}, dapple{0.55, 0.55, 0.58}, dark{0.30, 0.20, 0.12}, oak{0.62, 0.44, 0.26};
  auto coat = [&](const Vec3& l) {
    return (cell_noise(int((l.x + 1) * 25), int((l.z + 1) * 25)) > 0.3 ? dapple : cream) + noise(0.02);
  };
  ellipsoid(b, {0.44, horse_y, 0.42}, {0.24, 0.10, 0.09}, int(3200 * d), 0.013 * sz, coat, horse);
  tube(b, {0.62, horse_y, 0.45}, {0.74, horse_y, 0.63}, 0.055, 0.045, int(700 * d), 0.012 * sz, cream, horse);
  ellipsoid(b, {0.81, horse_y, 0.63}, {0.11, 0.05, 0.055}, int(900 * d), 0.01 * sz, coat, horse);
  for (double side : {-1.0, 1.0}) {
    ellipsoid(b, {0.73, horse_y + side * 0.03, 0.70}, {0.014, 0.012, 0.035}, 80, 0.006, [&](const Vec3&) { return cream; }, horse);
    for (double x : {0.26, 0.64}) {
      const double foot_z = 0.035 + 0.12 * std::pow((x - 0.47) / 0.45, 2) + 0.03;
      tube(b, {x + (x < 0.4 ? -0.06 : 0.06), horse_y + side * 0.085, foot_z}, {x, horse_y + side * 0.06, 0.39}, 0.02, 0.024,
           int(260 * d) + 40, 0.009 * sz, cream, horse);
    }
    for (double x = 0.02; x <= 0.92; x += 0.008) {  // a rocker: a bow of 4 x 2 cm board
      const double z = 0.035 + 0.12 * std::pow((x - 0.47) / 0.45, 2), slope = 2 * 0.12 * (x - 0.47) / (0.45 * 0.45);
      const Vec3 along = normalized(Vec3{1, 0, slope}), up = normalized(Vec3{-slope, 0, 1});
      for (double face : {-1.0, 1.0}) b.strip({x, horse_y + side * 0.1 + face * 0.01, z}, {0, face, 0}, along, 0.012, 0.02, oak, horse, 0.03);
      b.strip(Vec3{x, horse_y + side * 0.1, z} + up * 0.02, up, along, 0.012, 0.012, oak * 1.05, horse, 0.03);
    }
  }
  ellipsoid(b, {0.42, horse_y, 0.49}, {0.08, 0.105, 0.025}, int(500 * d), 0.01 * sz, [&](const Vec3&) { return Vec3{0.68, 0.14, 0.12}; },
            horse);
  for (double t = 0; t <= 1; t += 0.04)  // mane: tufts along the neck's back, tail at the back
    for (double side : {-1.0, 1.0})
      b.strip(Vec3{0.62, horse_y + side * 0.012, 0.45} + Vec3{0.12, 0, 0.18} * t + Vec3{-0.83, 0, 0.55} * 0.05, {0, side, 0},
              {-0.83, 0, 0.55}, 0.015, 0.012, dark, horse, 0.02);
  for (double t = 0; t <= 1; t += 0.08)
    b.strip(Vec3{0.2 - 0.04 * t, horse_y, 0.45 - 0.14 * t}, {0, -1, 0}, {-0.3, 0, -1}, 0.03, 0.02, dark, horse, 0.02);
  tube(b, {0.76, horse_y - 0.1, 0.66}, {0.76, horse_y + 0.1, 0.66}, 0.01, 0.01, 100, 0.006, dark, horse);
  // A low white shelf against the wall with a doll's house on it.
  cuboid(b, {1.3, 1.3, 0.18}, {0.3, 0.2, 0.18}, int(3500 * d), 0.025 * sz,
         [&](const Vec3& p, const Vec3& n) { return (n.y < -0.5 && std::abs(p.z) < 0.01 ? Vec3{0.6, 0.6, 0.58} : white) + noise(0.015); },
         -1);
  const Vec3 house_c{1.3, 1.28, 0.36};
  const double hx = 0.22, hy = 0.16, wall_h = 0.36, ridge_h = 0.2, eave = 0.03;
  const int house = add_object(demo, "dolls_house", house_c + Vec3{0, 0, 0.3}, 0.4f);
  const Vec3 yellow{0.93, 0.84, 0.58}, window{0.30, 0.38, 0.48}, door{0.70, 0.18, 0.15};
  cuboid(b, house_c + Vec3{0, 0, wall_h / 2}, {hx, hy, wall_h / 2}, int(6000 * d), 0.012 * sz,
         [&](const Vec3& p, const Vec3& n) {
           if (n.z > 0.5) return yellow;
           const double u = std::abs(n.x) > 0.5 ? p.y : p.x, v = p.z + wall_h / 2;
           if (n.y < -0.5 && std::abs(u) < 0.045 && v < 0.15) return door;
           const double wu = std::fmod(std::abs(u) + 10, 0.14) - 0.07;
           const bool pane = std::abs(u) > 0.07 && std::abs(wu) < 0.035 && (std::abs(v - 0.1) < 0.045 || std::abs(v - 0.27) < 0.045);
           const bool sill = std::abs(u) > 0.07 && std::abs(wu) < 0.045 && (std::abs(v - 0.1) < 0.055 || std::abs(v - 0.27) < 0.055);
           return (pane ? window : sill ? Vec3{0.96, 0.96, 0.94} : yellow) + noise(0.015);
         },
         house);
  const double slope_len = std::hypot(hy + eave, ridge_h);
  for (double side : {-1.0, 1.0}) {  // the two roof slopes, shingle rows darker
    const Vec3 nrm = normalized(Vec3{0, side * ridge_h, hy + eave});
    for (int i = 0, n = int(1800 * d); i < n; ++i) {
      const double x = rng.range(-hx - eave, hx + eave), t = rng.uniform();
      const Vec3 p = house_c + Vec3{x, side * (hy + eave) * (1 - t), wall_h + ridge_h * t - 0.01 * (1 - t)};
      const bool row = std::fmod(t * slope_len, 0.04) < 0.008;
      b.splat(p, nrm, 0.013 * sz, (row ? Vec3{0.42, 0.16, 0.12} : Vec3{0.64, 0.25, 0.18}) + noise(0.02), house, 0.03);
    }
    for (int i = 0, n = int(400 * d); i < n; ++i) {  // a gable: the wall's triangle under the roof
      const double t = rng.uniform(), w = rng.range(-1, 1) * hy * (1 - t);
      b.splat(house_c + Vec3{side * hx, w, wall_h + ridge_h * t}, {side, 0, 0}, 0.012 * sz, yellow + noise(0.015), house, 0.03);
    }
  }
  const Vec3 chimney_c = house_c + Vec3{0.12, -0.06, wall_h + ridge_h * (1 - 0.06 / (hy + eave)) - 0.025};
  cuboid(b, chimney_c + Vec3{0, 0, 0.08}, {0.03, 0.03, 0.08}, int(500 * d), 0.007 * sz,
         [&](const Vec3& p, const Vec3& n) {
           if (n.z > 0.5) return Vec3{0.2, 0.2, 0.2};  // painted white, a dark cap
           return (p.z > 0.06 ? Vec3{0.25, 0.25, 0.26} : Vec3{0.92, 0.91, 0.88}) + noise(0.02);
         },
         house);
  // A broom leaning on the wall at the right: wooden handle, red band, straw bristles.
  const Vec3 broom_foot{1.95, 1.27, 0}, broom_top{1.82, wall_y - 0.015, 1.32};
  const int broom = add_object(demo, "broom", (broom_foot + broom_top) * 0.5, 0.7f);
  const Vec3 lean = normalized(broom_top - broom_foot);
  tube(b, broom_foot + lean * 0.2, broom_top, 0.013, 0.013, int(1500 * d) + 80, 0.005 * sz, {0.74, 0.58, 0.40}, broom);
  tube(b, broom_foot + lean * 0.17, broom_foot + lean * 0.21, 0.03, 0.018, 150, 0.006, {0.62, 0.12, 0.12}, broom);
  const Vec3 across{1, 0, 0}, face = normalized(cross(across, lean));
  for (int i = 0, n = int(700 * d); i < n; ++i) {  // the bristles: a fan from the band to the floor
    const double t = rng.uniform(), w = rng.range(-1, 1) * (0.03 + 0.11 * (1 - t));
    const Vec3 p = broom_foot + lean * (0.17 * t) + across * w + face * rng.range(-0.02, 0.02);
    b.strip(p, face * (rng.uniform() < 0.5 ? -1.0 : 1.0), lean, 0.02, 0.006, Vec3{0.80, 0.68, 0.42} * rng.range(0.85, 1.1), broom, 0.02);
  }
  // Floaters: faint blobs in the air a short training leaves, none by the cameras.
  b.size_scale = 1.0;
  b.depth_jitter = 0;
  b.shape_jitter = 0;
  for (int i = 0, n = int(160 * d); i < n; ++i)
    b.floater({rng.range(-2.0, 2.4), rng.range(-0.8, 1.45), rng.range(0.1, 2.3)}, rng.range(0.02, 0.07) * sz,
              Vec3{0.72, 0.72, 0.66} * rng.range(0.6, 1.1), rng.range(0.05, 0.3));
  // The capture: a 5 x 4 grid 3.25 m from the wall, held by hand.
  const HandHeld hand{31, 0.03, 0.05};
  forward_grid(demo, {0.15, -1.7, 1.225}, {0.2, 0, 0.15}, {0.15, wall_y, 0.55}, {0.07, 0, 0.05}, 66.0, opt, &hand);
  add_task(s, "climbing_triangle", "rungs with gaps before a patterned wall, the far rungs between the near ones", triangle,
           {(tri_x0 + tri_x1) / 2 + 0.1, tri_y - tri_half * (1 - 4 / 8.0) - 0.016, tri_h * 4 / 8.0}, 7);
  add_task(s, "rocking_horse", "behind a toy chest: only its back, neck and head above the lid; the clicked flank hidden from the lower views",
           horse, {0.40, horse_y - 0.09, 0.40}, 12);
  add_task(s, "rabbit", "a plush toy in a playpen, seen through its bars", rabbit, rabbit_c + Vec3{0, -0.1, 0.15}, 12, 20);
  add_task(s, "broom", "a broom's thin handle leaning on the wall near the frame's right edge", broom,
           broom_foot + lean * 0.75 + Vec3{0, -0.013, 0}, 10);
  add_task(s, "dolls_house", "compound object: a doll's house (walls, door, windows, roof, chimney) clicked on its roof", house,
           house_c + Vec3{-0.1, -(hy + eave) * 0.5, wall_h + ridge_h * 0.5}, 12);
  return std::move(s);
}

// Forward-facing hand-held capture of a corner of a home office (a 5 x 4 grid as LLFF scenes are
// taken, each camera a little off the grid and off its aim), with jittered Gaussians and faint
// floaters, built as a held-out check by a session that had not seen the method's tuning (one
// change after a first score, the leaves spread apart so that the books show through them as its
// brief asked; none after the first run docs/evaluation.md reports): a monstera whose broad, slit leaves on
// long stalks stand 20-30 cm in front of a bookcase full of coloured spines, which show through the
// gaps between the leaves (the truth is the leaves, stalks and stems, not the pot); a thin wooden
// coat stand near the frame's left edge, its hooks above the top of most views; a waste-paper bin
// on the floor partly behind the end panel of the desk's return, the clicked point hidden by the
// panel from the grid's left columns; an anglepoise desk lamp (a base, twin-rod arms, a conical
// shade) clicked on its shade; a stapler on the desk; an office chair with a see-through mesh back
// in front of the desk, its five-spoke base on castors; and a globe on the bookcase's top shelf
// among books.
EvalScene office(const EvalSetOptions& opt) {
  SceneStart start("office", 131);
  auto& [s, demo, g, rng, b] = start;
  const double d = opt.density, sz = 1 / std::sqrt(d);
  const double wall_y = 2.0;
  auto noise = [&](double a) { return Vec3{1, 1, 1} * (a * rng.normal()); };
  const Vec3 paint{0.80, 0.82, 0.79}, white{0.91, 0.91, 0.89};
  b.depth_jitter = 0.006;
  b.shape_jitter = 0.35;
  for (int i = 0, n = int(11000 * d); i < n; ++i) {  // painted wall, pale grey-green, blotchy
    const Vec3 p{rng.range(-2.8, 3.4), wall_y, rng.range(0, 2.9)};
    if (p.x > 2.05 && p.x < 2.75 && p.z > 0.95 && p.z < 2.15) continue;  // the window
    const double blotch = 0.04 * cell_noise(int(std::floor((p.x + 10) / 0.4)), int(std::floor(p.z / 0.4)));
    b.splat(p, {0, -1, 0}, 0.05 * sz, paint * (0.93 + 0.025 * p.z) + Vec3{1, 1, 1} * blotch + noise(0.02), -1, 0.02);
  }
  for (int i = 0, n = int(1500 * d); i < n; ++i) {  // a window: white frame and cross bar, pale sky
    const double x = rng.range(2.05, 2.75), z = rng.range(0.95, 2.15);
    const bool frame = x < 2.1 || x > 2.7 || z < 1.0 || z > 2.1 || std::abs(x - 2.4) < 0.02 || std::abs(z - 1.6) < 0.02;
    const Vec3 c = frame ? white : Vec3{0.74, 0.83, 0.93} + Vec3{1, 1, 1} * (0.05 * (z - 1.5));
    b.splat({x, wall_y + (frame ? -0.01 : 0.02), z}, {0, -1, 0}, 0.025 * sz, c + noise(0.015), -1, frame ? 0.03 : 0.08);
  }
  for (int i = 0, n = int(250 * d); i < n; ++i)  // its sill
    b.splat({rng.range(2.0, 2.8), rng.range(wall_y - 0.12, wall_y), 0.94}, {0, 0, 1}, 0.02 * sz, white + noise(0.015), -1, 0.03);
  for (int i = 0, n = int(900 * d); i < n; ++i)  // white skirting board
    b.strip({rng.range(-2.8, 3.4), wall_y - 0.012, rng.range(0, 0.09)}, {0, -1, 0}, {1, 0, 0}, 0.03, 0.02, white + noise(0.02), -1, 0.04);
  for (int i = 0, n = int(1400 * d); i < n; ++i) {  // a cork pinboard over the desk, notes pinned on it
    const double x = rng.range(0.7, 1.5), z = rng.range(1.25, 1.75);
    const bool frame = x < 0.72 || x > 1.48 || z < 1.27 || z > 1.73;
    Vec3 c = frame ? Vec3{0.55, 0.40, 0.26} : Vec3{0.72, 0.56, 0.38} + noise(0.04);
    const struct { double x, z; Vec3 rgb; } notes[] = {
        {0.82, 1.60, {0.95, 0.90, 0.45}}, {0.98, 1.45, {0.95, 0.95, 0.93}}, {1.22, 1.58, {0.55, 0.80, 0.90}}, {1.35, 1.38, {0.95, 0.60, 0.65}}};
    for (const auto& note : notes)
      if (std::abs(x - note.x) < 0.05 && std::abs(z - note.z) < 0.05) c = note.rgb;
    b.splat({x, wall_y - 0.015, z}, {0, -1, 0}, 0.018 * sz, c, -1, 0.02);
  }
  b.depth_jitter = 0.004;
  floor_boards(b, {-2.8, 3.4, -1.0, wall_y, 0.12, 0.53, 1.4, 0.006, {0.36, 0.30, 0.24}, {0.70, 0.60, 0.48},
                   {1, 0.85, 0.7}, 0.10, 0.045 * sz, 0.05},
               int(9000 * d));  // pale ash, 12 cm wide
  // The bookcase against the wall: walnut sides, shelves and back, five shelves of books.
  b.depth_jitter = 0.002;
  b.shape_jitter = 0.2;
  const double bc_x0 = -1.45, bc_x1 = -0.05, bc_front = 1.68, bc_top = 1.82;
  const Vec3 walnut{0.42, 0.29, 0.18};
  const double shelf_top[] = {0.10, 0.45, 0.80, 1.15, 1.50};
  for (double x : {bc_x0 + 0.02, bc_x1 - 0.02}) {  // the sides' inner faces and front edges
    for (int i = 0, n = int(900 * d); i < n; ++i)
      b.splat({x, rng.range(bc_front, wall_y), rng.range(0, bc_top)}, {x < -0.7 ? 1.0 : -1.0, 0, 0}, 0.02 * sz, walnut * 0.9 + noise(0.02), -1,
              0.03);
    for (double z = 0; z < bc_top; z += 0.012)
      b.strip({x + (x < -0.7 ? -0.01 : 0.01), bc_front, z}, {0, -1, 0}, {0, 0, 1}, 0.01, 0.01, walnut + noise(0.02), -1, 0.04);
  }
  for (int i = 0, n = int(900 * d); i < n; ++i)  // the right side's outer face
    b.splat({bc_x1, rng.range(bc_front, wall_y), rng.range(0, bc_top)}, {1, 0, 0}, 0.02 * sz, walnut * 0.95 + noise(0.02), -1, 0.03);
  for (int i = 0, n = int(2400 * d); i < n; ++i)  // the back panel
    b.splat({rng.range(bc_x0, bc_x1), wall_y - 0.01, rng.range(0.08, bc_top)}, {0, -1, 0}, 0.025 * sz, walnut * 0.7 + noise(0.02), -1, 0.02);
  for (int i = 0, n = int(300 * d); i < n; ++i)  // the plinth
    b.splat({rng.range(bc_x0, bc_x1), bc_front, rng.range(0, 0.08)}, {0, -1, 0}, 0.012 * sz, walnut * 0.8 + noise(0.02), -1, 0.03);
  for (double z : {shelf_top[0], shelf_top[1], shelf_top[2], shelf_top[3], shelf_top[4], bc_top}) {
    for (double x = bc_x0; x < bc_x1; x += 0.012)  // the board's front edge
      b.strip({x, bc_front, z - 0.01}, {0, -1, 0}, {1, 0, 0}, 0.01, 0.01, walnut * 1.05 + noise(0.02), -1, 0.04);
    for (int i = 0, n = int(400 * d); i < n; ++i)  // its top in front of the books
      b.splat({rng.range(bc_x0, bc_x1), rng.range(bc_front, bc_front + 0.1), z}, {0, 0, 1}, 0.012 * sz, walnut + noise(0.02), -1, 0.04);
  }
  const Vec3 spines[] = {{0.62, 0.12, 0.12}, {0.12, 0.25, 0.50}, {0.14, 0.40, 0.25}, {0.85, 0.72, 0.30}, {0.90, 0.88, 0.82},
                         {0.20, 0.20, 0.22}, {0.55, 0.30, 0.55}, {0.85, 0.45, 0.18}, {0.35, 0.55, 0.70}, {0.50, 0.35, 0.20}};
  const double globe_x = -0.29;
  for (int k = 0; k < 5; ++k) {  // the books, shelf by shelf, a gap now and then
    const double z0 = shelf_top[k], room = (k < 4 ? shelf_top[k + 1] - 0.02 : bc_top - 0.02) - z0;
    double x = bc_x0 + 0.02 + rng.range(0, 0.04);
    while (x < bc_x1 - 0.035) {
      if (k == 4 && x > globe_x - 0.15 && x < globe_x + 0.14) {  // the globe's place
        x = globe_x + 0.14;
        continue;
      }
      if (rng.uniform() < 0.06) {
        x += rng.range(0.04, 0.12);
        continue;
      }
      const double w = std::min(rng.range(0.018, 0.05), bc_x1 - 0.02 - x), h = room * rng.range(0.55, 0.93);
      const Vec3 col = spines[int(rng.uniform() * 10) % 10] * rng.range(0.85, 1.1);
      const double front = bc_front + rng.range(0.015, 0.04);
      for (int i = 0, n = int(w * h * d / 1.6e-4) + 3; i < n; ++i) {  // the spine, a title band and a foot band
        const double u = rng.range(0, w), v = rng.range(0, h);
        const bool band = std::abs(v - 0.8 * h) < 0.012 || std::abs(v - 0.12 * h) < 0.005;
        b.splat({x + u, front, z0 + v}, {0, -1, 0}, 0.009 * sz, band ? col * 0.5 + Vec3{0.38, 0.32, 0.15} : col, -1, 0.03);
      }
      for (int i = 0, n = int(w * 0.2 * d / 2e-4) + 1; i < n; ++i)  // its top (the pages)
        b.splat({x + rng.range(0, w), front + rng.range(0, 0.2), z0 + h}, {0, 0, 1}, 0.01 * sz, Vec3{0.88, 0.85, 0.78}, -1, 0.02);
      x += w + rng.range(0, 0.004);
    }
  }
  // A globe on the top shelf: a brass stand and half meridian, oceans and continents.
  const Vec3 globe_c{globe_x, 1.84, shelf_top[4] + 0.165};
  const int globe = add_object(demo, "globe", globe_c, 0.16f);
  const Vec3 brass{0.70, 0.57, 0.30};
  cylinder(b, {globe_x, 1.84, shelf_top[4]}, 0.05, 0.045, 0.015, 200, 0.006, brass * 0.8, globe, true);
  tube(b, {globe_x, 1.84, shelf_top[4] + 0.01}, globe_c - Vec3{0, 0, 0.11}, 0.008, 0.008, 60, 0.004, brass, globe);
  ellipsoid(b, globe_c, {0.1, 0.1, 0.1}, int(1800 * d), 0.008 * sz,
            [&](const Vec3& l) {
              const double lat = std::asin(std::clamp(l.z / 0.1, -1.0, 1.0)), lon = std::atan2(l.y, l.x);
              const double land = cell_noise(int(std::floor(lat / 0.3)) + 7, int(std::floor(lon / 0.35)) + 11);
              return (land > 0.12 ? (land > 0.35 ? Vec3{0.78, 0.66, 0.44} : Vec3{0.48, 0.60, 0.34}) : Vec3{0.18, 0.38, 0.62}) + noise(0.02);
            },
            globe, 0.06);
  for (int i = 0; i <= 60; ++i) {  // the meridian, tilted with the axis, on the left
    const double a = -M_PI / 2 + M_PI * i / 60, tilt = 0.4;
    const double x = -std::cos(a), z = std::sin(a);
    const Vec3 r{x * std::cos(tilt) + z * std::sin(tilt), 0, -x * std::sin(tilt) + z * std::cos(tilt)};
    b.strip(globe_c + r * 0.112, normalized(r + Vec3{0, -0.3, 0}), cross(r, Vec3{0, 1, 0}), 0.008, 0.006, brass, globe, 0.08);
  }
  // The monstera in a cream pot, 20-30 cm in front of the books: three short stems, long
  // stalks, about 12 broad leaves, most of them slit from the edge between the veins.
  b.depth_jitter = 0.003;
  b.shape_jitter = 0.25;
  const Vec3 pot_c{-0.6, 1.2, 0};
  const int pot = add_object(demo, "plant_pot", pot_c + Vec3{0, 0, 0.17}, 0.25f);
  const Vec3 cream{0.86, 0.84, 0.79};
  cylinder(b, pot_c, 0.14, 0.17, 0.3, int(1800 * d), 0.013 * sz, cream, pot, false);
  cylinder(b, pot_c + Vec3{0, 0, 0.3}, 0.176, 0.176, 0.04, int(400 * d), 0.01 * sz, cream * 0.9, pot, false);
  for (int i = 0, n = int(250 * d); i < n; ++i) {  // the soil inside the rim
    const double r = 0.165 * std::sqrt(rng.uniform()), a = rng.range(0, 2 * M_PI);
    b.splat(pot_c + Vec3{r * std::cos(a), r * std::sin(a), 0.32}, {0, 0, 1}, 0.014 * sz, Vec3{0.22, 0.16, 0.11} + noise(0.02), pot, 0.01);
  }
  const int monstera = add_object(demo, "monstera", pot_c + Vec3{0, 0, 0.85}, 0.65f);
  const Vec3 stalk_rgb{0.30, 0.45, 0.20};
  const Vec3 stem_top[] = {pot_c + Vec3{-0.05, 0.02, 0.55}, pot_c + Vec3{0.04, -0.03, 0.6}, pot_c + Vec3{0.01, 0.04, 0.5}};
  for (const Vec3& t : stem_top)
    tube(b, Vec3{pot_c.x + (t.x - pot_c.x) * 0.3, pot_c.y + (t.y - pot_c.y) * 0.3, 0.31}, t, 0.014, 0.011, int(250 * d) + 40, 0.006 * sz,
         stalk_rgb * 0.9, monstera);
  std::vector<Vec3> leaf_at;
  for (int tries = 0; leaf_at.size() < 12 && tries < 4000; ++tries) {  // spread out, so the books show between them
    const Vec3 c = pot_c + Vec3{rng.range(-0.5, 0.5), rng.range(-0.15, 0.12), rng.range(0.6, 1.25)};
    if (std::abs(c.x - pot_c.x) > 0.38 && c.z > 1.1) continue;  // a rounded crown
    bool close = false;
    for (const Vec3& o : leaf_at) close = close || std::hypot(o.x - c.x, o.z - c.z) < 0.22;
    if (!close) leaf_at.push_back(c);
  }
  Vec3 leaf_click{0, 0, 0};
  double best_leaf = -1e9;
  b.depth_jitter = 0.004;
  b.shape_jitter = 0.3;
  for (const Vec3& c : leaf_at) {
    const Vec3& top = stem_top[c.x < pot_c.x - 0.1 ? 0 : c.x > pot_c.x + 0.1 ? 1 : 2];
    const Vec3 n = normalized(Vec3{rng.normal() * 0.3 + (c.x - pot_c.x) * 0.8, -1, 0.3 + rng.normal() * 0.3});
    Vec3 out = c - top;
    out = out - n * dot(out, n);
    const Vec3 along = normalized(out), across = cross(n, along);
    const double len = rng.range(0.26, 0.36), wid = len * rng.range(0.75, 0.9);
    const bool slit = rng.uniform() < 0.8;
    const Vec3 green = Vec3{0.09, 0.29, 0.11} * rng.range(0.85, 1.25);
    tube(b, top, c - along * (0.5 * len), 0.006, 0.005, int(120 * d) + 30, 0.004 * sz, stalk_rgb, monstera);
    for (int i = 0, m = int(len * wid * d / 1.3e-4) + 40; i < m; ++i) {
      const double u = rng.range(-1, 1), v = rng.range(-1, 1), half = std::sqrt(1 - u * u);
      if (std::abs(v) > half) continue;
      const double a = u * len / 2, t = std::abs(v) * wid / 2;
      if (slit && std::abs(v) > 0.35 * half && std::fmod(a - 0.6 * t + 1, 0.055) < 0.012) continue;  // a slit between veins
      const Vec3 col = t < 0.005 ? Vec3{0.28, 0.46, 0.20} : green + noise(0.02);
      b.splat(c + along * a + across * (v * wid / 2) - n * (0.03 * v * v), n, 0.011 * sz, col, monstera, 0.08);
    }
    const double score = -n.y - std::abs(c.x - pot_c.x) - std::abs(c.z - 0.9) - c.y + pot_c.y;
    if (score > best_leaf) best_leaf = score, leaf_click = c + n * 0.002;
  }
  // The coat stand near the left edge: a 3 cm pole on three splayed feet, six hooks and a knob.
  b.depth_jitter = 0.002;
  b.shape_jitter = 0.2;
  const Vec3 stand_c{-0.7, 0.0, 0}, oak{0.52, 0.36, 0.21};
  const int stand = add_object(demo, "coat_stand", stand_c + Vec3{0, 0, 0.95}, 1.0f);
  tube(b, stand_c + Vec3{0, 0, 0.2}, stand_c + Vec3{0, 0, 1.88}, 0.015, 0.015, int(2000 * d) + 80, 0.006 * sz, oak, stand);
  ellipsoid(b, stand_c + Vec3{0, 0, 1.9}, {0.024, 0.024, 0.03}, 120, 0.006, [&](const Vec3&) { return oak * 0.9; }, stand);
  for (int k = 0; k < 3; ++k) {
    const double a = M_PI / 2 + k * 2 * M_PI / 3;
    tube(b, stand_c + Vec3{0, 0, 0.32}, stand_c + Vec3{0.3 * std::cos(a), 0.3 * std::sin(a), 0.012}, 0.013, 0.01, int(400 * d) + 40,
         0.005 * sz, oak * 0.95, stand);
  }
  for (int k = 0; k < 6; ++k) {
    const double a = M_PI / 6 + k * M_PI / 3, z = k % 2 ? 1.7 : 1.78;
    const Vec3 r{std::cos(a), std::sin(a), 0};
    const Vec3 tip = stand_c + r * 0.11 + Vec3{0, 0, z + 0.06};
    tube(b, stand_c + r * 0.012 + Vec3{0, 0, z}, tip, 0.007, 0.006, 80, 0.004, oak * 0.85, stand);
    ellipsoid(b, tip, {0.011, 0.011, 0.011}, 40, 0.004, [&](const Vec3&) { return oak * 0.8; }, stand);
  }
  // The desk: a light oak top along the wall and a return towards the cameras on its left,
  // white panels (the return's end panel faces the cameras), a monitor, keyboard and papers.
  const int desk = add_object(demo, "desk", {0.9, 1.4, 0.5}, 1.0f);
  const double top_z = 0.75;
  const Vec3 oak_top{0.74, 0.61, 0.45};
  auto top_face = [&](double x0, double x1, double y0, double y1, int n) {
    for (int i = 0; i < n; ++i) {
      const double x = rng.range(x0, x1), y = rng.range(y0, y1);
      const double grain = 0.04 * std::sin(x * 90 + 3 * std::sin(y * 7));
      b.splat({x, y, top_z}, {0, 0, 1}, 0.02 * sz, oak_top + Vec3{1, 0.9, 0.8} * grain + noise(0.015), desk, 0.06);
    }
  };
  top_face(0.2, 1.9, 1.35, wall_y, int(3400 * d));
  top_face(0.2, 0.8, 0.65, 1.35, int(1300 * d));
  for (double x = 0.2; x < 1.9; x += 0.012)  // the tops' front edges
    b.strip({x, x < 0.8 ? 0.65 : 1.35, top_z - 0.015}, {0, -1, 0}, {1, 0, 0}, 0.01, 0.012, white + noise(0.015), desk, 0.04);
  for (double y = 0.65; y < 1.35; y += 0.012)  // the return's right edge
    b.strip({0.8, y, top_z - 0.015}, {1, 0, 0}, {0, 1, 0}, 0.01, 0.012, white + noise(0.015), desk, 0.04);
  for (int i = 0, n = int(2600 * d); i < n; ++i)  // the return's end panel, facing the cameras
    b.splat({rng.range(0.2, 0.8), 0.65, rng.range(0, top_z - 0.03)}, {0, -1, 0}, 0.014 * sz, white + noise(0.015), desk, 0.03);
  for (double z = 0; z < top_z - 0.03; z += 0.012)  // its edge on the right, 2 cm thick
    b.strip({0.8, 0.66, z}, {1, 0, 0}, {0, 0, 1}, 0.01, 0.01, white * 0.97 + noise(0.015), desk, 0.03);
  for (int i = 0, n = int(800 * d); i < n; ++i)  // the left panel's outer face
    b.splat({0.2, rng.range(0.65, wall_y), rng.range(0, top_z - 0.03)}, {-1, 0, 0}, 0.03 * sz, white * 0.95 + noise(0.015), desk, 0.03);
  for (int i = 0, n = int(1500 * d); i < n; ++i)  // its inner face, seen under the desk
    b.splat({0.22, rng.range(0.67, wall_y), rng.range(0, top_z - 0.03)}, {1, 0, 0}, 0.025 * sz, white * 0.85 + noise(0.015), desk, 0.03);
  for (int i = 0, n = int(800 * d); i < n; ++i)  // the right panel's inner face
    b.splat({1.88, rng.range(1.35, wall_y), rng.range(0, top_z - 0.03)}, {-1, 0, 0}, 0.025 * sz, white * 0.85 + noise(0.015), desk, 0.03);
  for (double z = 0; z < top_z - 0.03; z += 0.012)  // its front edge
    b.strip({1.89, 1.35, z}, {0, -1, 0}, {0, 0, 1}, 0.01, 0.01, white + noise(0.015), desk, 0.03);
  for (int i = 0, n = int(900 * d); i < n; ++i) {  // the monitor: black bezel, dark screen
    const double x = rng.range(0.95, 1.5), z = rng.range(0.98, 1.3);
    const bool bezel = x < 0.965 || x > 1.485 || z < 1.0 || z > 1.285;
    b.splat({x, 1.82, z}, {0, -1, 0}, 0.01 * sz, bezel ? Vec3{0.06, 0.06, 0.07} : Vec3{0.10, 0.12, 0.16} + noise(0.01), -1, 0.1);
  }
  tube(b, {1.225, 1.86, top_z}, {1.225, 1.86, 0.99}, 0.02, 0.02, 150, 0.006, {0.15, 0.15, 0.16}, -1);
  cuboid(b, {1.225, 1.84, top_z + 0.005}, {0.11, 0.08, 0.005}, 200, 0.008, [&](const Vec3&, const Vec3&) { return Vec3{0.15, 0.15, 0.16}; },
         -1);
  cuboid(b, {1.25, 1.53, top_z + 0.011}, {0.22, 0.07, 0.011}, int(700 * d), 0.007 * sz,
         [&](const Vec3& p, const Vec3& n) {
           const bool key = n.z > 0.5 && std::fmod(p.x + 10, 0.019) > 0.004 && std::fmod(p.y + 10, 0.019) > 0.004;
           return key ? Vec3{0.85, 0.85, 0.84} : Vec3{0.55, 0.56, 0.58};
         },
         -1);
  cuboid(b, {0.48, 1.0, top_z + 0.012}, {0.105, 0.15, 0.012}, int(600 * d), 0.01 * sz,
         [&](const Vec3&, const Vec3& n) { return n.z > 0.5 ? Vec3{0.95, 0.95, 0.93} : Vec3{0.85, 0.85, 0.82}; }, -1);
  // The desk lamp at the back left: a round base, twin-rod arms, a teal conical shade.
  b.depth_jitter = 0.0015;
  b.shape_jitter = 0.2;
  const Vec3 lamp_base{0.42, 1.78, top_z};
  const Vec3 elbow = lamp_base + Vec3{0.04, 0.05, 0.40}, head = lamp_base + Vec3{0.26, -0.12, 0.5};
  const Vec3 shade_dir = normalized(Vec3{0.35, -0.25, -1});
  const int lamp = add_object(demo, "desk_lamp", lamp_base + Vec3{0.12, -0.05, 0.3}, 0.35f);
  const Vec3 lamp_black{0.10, 0.10, 0.11}, teal{0.10, 0.40, 0.38};
  cylinder(b, lamp_base, 0.075, 0.068, 0.03, int(500 * d) + 50, 0.007 * sz, lamp_black, lamp, true);
  tube(b, lamp_base + Vec3{0, 0, 0.03}, lamp_base + Vec3{0, 0, 0.07}, 0.014, 0.012, 60, 0.005, lamp_black, lamp);
  const Vec3 side = normalized(cross(elbow - lamp_base, head - elbow));
  for (double off : {-0.012, 0.012}) {
    tube(b, lamp_base + Vec3{0, 0, 0.07} + side * off, elbow + side * off, 0.005, 0.005, int(180 * d) + 30, 0.003 * sz, lamp_black, lamp);
    tube(b, elbow + side * off, head + side * off, 0.005, 0.005, int(180 * d) + 30, 0.003 * sz, lamp_black, lamp);
  }
  tube(b, lamp_base + Vec3{0.015, 0, 0.1}, lamp_base + Vec3{0.03, 0.03, 0.26}, 0.007, 0.007, 60, 0.003, {0.6, 0.6, 0.62}, lamp);  // spring
  ellipsoid(b, elbow, {0.016, 0.016, 0.016}, 60, 0.005, [&](const Vec3&) { return lamp_black; }, lamp);
  ellipsoid(b, head, {0.034, 0.034, 0.034}, 120, 0.006, [&](const Vec3&) { return teal * 0.9; }, lamp);
  tube(b, head, head + shade_dir * 0.17, 0.03, 0.09, int(1400 * d) + 100, 0.007 * sz, teal, lamp);
  for (int i = 0; i < 100; ++i) {  // the bulb's glow inside the mouth
    const Vec3 u = normalized(cross(shade_dir, Vec3{1, 0, 0})), v = cross(shade_dir, u);
    const double r = 0.075 * std::sqrt(rng.uniform()), a = rng.range(0, 2 * M_PI);
    b.splat(head + shade_dir * 0.15 + u * (r * std::cos(a)) + v * (r * std::sin(a)), shade_dir, 0.008, {0.98, 0.94, 0.78}, lamp, 0.02);
  }
  const Vec3 shade_mid = head + shade_dir * 0.085;
  const Vec3 toward = normalized(Vec3{0, -1, 0} - shade_dir * dot(Vec3{0, -1, 0}, shade_dir));
  // A stapler on the desk: black base and hinge, red arm.
  const Vec3 stapler_c{0.85, 1.5, top_z};
  const int stapler = add_object(demo, "stapler", stapler_c + Vec3{0, 0, 0.02}, 0.09f);
  const Vec3 red{0.72, 0.10, 0.10}, black{0.07, 0.07, 0.08};
  cuboid(b, stapler_c + Vec3{0, 0, 0.004}, {0.075, 0.018, 0.004}, int(200 * d) + 40, 0.004 * sz,
         [&](const Vec3&, const Vec3&) { return black; }, stapler);
  cuboid(b, stapler_c + Vec3{0.005, 0, 0.025}, {0.07, 0.016, 0.014}, int(700 * d) + 100, 0.0045 * sz,
         [&](const Vec3& p, const Vec3&) { return p.x > 0.06 ? Vec3{0.6, 0.6, 0.62} : red; }, stapler);
  cuboid(b, stapler_c + Vec3{-0.068, 0, 0.018}, {0.01, 0.017, 0.018}, 80, 0.004, [&](const Vec3&, const Vec3&) { return black; },
         stapler);
  // The waste-paper bin on the floor, tucked beside the return behind its end panel: blue
  // plastic, a darker inside, two balls of paper.
  const Vec3 bin_c{0.85, 1.1, 0};
  const int bin = add_object(demo, "bin", bin_c + Vec3{0, 0, 0.16}, 0.2f);
  const Vec3 blue{0.22, 0.36, 0.52};
  cylinder(b, bin_c, 0.12, 0.14, 0.32, int(1600 * d), 0.011 * sz, blue, bin, false);
  cylinder(b, bin_c + Vec3{0, 0, 0.3}, 0.143, 0.143, 0.02, int(300 * d), 0.007 * sz, blue * 0.8, bin, false);
  cylinder(b, bin_c + Vec3{0, 0, 0.01}, 0.112, 0.132, 0.31, int(900 * d), 0.011 * sz, blue * 0.55, bin, false);
  for (const Vec3& at : {bin_c + Vec3{-0.03, 0.02, 0.28}, bin_c + Vec3{0.05, -0.03, 0.29}})
    ellipsoid(b, at, {0.04, 0.038, 0.035}, int(200 * d) + 40, 0.008 * sz, [&](const Vec3&) { return Vec3{0.92, 0.92, 0.88} + noise(0.04); },
              bin);
  const double bin_a = -80 * M_PI / 180, bin_r = 0.12 + 0.02 * 0.2 / 0.32;
  // The office chair in front of the desk: five spokes on castors, a post, a seat, armrests,
  // a mesh back (a black frame round a grid of thin strands).
  const Vec3 chair_c{1.35, 0.95, 0};
  const int chair = add_object(demo, "chair", chair_c + Vec3{0, -0.05, 0.55}, 0.6f);
  const Vec3 fabric{0.20, 0.20, 0.22}, mesh_rgb{0.13, 0.13, 0.15};
  auto solid = [&](const Vec3& c) { return [c](const Vec3&) { return c; }; };
  for (int k = 0; k < 5; ++k) {
    const double a = M_PI / 2 + k * 2 * M_PI / 5;
    const Vec3 r{std::cos(a), std::sin(a), 0};
    tube(b, chair_c + Vec3{0, 0, 0.1}, chair_c + r * 0.3 + Vec3{0, 0, 0.07}, 0.02, 0.014, int(250 * d) + 40, 0.006 * sz, black, chair);
    tube(b, chair_c + r * 0.3 + Vec3{0, 0, 0.07}, chair_c + r * 0.3 + Vec3{0, 0, 0.045}, 0.01, 0.01, 30, 0.004, black, chair);
    ellipsoid(b, chair_c + r * 0.3 + Vec3{0, 0, 0.028}, {0.025, 0.025, 0.028}, 120, 0.006, solid(black * 1.4), chair);
  }
  tube(b, chair_c + Vec3{0, 0, 0.08}, chair_c + Vec3{0, 0, 0.25}, 0.035, 0.032, int(250 * d) + 40, 0.008 * sz, black, chair);
  tube(b, chair_c + Vec3{0, 0, 0.25}, chair_c + Vec3{0, 0, 0.43}, 0.022, 0.022, int(200 * d) + 40, 0.006 * sz, {0.45, 0.45, 0.47}, chair);
  cuboid(b, chair_c + Vec3{0, 0.02, 0.425}, {0.1, 0.1, 0.015}, 200, 0.01, [&](const Vec3&, const Vec3&) { return black; }, chair);
  ellipsoid(b, chair_c + Vec3{0, 0.02, 0.475}, {0.25, 0.24, 0.045}, int(2500 * d), 0.011 * sz,
            [&](const Vec3&) { return fabric + noise(0.02); }, chair);
  for (double sd : {-1.0, 1.0}) {  // armrests
    tube(b, chair_c + Vec3{sd * 0.1, 0.0, 0.43}, chair_c + Vec3{sd * 0.25, 0.0, 0.44}, 0.012, 0.012, 60, 0.005, black, chair);
    tube(b, chair_c + Vec3{sd * 0.25, 0.0, 0.44}, chair_c + Vec3{sd * 0.26, -0.02, 0.66}, 0.015, 0.015, int(150 * d) + 30, 0.005 * sz, black,
         chair);
    ellipsoid(b, chair_c + Vec3{sd * 0.26, -0.02, 0.675}, {0.035, 0.12, 0.015}, int(300 * d) + 40, 0.007 * sz, solid(black * 1.5), chair);
  }
  const Vec3 back_c = chair_c + Vec3{0, -0.22, 0.86}, up = normalized(Vec3{0, -0.12, 1}), across_x{1, 0, 0};
  const Vec3 back_n = cross(across_x, up);  // towards the cameras, a little down
  tube(b, chair_c + Vec3{0, -0.05, 0.42}, chair_c + Vec3{0, -0.23, 0.45}, 0.018, 0.018, 80, 0.006, black, chair);  // the back's support
  tube(b, chair_c + Vec3{0, -0.23, 0.45}, back_c - up * 0.25, 0.018, 0.018, 80, 0.006, black, chair);
  const double hw = 0.23, hh = 0.26;
  auto rim = [&](double t) {  // the frame: a rounded rectangle (a superellipse)
    const double c = std::cos(t), s_ = std::sin(t);
    return back_c + across_x * (hw * (c < 0 ? -1 : 1) * std::pow(std::abs(c), 1 / 3.0)) + up * (hh * (s_ < 0 ? -1 : 1) * std::pow(std::abs(s_), 1 / 3.0));
  };
  for (int k = 0; k < 48; ++k)
    tube(b, rim(2 * M_PI * k / 48), rim(2 * M_PI * (k + 1) / 48), 0.012, 0.012, int(40 * d) + 12, 0.005 * sz, black, chair);
  b.depth_jitter = 0.001;
  b.shape_jitter = 0.15;
  auto inside = [&](double x, double v) { return std::pow(std::abs(x / hw), 6) + std::pow(std::abs(v / hh), 6) < 0.9; };
  for (double x = -hw + 0.011; x < hw; x += 0.022)  // vertical strands
    for (double v = -hh; v < hh; v += 0.01)
      if (inside(x, v)) b.strip(back_c + across_x * x + up * v, back_n, up, 0.008, 0.0025, mesh_rgb, chair, 0.02);
  for (double v = -hh + 0.011; v < hh; v += 0.022)  // horizontal strands
    for (double x = -hw; x < hw; x += 0.01)
      if (inside(x, v)) b.strip(back_c + across_x * x + up * v, back_n, across_x, 0.008, 0.0025, mesh_rgb, chair, 0.02);
  // Floaters: faint blobs in the air, more of them around the plant, none by the cameras.
  b.depth_jitter = 0;
  b.shape_jitter = 0;
  for (int i = 0, n = int(170 * d); i < n; ++i) {
    const bool near_plant = i % 4 == 0;
    Vec3 p{rng.range(-1.8, 2.4), rng.range(-0.5, 1.9), rng.range(0.1, 2.4)};
    if (near_plant) {  // around the crown, outside it, not behind it
      Vec3 u;
      do u = {rng.range(-1.6, 1.6), rng.range(-1.8, 0.2), rng.range(-1.4, 1.6)};
      while (dot(u, u) < 1.15 * 1.15 || dot(u, u) > 1.8 * 1.8);
      p = pot_c + Vec3{0, 0, 0.92} + Vec3{u.x * 0.5, u.y * 0.2, u.z * 0.35};
    }
    const Vec3 c = near_plant ? Vec3{0.18, 0.32, 0.16} : paint * rng.range(0.6, 1.05);
    b.floater(p, rng.range(0.02, 0.07) * sz, c, rng.range(0.05, 0.3));
  }
  // The capture: a 5 x 4 grid 4 m from the wall, held by hand.
  const HandHeld hand{47, 0.03, 0.05};
  forward_grid(demo, {0.3, -2.0, 1.15}, {0.2, 0, 0.15}, {0.3, wall_y, 0.45}, {0.07, 0, 0.05}, 64.0, opt, &hand);
  add_task(s, "monstera", "broad leaves with gaps in front of a bookcase", monstera, leaf_click, 7);
  add_task(s, "coat_stand", "thin coat stand at the frame's edge, its top out of view", stand, stand_c + Vec3{0, -0.015, 1.0}, 6);
  add_task(s, "bin", "bin partly behind a desk's side panel, the clicked point hidden in some views", bin,
           bin_c + Vec3{bin_r * std::cos(bin_a), bin_r * std::sin(bin_a), 0.2}, 9);
  add_task(s, "desk_lamp", "desk lamp: a shade on thin arms, clicked on the shade", lamp, shade_mid + toward * 0.062, 12);
  add_task(s, "stapler", "tiny object on a desk", stapler, stapler_c + Vec3{0, -0.017, 0.025}, 7);
  add_task(s, "chair", "office chair with a mesh back", chair, back_c - across_x * hw + up * 0.05 + back_n * 0.012, 7);
  add_task(s, "globe", "a globe on a shelf among books", globe, globe_c + normalized(Vec3{0, -1, 0.2}) * 0.1, 12);
  return std::move(s);
}

// A garage filmed by hand on a half orbit in front of its back wall (22 cameras on an arc of
// 120 degrees, alternately lower and higher, every third nearer, each a little off its path
// and its aim), with jittered Gaussians, coarse walls and faint floaters, built as a held-out
// check by a session that had not seen the segmentation method or its tuning: an extension
// ladder of yellow stiles and aluminium rungs leaning on the block wall, which shows between
// the rungs; a blue gas bottle standing behind two stacked cardboard boxes, the clicked point
// hidden from the right of the arc; a traffic cone inside a storage cage of welded mesh, seen
// through it; a fishing rod leaning on the side wall near the frame's right edge in the views
// from the left (out of the others), its tip above the frame; a wheelbarrow (green tub, wheel,
// frame, wooden grips) clicked on its tub (the truth is all of it); a spray can on a steel
// shelf; and the middle one of three stacked tyres.
EvalScene garage(const EvalSetOptions& opt) {
  SceneStart start("garage", 157);
  auto& [s, demo, g, rng, b] = start;
  const double d = opt.density, sz = 1 / std::sqrt(d);
  const double wall_y = 2.4, side_x = 3.6, front_y = -1.6, room_h = 3.6;
  auto noise = [&](double a) { return Vec3{1, 1, 1} * (a * rng.normal()); };
  // The room: painted concrete blocks (a darker grey dado), a block wall with a window at the
  // left, a white sectional door at the right, a sealed concrete floor; coarse, loose Gaussians.
  b.depth_jitter = 0.006;
  b.shape_jitter = 0.3;
  auto blocks = [&](double u, double z) {
    const int row = int(std::floor(z / 0.2)), col = int(std::floor((u + 20 + (row & 1) * 0.2) / 0.4));
    const bool joint = std::fmod(z, 0.2) < 0.012 || std::fmod(u + 20 + (row & 1) * 0.2, 0.4) < 0.012;
    Vec3 c = (z < 1.1 ? Vec3{0.50, 0.53, 0.56} : Vec3{0.82, 0.81, 0.77}) + Vec3{1, 1, 1} * (0.05 * cell_noise(col, row));
    if (std::abs(z - 1.1) < 0.012) c = {0.30, 0.32, 0.34};  // the dado's edge
    return (joint ? c * 0.86 : c) + noise(0.02);
  };
  back_wall(b, side_x, wall_y, room_h, int(15000 * d), 0.045 * sz, 0.02, {}, blocks);  // up past every view
  b.size_scale = 1.5;  // the side walls and the floor only as far forward as any camera sees
  for (int i = 0, n = int(4000 * d); i < n; ++i) {  // the left wall, a window in it
    const Vec3 p{-side_x, rng.range(front_y, wall_y), rng.range(0, room_h)};
    Vec3 c = blocks(p.y, p.z);
    if (p.y > -1.2 && p.y < 0.2 && p.z > 1.15 && p.z < 2.1) {
      const bool frame = p.y < -1.15 || p.y > 0.15 || p.z < 1.2 || p.z > 2.05 || std::abs(p.y + 0.5) < 0.02;
      c = frame ? Vec3{0.93, 0.93, 0.91} : Vec3{0.72, 0.82, 0.92} + Vec3{1, 1, 1} * (0.06 * (p.z - 1.6));
    }
    b.splat(p, {1, 0, 0}, 0.05 * sz, c, -1, 0.02);
  }
  for (int i = 0, n = int(4000 * d); i < n; ++i) {  // the right wall: a sectional door, 50 cm panels
    const Vec3 p{side_x, rng.range(front_y, wall_y), rng.range(0, room_h)};
    Vec3 c = blocks(p.y, p.z);
    if (p.y > -2.7 && p.y < 0.5 && p.z < 2.2) {
      const bool groove = std::fmod(p.z, 0.52) < 0.02 || std::fmod(p.y + 2.7, 0.8) < 0.012;
      c = (groove ? Vec3{0.70, 0.71, 0.72} : Vec3{0.92, 0.92, 0.90}) + noise(0.015);
    }
    b.splat(p, {-1, 0, 0}, 0.05 * sz, c, -1, 0.03);
  }
  b.size_scale = 1.25;
  b.depth_jitter = 0.004;
  for (int i = 0, n = int(9000 * d); i < n; ++i) {  // the floor: grey sealed concrete, joints, an oil stain
    const Vec3 p{rng.range(-side_x, side_x), rng.range(front_y - 0.2, wall_y), 0};
    const bool joint = std::fmod(p.x + 20, 2.4) < 0.01 || std::fmod(p.y + 20, 2.4) < 0.01;
    Vec3 c = Vec3{0.52, 0.52, 0.50} + Vec3{1, 1, 1} * (0.05 * cell_noise(int((p.x + 20) / 0.7), int((p.y + 20) / 0.7)));
    const double oil = std::hypot((p.x - 0.9) / 0.45, (p.y + 0.4) / 0.3);
    if (oil < 1) c = c * (0.55 + 0.3 * oil);
    b.splat(p, {0, 0, 1}, 0.05 * sz, (joint ? c * 0.6 : c) + noise(0.02), -1, 0.04);
  }
  b.size_scale = 1.0;
  // On the back wall: a grey fuse box and a coiled green garden hose on a bracket.
  b.depth_jitter = 0.002;
  b.shape_jitter = 0.2;
  cuboid(b, {-0.35, wall_y - 0.06, 1.65}, {0.16, 0.06, 0.2}, int(900 * d), 0.014 * sz,
         [&](const Vec3& p, const Vec3& n) { return (n.y < -0.5 && std::abs(p.x) < 0.1 && std::abs(p.z) < 0.14 ? Vec3{0.62, 0.63, 0.64} : Vec3{0.70, 0.71, 0.72}) + noise(0.015); },
         -1);
  const Vec3 hose_c{-1.75, wall_y - 0.08, 1.45};
  tube(b, hose_c + Vec3{0, 0.07, 0.16}, hose_c + Vec3{0, -0.06, 0.16}, 0.015, 0.015, 80, 0.006, {0.2, 0.2, 0.22}, -1);
  for (int loop = 0; loop < 6; ++loop) {
    const double R = 0.17 + 0.012 * loop, off = -0.035 + 0.014 * loop;
    for (int i = 0, n = int(420 * d); i < n; ++i) {
      const double a = rng.range(0, 2 * M_PI), t = rng.range(0, 2 * M_PI);
      const Vec3 radial{std::cos(a), 0, std::sin(a)};
      const Vec3 nrm = radial * std::cos(t) + Vec3{0, -std::sin(t), 0};
      b.splat(hose_c + radial * R + Vec3{0, off, -0.04 * (1 - std::sin(a)) * 0.5} + nrm * 0.012, nrm, 0.006 * sz,
              Vec3{0.20, 0.52, 0.24} + noise(0.02), -1, 0.05);
    }
  }
  // A steel shelving unit against the back wall at the left: blue-grey angle posts,
  // galvanised shelves, plastic bins, tins, and a spray can.
  const double sh_x0 = -3.15, sh_x1 = -2.05, sh_y0 = 1.93, sh_y1 = wall_y - 0.02;
  const double shelf_z[] = {0.12, 0.55, 1.0, 1.45, 1.85};
  const Vec3 post_rgb{0.32, 0.38, 0.46}, galv{0.64, 0.65, 0.66};
  for (double x : {sh_x0, sh_x1})
    for (double y : {sh_y0, sh_y1})
      for (int i = 0, n = int(500 * d); i < n; ++i) {  // an angle post: two 3.5 cm faces
        const bool across = rng.uniform() < 0.5;
        const double z = rng.range(0, 1.9), w = rng.range(0, 0.035);
        const double sx = x < -2.6 ? 1 : -1, sy = y < 2.1 ? 1 : -1;
        if (across) b.splat({x + sx * w, y, z}, {0, -1, 0}, 0.008 * sz, post_rgb + noise(0.02), -1, 0.05);
        else b.splat({x, y + sy * w, z}, {x < -2.6 ? -1.0 : 1.0, 0, 0}, 0.008 * sz, post_rgb + noise(0.02), -1, 0.05);
      }
  for (double z : shelf_z) {
    quad(b, {sh_x0, sh_y0, z}, {sh_x1, sh_y0, z}, {sh_x1, sh_y1, z}, {sh_x0, sh_y1, z}, {0, 0, 1}, int(700 * d), 0.016 * sz,
         [&](double, double) { return galv + noise(0.02); }, -1, 0.06);
    quad(b, {sh_x0, sh_y0, z - 0.035}, {sh_x1, sh_y0, z - 0.035}, {sh_x1, sh_y0, z}, {sh_x0, sh_y0, z}, {0, -1, 0}, int(260 * d), 0.008 * sz,
         [&](double, double) { return galv * 0.9 + noise(0.02); }, -1, 0.06);
  }
  const Vec3 bin_rgb[] = {{0.18, 0.36, 0.62}, {0.85, 0.72, 0.18}, {0.30, 0.30, 0.32}, {0.18, 0.36, 0.62}, {0.86, 0.86, 0.83}};
  const struct { double x, hx, hz; int shelf, colour; } bins[] = {
      {-2.85, 0.25, 0.15, 0, 0}, {-2.33, 0.24, 0.15, 0, 3}, {-2.9, 0.2, 0.12, 1, 1}, {-2.95, 0.16, 0.1, 2, 2}, {-2.75, 0.3, 0.13, 3, 4},
      {-2.3, 0.2, 0.09, 3, 2}, {-2.6, 0.45, 0.14, 4, 0}};
  for (const auto& bn : bins) {
    const Vec3 col = bin_rgb[bn.colour];
    cuboid(b, {bn.x, (sh_y0 + sh_y1) / 2, shelf_z[bn.shelf] + bn.hz}, {bn.hx, 0.2, bn.hz}, int(1400 * bn.hx * d) + 80, 0.014 * sz,
           [&](const Vec3& p, const Vec3& n) { return (n.z > 0.5 ? col * 0.85 : std::abs(p.z - bn.hz) < 0.02 ? col * 1.12 : col) + noise(0.02); },
           -1);
  }
  for (int k = 0; k < 3; ++k)  // paint tins on the second shelf
    cylinder(b, {-2.55 + 0.2 * k, 2.1, shelf_z[1]}, 0.085, 0.085, 0.19, int(450 * d), 0.011 * sz,
             k == 1 ? Vec3{0.90, 0.90, 0.88} : Vec3{0.75, 0.76, 0.78}, -1, true, 0.095);
  // The spray can, on the third shelf near its front: red with a white band, a white cap.
  b.depth_jitter = 0.001;
  b.shape_jitter = 0.15;
  const Vec3 can_c{-2.48, 2.04, shelf_z[2]};
  const int can = add_object(demo, "spray_can", can_c + Vec3{0, 0, 0.1}, 0.1f);
  for (int i = 0, n = int(700 * d) + 80; i < n; ++i) {
    const double a = rng.range(0, 2 * M_PI), z = rng.range(0, 0.16);
    const Vec3 radial{std::cos(a), std::sin(a), 0};
    const bool band = z > 0.06 && z < 0.1;
    b.splat(can_c + radial * 0.033 + Vec3{0, 0, z}, radial, 0.0045 * sz, (band ? Vec3{0.92, 0.92, 0.90} : Vec3{0.80, 0.12, 0.10}) + noise(0.02),
            can, 0.1);
  }
  cylinder(b, can_c + Vec3{0, 0, 0.16}, 0.033, 0.022, 0.02, 120, 0.004, {0.78, 0.78, 0.80}, can, false);
  cylinder(b, can_c + Vec3{0, 0, 0.175}, 0.027, 0.027, 0.045, int(200 * d) + 40, 0.004 * sz, {0.93, 0.93, 0.92}, can, true);
  // Two cardboard boxes stacked on the floor, a blue gas bottle behind them, to their left.
  b.depth_jitter = 0.002;
  b.shape_jitter = 0.25;
  const Vec3 cardboard{0.64, 0.48, 0.30};
  auto carton = [&](double hz) {
    return [&, hz](const Vec3& p, const Vec3& n) {
      if (n.z > 0.5 && std::abs(p.x) < 0.03) return Vec3{0.74, 0.64, 0.44} + noise(0.015);  // tape along the top
      if (n.z < 0.5 && std::abs(p.z - hz) < 0.025 && std::abs(p.x) < 0.03) return Vec3{0.74, 0.64, 0.44} + noise(0.015);
      return cardboard * (n.z > 0.5 ? 1.05 : 0.95) + noise(0.025);
    };
  };
  cuboid(b, {-0.62, 1.5, 0.18}, {0.27, 0.21, 0.18}, int(3000 * d), 0.015 * sz, carton(0.18), -1);
  cuboid(b, {-0.6, 1.52, 0.36 + 0.15}, {0.22, 0.18, 0.15}, int(2200 * d), 0.015 * sz, carton(0.15), -1);
  const Vec3 tank_c{-1.02, 2.0, 0};
  const int tank = add_object(demo, "gas_bottle", tank_c + Vec3{0, 0, 0.35}, 0.3f);
  const Vec3 tank_blue{0.16, 0.30, 0.62};
  const double tank_r = 0.155;
  for (int i = 0, n = int(2600 * d); i < n; ++i) {  // the body, a white label on its front
    const double a = rng.range(0, 2 * M_PI), z = rng.range(0.06, 0.5);
    const Vec3 radial{std::cos(a), std::sin(a), 0};
    const bool label = std::abs(a + M_PI / 2 + 0.3) < 0.5 && z > 0.2 && z < 0.34;
    b.splat(tank_c + radial * tank_r + Vec3{0, 0, z}, radial, 0.011 * sz, (label ? Vec3{0.93, 0.92, 0.88} : tank_blue) + noise(0.02), tank,
            0.08);
  }
  for (double sign : {-1.0, 1.0})  // the domed top and bottom
    for (int i = 0, n = int(600 * d); i < n; ++i) {
      const double a = rng.range(0, 2 * M_PI), e = std::acos(rng.uniform());
      const Vec3 u{std::sin(e) * std::cos(a), std::sin(e) * std::sin(a), sign * std::cos(e)};
      const Vec3 p{u.x * tank_r, u.y * tank_r, u.z * 0.07};
      b.splat(tank_c + Vec3{0, 0, sign > 0 ? 0.5 : 0.06} + p, normalized(Vec3{u.x / tank_r, u.y / tank_r, u.z / 0.07}), 0.01 * sz,
              tank_blue + noise(0.02), tank, 0.08);
    }
  cylinder(b, tank_c, 0.13, 0.13, 0.04, int(300 * d), 0.008 * sz, tank_blue * 0.7, tank, false);  // the foot ring
  cylinder(b, tank_c + Vec3{0, 0, 0.55}, 0.085, 0.085, 0.12, int(500 * d), 0.008 * sz, tank_blue * 0.9, tank, false);  // the collar
  cylinder(b, tank_c + Vec3{0, 0, 0.56}, 0.02, 0.02, 0.08, 80, 0.005, {0.72, 0.60, 0.30}, tank, true);  // the valve
  // The extension ladder leaning on the wall: yellow fibreglass stiles 6.5 x 2.5 cm, round
  // aluminium rungs every 28 cm, black rubber feet.
  b.depth_jitter = 0.0015;
  b.shape_jitter = 0.2;
  const Vec3 foot{0.0, 1.78, 0.0}, top_at{0.0, wall_y - 0.035, 2.4};
  const Vec3 rail = normalized(top_at - foot), ex{1, 0, 0}, face = normalized(cross(rail, ex));  // face: towards the cameras
  const double rail_len = norm(top_at - foot), lad_x0 = 0.22, lad_x1 = 0.66;
  const int ladder = add_object(demo, "ladder", Vec3{(lad_x0 + lad_x1) / 2, 0, 0} + (foot + top_at) * 0.5, 1.3f);
  const Vec3 fibreglass{0.92, 0.70, 0.12}, alu{0.74, 0.75, 0.77};
  for (double x : {lad_x0, lad_x1}) {
    const Vec3 base = foot + Vec3{x, 0, 0};
    for (int i = 0, n = int(1700 * d); i < n; ++i) {
      const double t = rng.range(0, rail_len), pick = rng.uniform();
      Vec3 p, nrm;
      if (pick < 0.35) p = face * 0.0325 + ex * rng.range(-0.0125, 0.0125), nrm = face;
      else if (pick < 0.5) p = face * -0.0325 + ex * rng.range(-0.0125, 0.0125), nrm = -face;
      else {
        const double sd = pick < 0.75 ? -1 : 1;
        p = ex * (0.0125 * sd) + face * rng.range(-0.0325, 0.0325), nrm = ex * sd;
      }
      const Vec3 c = t < 0.06 ? Vec3{0.08, 0.08, 0.08} : fibreglass * (nrm.x != 0 ? 0.9 : 1.0);
      b.splat(base + rail * t + p, nrm, 0.008 * sz, c + noise(0.02), ladder, 0.05);
    }
  }
  for (double t = 0.3; t < rail_len - 0.05; t += 0.28)
    tube(b, foot + rail * t + Vec3{lad_x0 + 0.0125, 0, 0}, foot + rail * t + Vec3{lad_x1 - 0.0125, 0, 0}, 0.016, 0.016, int(260 * d) + 40,
         0.006 * sz, alu, ladder);
  // A storage cage against the wall at the right: welded mesh (6 mm wires, 10 cm squares) on
  // a frame of square tube, front and sides; a traffic cone stands inside it.
  const double cage_x0 = 1.05, cage_x1 = 2.35, cage_y = 1.4, cage_h = 1.55;
  const Vec3 mesh_rgb{0.22, 0.23, 0.25};
  b.depth_jitter = 0.001;
  b.shape_jitter = 0.15;
  for (int side = 0; side < 3; ++side) {  // 0 the front, 1 the left side, 2 the right side
    const Vec3 a = side == 2 ? Vec3{cage_x1, cage_y, 0} : Vec3{cage_x0, cage_y, 0};
    const Vec3 e = side == 0 ? Vec3{cage_x1, cage_y, 0} : side == 1 ? Vec3{cage_x0, wall_y - 0.02, 0} : Vec3{cage_x1, wall_y - 0.02, 0};
    const Vec3 along = normalized(e - a), nrm = side == 0 ? Vec3{0, -1, 0} : side == 1 ? Vec3{-1, 0, 0} : Vec3{1, 0, 0};
    const double len = norm(e - a);
    for (double u = 0.1; u < len - 0.02; u += 0.1)
      for (double z = 0.03; z < cage_h; z += 0.011)
        b.strip(a + along * u + Vec3{0, 0, z}, nrm, {0, 0, 1}, 0.008, 0.003, mesh_rgb + noise(0.02), -1, 0.04);
    for (double z = 0.1; z < cage_h - 0.02; z += 0.1)
      for (double u = 0.01; u < len; u += 0.011)
        b.strip(a + along * u + Vec3{0, 0, z} - nrm * 0.004, nrm, along, 0.008, 0.003, mesh_rgb + noise(0.02), -1, 0.04);
    for (double z : {0.02, cage_h})  // the frame's rails
      tube(b, a + Vec3{0, 0, z}, e + Vec3{0, 0, z}, 0.015, 0.015, int(300 * len * d) + 30, 0.006 * sz, mesh_rgb * 1.2, -1);
  }
  for (const Vec3& c : {Vec3{cage_x0, cage_y, 0}, Vec3{cage_x1, cage_y, 0}, Vec3{cage_x0, wall_y - 0.03, 0}, Vec3{cage_x1, wall_y - 0.03, 0}})
    tube(b, c, c + Vec3{0, 0, cage_h}, 0.018, 0.018, int(350 * d) + 30, 0.006 * sz, mesh_rgb * 1.2, -1);
  b.depth_jitter = 0.0015;
  b.shape_jitter = 0.2;
  const Vec3 cone_c{1.72, 1.98, 0};
  const int cone = add_object(demo, "traffic_cone", cone_c + Vec3{0, 0, 0.3}, 0.3f);
  cuboid(b, cone_c + Vec3{0, 0, 0.015}, {0.18, 0.18, 0.015}, int(700 * d), 0.011 * sz, one_colour(Vec3{0.08, 0.08, 0.09}), cone);
  for (int i = 0, n = int(2600 * d); i < n; ++i) {
    const double a = rng.range(0, 2 * M_PI), t = std::sqrt(rng.uniform());  // more where it is wider
    const double z = 0.03 + 0.67 * (1 - t), r = 0.025 + 0.115 * t;
    const Vec3 nrm = normalized(Vec3{std::cos(a), std::sin(a), 0.115 / 0.67});
    const bool band = (z > 0.3 && z < 0.4) || (z > 0.48 && z < 0.54);
    b.splat(cone_c + Vec3{r * std::cos(a), r * std::sin(a), z}, nrm, 0.01 * sz,
            (band ? Vec3{0.93, 0.93, 0.92} : Vec3{0.96, 0.42, 0.08}) + noise(0.02), cone, band ? 0.12 : 0.04);
  }
  // A fishing rod leaning on the right wall beside the door: a cork grip, a reel under it, a
  // dark blank tapering to its tip above every view, the line's guides.
  const Vec3 rod_foot{side_x - 0.3, 0.95, 0.0}, rod_top{side_x - 0.015, 0.9, 2.95};
  const Vec3 rod = normalized(rod_top - rod_foot);
  const double rod_len = norm(rod_top - rod_foot);
  const int fishing_rod = add_object(demo, "fishing_rod", rod_foot + rod * (rod_len / 2), 1.5f);
  tube(b, rod_foot, rod_foot + rod * 0.03, 0.02, 0.02, 60, 0.005, {0.1, 0.1, 0.1}, fishing_rod);
  tube(b, rod_foot + rod * 0.03, rod_foot + rod * 0.5, 0.018, 0.016, int(600 * d) + 60, 0.005 * sz, {0.74, 0.58, 0.40}, fishing_rod);
  tube(b, rod_foot + rod * 0.5, rod_top, 0.011, 0.004, int(1600 * d) + 100, 0.004 * sz, {0.12, 0.16, 0.14}, fishing_rod);
  const Vec3 out = normalized(cross(rod, Vec3{0, 1, 0}));  // off the rod towards the room
  ellipsoid(b, rod_foot + rod * 0.4 + out * 0.055, {0.035, 0.03, 0.03}, 220, 0.005, [&](const Vec3& l) {
    return (l.x > 0.015 ? Vec3{0.75, 0.6, 0.25} : Vec3{0.16, 0.16, 0.18}) + noise(0.02); }, fishing_rod, 0.08);
  tube(b, rod_foot + rod * 0.4, rod_foot + rod * 0.4 + out * 0.03, 0.005, 0.005, 30, 0.003, {0.2, 0.2, 0.2}, fishing_rod);
  for (double t = 0.7; t < rod_len - 0.1; t += 0.35)
    ellipsoid(b, rod_foot + rod * t + out * 0.02, {0.008, 0.008, 0.008}, 30, 0.003, [&](const Vec3&) { return Vec3{0.8, 0.8, 0.82}; },
              fishing_rod, 0.1);
  // The wheelbarrow on the floor, along x: a green tub (its outside, inside and rolled rim),
  // a wheel at the front (a black tyre, a red hub), a frame of black tube to wooden grips, legs.
  b.depth_jitter = 0.0015;
  b.shape_jitter = 0.2;
  const Vec3 wb{0.15, 0.35, 0};
  const int barrow = add_object(demo, "wheelbarrow", wb + Vec3{0, 0, 0.4}, 0.8f);
  const Vec3 tub_out{0.16, 0.46, 0.26}, tub_in{0.13, 0.38, 0.22}, black{0.09, 0.09, 0.10};
  const Vec3 bot[4] = {wb + Vec3{-0.25, -0.18, 0.3}, wb + Vec3{0.2, -0.18, 0.3}, wb + Vec3{0.2, 0.18, 0.3}, wb + Vec3{-0.25, 0.18, 0.3}};
  const Vec3 lip[4] = {wb + Vec3{-0.42, -0.32, 0.62}, wb + Vec3{0.48, -0.32, 0.62}, wb + Vec3{0.48, 0.32, 0.62}, wb + Vec3{-0.42, 0.32, 0.62}};
  const Vec3 tub_mid = wb + Vec3{0, 0, 0.45};
  for (int k = 0; k < 4; ++k) {  // four sloping sides
    const Vec3 &p00 = bot[k], &p10 = bot[(k + 1) % 4], &p11 = lip[(k + 1) % 4], &p01 = lip[k];
    Vec3 n = normalized(cross(p10 - p00, p01 - p00));
    if (dot(n, (p00 + p11) * 0.5 - tub_mid) < 0) n = -n;
    const int count = int(norm(cross(p11 - p00, p01 - p10)) * 0.5 * 4000 * d) + 40;
    quad(b, p00, p10, p11, p01, n, count, 0.014 * sz, [&](double, double) { return tub_out + noise(0.02); }, barrow, 0.08);
    quad(b, p00 - n * 0.006, p10 - n * 0.006, p11 - n * 0.006, p01 - n * 0.006, -n, count, 0.014 * sz,
         [&](double, double v) { return tub_in * (0.85 + 0.15 * v) + noise(0.02); }, barrow, 0.05);
    tube(b, p01, p11, 0.012, 0.012, int(norm(p11 - p01) * 300 * d) + 30, 0.005 * sz, tub_out * 1.15, barrow);
  }
  quad(b, bot[0], bot[1], bot[2], bot[3], {0, 0, -1}, int(500 * d), 0.014 * sz, [&](double, double) { return tub_out * 0.8 + noise(0.02); },
       barrow, 0.05);
  quad(b, bot[0] + Vec3{0, 0, 0.006}, bot[1] + Vec3{0, 0, 0.006}, bot[2] + Vec3{0, 0, 0.006}, bot[3] + Vec3{0, 0, 0.006}, {0, 0, 1},
       int(500 * d), 0.014 * sz, [&](double, double) { return tub_in * 0.8 + noise(0.02); }, barrow, 0.05);
  const Vec3 hub = wb + Vec3{0.66, 0, 0.19};
  for (int i = 0, n = int(1800 * d); i < n; ++i) {  // the tyre: a torus around the axle (y), tread grooves
    const double a = rng.range(0, 2 * M_PI), t = rng.range(0, 2 * M_PI);
    const Vec3 radial{std::cos(a), 0, std::sin(a)};
    const Vec3 nrm = radial * std::cos(t) + Vec3{0, std::sin(t), 0};
    const bool groove = std::cos(t) > 0.6 && std::fmod(a + 2 * M_PI, 0.2) < 0.05;
    b.splat(hub + radial * 0.145 + nrm * 0.045, nrm, 0.009 * sz, (groove ? black * 0.5 : black) + noise(0.015), barrow, 0.03);
  }
  for (double side : {-1.0, 1.0})
    for (int i = 0, n = int(400 * d); i < n; ++i) {  // the hub's faces: a red disc, a grey centre
      const double r = 0.105 * std::sqrt(rng.uniform()), a = rng.range(0, 2 * M_PI);
      b.splat(hub + Vec3{r * std::cos(a), side * 0.03, r * std::sin(a)}, {0, side, 0}, 0.008 * sz,
              (r < 0.025 ? Vec3{0.6, 0.6, 0.62} : Vec3{0.78, 0.14, 0.12}) + noise(0.02), barrow, 0.06);
    }
  for (double side : {-1.0, 1.0}) {
    const Vec3 axle = hub + Vec3{0, side * 0.05, 0}, under = wb + Vec3{-0.3, side * 0.22, 0.28};
    const Vec3 back = wb + Vec3{-0.8, side * 0.28, 0.5}, grip_end = wb + Vec3{-1.05, side * 0.3, 0.56};
    tube(b, axle, under, 0.016, 0.016, int(500 * d) + 40, 0.006 * sz, black, barrow);
    tube(b, under, back, 0.016, 0.016, int(300 * d) + 40, 0.006 * sz, black, barrow);
    tube(b, back, grip_end, 0.02, 0.02, int(200 * d) + 30, 0.006 * sz, {0.58, 0.40, 0.22}, barrow);
    tube(b, wb + Vec3{-0.22, side * 0.2, 0.29}, wb + Vec3{-0.3, side * 0.25, 0.02}, 0.014, 0.014, int(220 * d) + 30, 0.006 * sz, black, barrow);
    cuboid(b, wb + Vec3{-0.3, side * 0.25, 0.01}, {0.04, 0.02, 0.01}, 50, 0.005, one_colour(black), barrow);
  }
  tube(b, hub + Vec3{0, -0.06, 0}, hub + Vec3{0, 0.06, 0}, 0.01, 0.01, 40, 0.004, {0.6, 0.6, 0.62}, barrow);
  tube(b, wb + Vec3{-0.24, -0.2, 0.16}, wb + Vec3{-0.24, 0.2, 0.16}, 0.011, 0.011, int(120 * d) + 20, 0.005 * sz, black, barrow);
  // Three tyres stacked on the floor at the left, the top one a little off.
  b.depth_jitter = 0.002;
  b.shape_jitter = 0.2;
  const Vec3 stack_c{-2.1, 0.85, 0};
  int tyres[3];
  for (int k = 0; k < 3; ++k) {
    const Vec3 c = stack_c + Vec3{k == 2 ? 0.04 : 0.0, k == 2 ? -0.025 : 0.0, 0.1 + 0.2 * k};
    tyres[k] = add_object(demo, k == 0 ? "tyre_bottom" : k == 1 ? "tyre" : "tyre_top", c, 0.33f);
    for (int i = 0, n = int(4200 * d); i < n; ++i) {  // the profile: an ellipse 13 x 20 cm round a 24.5 cm ring
      const double a = rng.range(0, 2 * M_PI), t = rng.range(-M_PI, M_PI);
      const Vec3 radial{std::cos(a), std::sin(a), 0};
      const double ct = std::cos(t), st = std::sin(t);
      const Vec3 p = c + radial * (0.245 + 0.065 * ct) + Vec3{0, 0, 0.1 * st};
      const Vec3 nrm = normalized(radial * (ct / 0.065) + Vec3{0, 0, st / 0.1});
      const bool tread = ct > 0.55, groove = tread && (std::fmod(a * 0.31 + 0.02 * (st > 0 ? 1 : 0) + 10, 0.035) < 0.008 || std::abs(st) < 0.06);
      const bool letters = std::abs(st) > 0.75 && ct > -0.2 && std::fmod(a + 2 * M_PI, 0.09) < 0.05 && std::fmod(a + 2 * M_PI, 1.4) < 0.7;
      const Vec3 col = groove ? Vec3{0.035, 0.035, 0.04} : letters ? Vec3{0.2, 0.2, 0.21} : Vec3{0.10, 0.10, 0.11};
      b.splat(p, nrm, 0.011 * sz, col + noise(0.012), tyres[k], 0.03);
    }
  }
  // Floaters: faint blobs in the air a trainer leaves, none by the cameras (all within 2.4 m
  // of the middle the cameras circle, 3.1 m or more away).
  const Vec3 focus{0.1, 1.25, 0.65};
  b.depth_jitter = 0;
  b.shape_jitter = 0;
  for (int i = 0, n = int(150 * d); i < n; ++i) {
    Vec3 p;
    do p = {rng.range(-3.0, 3.0), rng.range(-0.3, 2.3), rng.range(0.1, 2.6)};
    while (std::hypot(p.x - focus.x, p.y - focus.y) > 2.4);
    b.floater(p, rng.range(0.02, 0.07) * sz, Vec3{0.70, 0.70, 0.66} * rng.range(0.6, 1.1), rng.range(0.05, 0.3));
  }
  // The capture: 22 cameras on an arc of 120 degrees, alternately at 1.3 m and 1.75 m, every
  // third nearer, held by hand (their own random stream: the Gaussians do not move with it).
  SplitMix64 hand(61);
  for (int id = 0; id < 22; ++id) {
    const double a = (-60 + 120.0 * id / 21) * M_PI / 180, r = id % 3 == 1 ? 3.1 : 3.7;
    const Vec3 wobble{hand.range(-0.04, 0.04), hand.range(-0.04, 0.04), hand.range(-0.04, 0.04)};
    const Vec3 aim{hand.range(-0.12, 0.12), hand.range(-0.05, 0.05), hand.range(-0.07, 0.07)};
    const Vec3 eye = Vec3{focus.x + r * std::sin(a), focus.y - r * std::cos(a), id % 2 ? 1.75 : 1.3} + wobble;
    demo.bundle.cameras.push_back(named(Camera::look_at(eye, focus + aim, {0, 0, 1}, opt.width, opt.height, 64.0), id, "arc"));
  }
  add_task(s, "ladder", "a leaning ladder: rungs with gaps that show the block wall", ladder,
           foot + rail * 1.2 + Vec3{lad_x0, 0, 0} + face * 0.033, 6);
  add_task(s, "gas_bottle", "gas bottle behind stacked boxes, the clicked point hidden from the right of the arc", tank,
           tank_c + Vec3{-0.06, -(tank_r + 0.002), 0.42}, 2);
  add_task(s, "traffic_cone", "traffic cone seen through a welded-mesh cage", cone, cone_c + Vec3{0, -0.1, 0.22}, 10, 20);
  add_task(s, "fishing_rod", "thin fishing rod at the frame's edge, its tip above the frame, out of most views", fishing_rod, rod_foot + rod * 0.25 + out * 0.017,
           3);
  add_task(s, "wheelbarrow", "compound object: a wheelbarrow (tub, wheel, frame, grips) clicked on its tub; the truth is all of it", barrow,
           wb + Vec3{0.05, -0.26, 0.46}, 11);
  add_task(s, "spray_can", "tiny spray can on a steel shelf", can, can_c + Vec3{0, -0.034, 0.04}, 16);
  add_task(s, "tyre", "the middle one of three stacked tyres touching each other", tyres[1], stack_c + normalized(Vec3{0.6, -0.8, 0}) * 0.305 + Vec3{0, 0, 0.3}, 15);
  return std::move(s);
}

// A bedroom filmed by hand on a half orbit in front of the bed (24 cameras on an arc of 110
// degrees, alternately lower and higher, every third nearer, each a little off its path and its
// aim), with jittered Gaussians, coarse walls and faint floaters, built as a held-out check by a
// session that had not seen the segmentation method or its tuning: a rattan armchair whose back
// is an open diamond lattice of cane, the wall showing through its gaps; a backpack on the floor
// beside the foot of the bed, the clicked point hidden by the bed from the right of the arc; a
// vase on the window sill seen through a net curtain; the thin iron curtain rod above it near
// the top of the frame, its ends out of some views and the curtain's tabs over it; a phone lying
// on the bedside table; an acoustic guitar leaning on the wall, clicked on its body (the truth is
// all of it); the left one of two pillows touching each other, the headboard and a cushion; and
// a grey cat curled up asleep on a grey rug of nearly its colour.
EvalScene bedroom(const EvalSetOptions& opt) {
  SceneStart start("bedroom", 307);
  auto& [s, demo, g, rng, b] = start;
  const double d = opt.density, sz = 1 / std::sqrt(d);
  const double wall_y = 2.4, side_x = 3.6, front_y = -1.8, room_h = 2.8;
  auto noise = [&](double a) { return Vec3{1, 1, 1} * (a * rng.normal()); };
  // n Gaussians on a rounded box (a superellipsoid, sum over axes of |l|^(2 / e) = 1 with l the
  // point in units of r: e 1 round, smaller squarer) of half sizes r along the axes ax, ay, az
  // around c, facing out, coloured by colour(l). Each is a point on the box's faces (by their
  // area) moved along its ray from c onto the surface, so they cover it evenly.
  auto rounded = [&](const Vec3& c, const Vec3& ax, const Vec3& ay, const Vec3& az, const Vec3& r, const Vec3& e, int n,
                     double size, auto colour, int label, double shine) {
    const double area[3] = {r.y * r.z, r.x * r.z, r.x * r.y};  // the faces across each axis
    for (int i = 0; i < n; ++i) {
      const double pick = rng.uniform() * (area[0] + area[1] + area[2]);
      const int k = pick < area[0] ? 0 : pick < area[0] + area[1] ? 1 : 2;
      Vec3 q{rng.range(-1, 1), rng.range(-1, 1), rng.range(-1, 1)};
      q[k] = rng.uniform() < 0.5 ? -1 : 1;
      double lo = 0, hi = 1;  // the surface's point t q, by bisection
      for (int it = 0; it < 40; ++it) {
        const double t = (lo + hi) / 2;
        double f = 0;
        for (int j = 0; j < 3; ++j) f += std::pow(std::abs(t * q[j]), 2 / e[j]);
        (f < 1 ? lo : hi) = t;
      }
      const Vec3 l = q * lo;
      Vec3 m;  // the gradient's components, in units of r
      for (int j = 0; j < 3; ++j) m[j] = (l[j] < 0 ? -1 : 1) * std::pow(std::abs(l[j]), 2 / e[j] - 1) / (e[j] * r[j]);
      const Vec3 p = c + ax * (l.x * r.x) + ay * (l.y * r.y) + az * (l.z * r.z);
      b.splat(p, normalized(ax * m.x + ay * m.y + az * m.z), size, colour(l), label, shine);
    }
  };
  // Where the bed, the rug, the cat and the backpack stand (no floor or rug under them: a
  // trainer leaves none where no view sees).
  const double bed_x0 = -0.4, bed_x1 = 1.2, bed_y0 = 0.3, bed_y1 = 2.3;
  const double rug_x0 = -0.9, rug_x1 = 1.7, rug_y0 = -0.55, rug_y1 = 0.75, rug_z = 0.015;
  const Vec3 cat_c{0.75, 0.05, rug_z}, pack_c{-0.62, 0.7, rug_z + 0.22};
  // The room: a dusty-blue painted wall, blotchy, a window in it at the left; the side walls (a
  // white door in the right one); oak floor boards; coarse, loose Gaussians.
  b.depth_jitter = 0.006;
  b.shape_jitter = 0.35;
  const Vec3 paint{0.66, 0.71, 0.76}, white{0.92, 0.92, 0.90};
  auto wall_rgb = [&](double u, double z) {
    const double blotch = 0.04 * cell_noise(int(std::floor((u + 20) / 0.45)), int(std::floor(z / 0.45)));
    return paint * (0.94 + 0.025 * z) + Vec3{1, 1, 1} * blotch + noise(0.02);
  };
  const double win_x0 = -2.6, win_x1 = -1.4, win_z0 = 0.95, win_z1 = 2.05;
  back_wall(b, side_x, wall_y, room_h, int(14000 * d), 0.05 * sz, 0.02, {{win_x0, win_x1, win_z0, win_z1}},
            wall_rgb);  // up past every view
  b.size_scale = 1.5;  // the side walls only as far forward as any camera sees
  for (double x : {-side_x, side_x})
    for (int i = 0, n = int(4000 * d); i < n; ++i) {
      const Vec3 p{x, rng.range(front_y, wall_y), rng.range(0, room_h)};
      Vec3 c = wall_rgb(p.y, p.z) * 0.95;
      if (x > 0 && p.y > -1.3 && p.y < -0.4 && p.z < 2.05)  // the door, its edges darker
        c = (p.y < -1.27 || p.y > -0.43 || p.z > 2.02 ? white * 0.8 : white) + noise(0.015);
      b.splat(p, {x < 0 ? 1.0 : -1.0, 0, 0}, 0.05 * sz, c, -1, 0.02);
    }
  b.size_scale = 1.25;
  b.depth_jitter = 0.004;
  for (int i = 0, n = int(10000 * d); i < n; ++i) {  // oak floor boards, 14 cm wide, none under the rug and the bed
    const Vec3 p{rng.range(-side_x, side_x), rng.range(front_y - 0.2, wall_y), 0};
    if ((p.x > rug_x0 && p.x < rug_x1 && p.y > rug_y0 && p.y < rug_y1) || (p.x > bed_x0 && p.x < bed_x1 && p.y > bed_y0)) continue;
    const int board = int(std::floor((p.x + 10) / 0.14));
    const double along = p.y + 10 + 0.61 * board;
    const bool seam = std::fmod(p.x + 10, 0.14) < 0.006 || std::fmod(along, 1.6) < 0.006;
    const Vec3 c = seam ? Vec3{0.30, 0.22, 0.15}
                        : Vec3{0.60, 0.47, 0.34} + Vec3{1, 0.8, 0.6} * (0.12 * cell_noise(board, int(along / 1.6)));
    b.splat(p, {0, 0, 1}, 0.05 * sz, c + noise(0.015), -1, 0.05);
  }
  b.size_scale = 1.0;
  b.depth_jitter = 0.002;
  b.shape_jitter = 0.2;
  for (int i = 0, n = int(900 * d); i < n; ++i)  // white skirting board
    b.strip({rng.range(-side_x, side_x), wall_y - 0.012, rng.range(0, 0.1)}, {0, -1, 0}, {1, 0, 0}, 0.03, 0.02, white + noise(0.02), -1,
            0.04);
  for (int i = 0, n = int(1600 * d); i < n; ++i) {  // the window: white frame and bars, a pale sky over a tree's green
    const double x = rng.range(win_x0, win_x1), z = rng.range(win_z0, win_z1);
    const bool frame = x < win_x0 + 0.05 || x > win_x1 - 0.05 || z < win_z0 + 0.05 || z > win_z1 - 0.05 ||
                       std::abs(x - (win_x0 + win_x1) / 2) < 0.025 || std::abs(z - 1.6) < 0.02;
    const Vec3 view = z < 1.3 + 0.12 * std::sin(x * 9) ? Vec3{0.40, 0.52, 0.34} : Vec3{0.76, 0.84, 0.93};
    b.splat({x, wall_y + (frame ? -0.01 : 0.03), z}, {0, -1, 0}, 0.022 * sz, (frame ? white : view) + noise(0.015), -1,
            frame ? 0.03 : 0.08);
  }
  const double sill_z = win_z0 - 0.02, sill_y = wall_y - 0.22;
  quad(b, {win_x0 - 0.1, sill_y, sill_z}, {win_x1 + 0.1, sill_y, sill_z}, {win_x1 + 0.1, wall_y, sill_z}, {win_x0 - 0.1, wall_y, sill_z},
       {0, 0, 1}, int(500 * d), 0.015 * sz, [&](double, double) { return white + noise(0.015); }, -1, 0.04);  // the sill
  quad(b, {win_x0 - 0.1, sill_y, sill_z - 0.04}, {win_x1 + 0.1, sill_y, sill_z - 0.04}, {win_x1 + 0.1, sill_y, sill_z},
       {win_x0 - 0.1, sill_y, sill_z}, {0, -1, 0}, int(200 * d), 0.01 * sz, [&](double, double) { return white * 0.95 + noise(0.015); },
       -1, 0.04);
  for (int i = 0, n = int(1200 * d); i < n; ++i) {  // a print above the bed, 3 cm off the wall: soft colour fields, a thin black frame
    const double x = rng.range(0.05, 0.75), z = rng.range(1.45, 1.95);
    const bool frame = x < 0.07 || x > 0.73 || z < 1.47 || z > 1.93;
    const Vec3 field = z > 1.72 + 0.05 * std::sin(x * 7) ? Vec3{0.86, 0.62, 0.42} : x < 0.4 ? Vec3{0.30, 0.45, 0.50} : Vec3{0.88, 0.84, 0.74};
    const Vec3 c = frame ? Vec3{0.08, 0.08, 0.08} : field;
    b.splat({x, wall_y - 0.03, z}, {0, -1, 0}, 0.012 * sz, c + noise(0.015), -1, 0.03);
  }
  // A vase on the sill, behind the net curtain: glazed cobalt blue, a white band.
  b.depth_jitter = 0.001;
  b.shape_jitter = 0.15;
  const Vec3 vase_c{-2.05, 2.3, sill_z}, cobalt{0.12, 0.24, 0.62};
  const int vase = add_object(demo, "vase", vase_c + Vec3{0, 0, 0.15}, 0.17f);
  for (int i = 0, n = int(2000 * d) + 100; i < n; ++i) {
    const double a = rng.range(0, 2 * M_PI), z = rng.range(0, 0.3);
    const double r = 0.035 + 0.06 * std::sin(M_PI * z / 0.3), dr = 0.06 * M_PI / 0.3 * std::cos(M_PI * z / 0.3);
    const Vec3 radial{std::cos(a), std::sin(a), 0};
    const bool band = z > 0.2 && z < 0.22;
    b.splat(vase_c + radial * r + Vec3{0, 0, z}, normalized(radial - Vec3{0, 0, dr}), 0.008 * sz,
            (band ? Vec3{0.90, 0.90, 0.88} : cobalt) + noise(0.02), vase, 0.12);
  }
  cylinder(b, vase_c + Vec3{0, 0, 0.295}, 0.037, 0.039, 0.02, 90, 0.005, cobalt * 0.9, vase, false);  // the lip
  // The net curtain, hanging in soft folds from fabric tabs over the rod: white threads in an open
  // 8 cm mesh, a denser hem and heading.
  const double cur_x0 = -2.72, cur_x1 = -1.28, cur_y = 2.1, rod_z = 2.3, cur_z0 = sill_z - 0.06, cur_z1 = rod_z - 0.02;
  auto fold = [&](double x) { return cur_y + 0.015 * std::sin(2 * M_PI * (x - cur_x0) / 0.24); };
  auto fold_n = [&](double x) { return normalized(Vec3{0.015 * 2 * M_PI / 0.24 * std::cos(2 * M_PI * (x - cur_x0) / 0.24), -1, 0}); };
  const Vec3 net{0.93, 0.93, 0.90};
  for (double x = cur_x0; x <= cur_x1 + 1e-9; x += 0.08)  // threads down
    for (double z = cur_z0; z < cur_z1; z += 0.01)
      b.strip({x, fold(x), z}, fold_n(x), {0, 0, 1}, 0.008, 0.002, net + noise(0.02), -1, 0.02);
  for (double z = cur_z0 + 0.05; z < cur_z1; z += 0.08)  // threads across
    for (double x = cur_x0; x <= cur_x1; x += 0.01)
      b.strip({x, fold(x), z}, fold_n(x), {1, 0, 0}, 0.008, 0.002, net + noise(0.02), -1, 0.02);
  for (int i = 0, n = int(800 * d); i < n; ++i) {  // the hem and the heading
    const double x = rng.range(cur_x0, cur_x1), z = i % 2 ? rng.range(cur_z0, cur_z0 + 0.04) : rng.range(cur_z1 - 0.05, cur_z1);
    b.splat({x, fold(x), z}, fold_n(x), 0.008 * sz, net * 0.97 + noise(0.02), -1, 0.02);
  }
  for (double x = cur_x0 + 0.03; x < cur_x1; x += 0.16)  // the tabs, looped over the rod
    for (int i = 0; i < 120; ++i) {
      const double t = rng.range(0, 2 * M_PI);
      const Vec3 r{0, std::cos(t), std::sin(t)};
      b.splat(Vec3{x + rng.range(-0.025, 0.025), cur_y, rod_z} + r * 0.02, r, 0.006, net * 0.97 + noise(0.02), -1, 0.02);
    }
  // The curtain rod: black iron, 2.8 cm thick, ball finials, two brackets from the wall.
  const double rod_x0 = -2.88, rod_x1 = -1.12;
  const int rod = add_object(demo, "curtain_rod", {(rod_x0 + rod_x1) / 2, cur_y, rod_z}, 0.9f);
  const Vec3 iron{0.11, 0.11, 0.12};
  tube(b, {rod_x0, cur_y, rod_z}, {rod_x1, cur_y, rod_z}, 0.014, 0.014, int(2200 * d) + 100, 0.005 * sz, iron, rod);
  for (double x : {rod_x0 - 0.03, rod_x1 + 0.03})
    ellipsoid(b, {x, cur_y, rod_z}, {0.035, 0.035, 0.035}, 250, 0.006, [&](const Vec3&) { return iron * 1.2 + noise(0.02); }, rod, 0.1);
  for (double x : {rod_x0 + 0.1, rod_x1 - 0.1}) {
    tube(b, {x, wall_y - 0.01, rod_z - 0.02}, {x, cur_y, rod_z - 0.02}, 0.008, 0.008, 120, 0.004, iron, rod);
    cuboid(b, {x, wall_y - 0.006, rod_z - 0.02}, {0.025, 0.006, 0.04}, 80, 0.005, one_colour(iron), rod);
  }
  // An acoustic guitar leaning on the wall between the window and the bed: a spruce top with a
  // rosette round the sound hole and a bridge, mahogany sides and back, a neck with a dark
  // fretboard and frets, a headstock with six tuners resting on the wall, six strings.
  b.depth_jitter = 0.0015;
  b.shape_jitter = 0.2;
  const double lean = 0.29;  // the sine of its lean from upright
  const Vec3 ga{0, lean, std::sqrt(1 - lean * lean)}, gx{1, 0, 0}, gn = cross(gx, ga);  // along it, across, out of its top
  const Vec3 go{-0.95, 2.03, 0.04};                                                      // its top's bottom end, on the middle line
  auto gp = [&](double u, double v, double w) { return go + ga * u + gx * v + gn * w; };
  const int guitar = add_object(demo, "guitar", gp(0.55, 0, 0), 0.65f);
  auto bout = [](double u) {  // the body's half width at u along it: two bouts and a waist
    const double lo = 0.19 * 0.19 - (u - 0.19) * (u - 0.19), hi = 0.145 * 0.145 - (u - 0.405) * (u - 0.405);
    return std::max({lo > 0 ? std::sqrt(lo) : 0.0, hi > 0 ? std::sqrt(hi) : 0.0, u > 0.19 && u < 0.405 ? 0.125 : 0.0});
  };
  const Vec3 spruce{0.86, 0.70, 0.46}, mahogany{0.42, 0.22, 0.11}, rosewood{0.16, 0.10, 0.07}, nickel{0.78, 0.78, 0.76};
  for (int i = 0, n = int(2600 * d) + 200; i < n; ++i) {  // the top
    const double u = rng.range(0, 0.55), v = rng.range(-0.19, 0.19), h = bout(u);
    if (std::abs(v) > h) continue;
    const double hole = std::hypot(u - 0.4, v);
    Vec3 c = spruce + noise(0.02);
    if (h - std::abs(v) < 0.007) c = rosewood;                                  // the binding
    else if (hole < 0.043) c = Vec3{0.04, 0.03, 0.03};                          // the sound hole
    else if (hole > 0.05 && hole < 0.058) c = rosewood * 1.3;                   // the rosette
    else if (u > 0.125 && u < 0.16 && std::abs(v) < 0.08) c = rosewood;         // the bridge
    b.splat(gp(u, v, 0), gn, 0.007 * sz, c, guitar, 0.08);
  }
  std::vector<std::pair<double, double>> outline;  // (u, v) round the body
  for (int k = 0; k <= 275; ++k) outline.push_back({0.002 * k, bout(0.002 * k)});
  for (int k = 275; k >= 0; --k) outline.push_back({0.002 * k, -bout(0.002 * k)});
  std::vector<double> run{0};
  for (size_t k = 1; k < outline.size(); ++k)
    run.push_back(run.back() + std::hypot(outline[k].first - outline[k - 1].first, outline[k].second - outline[k - 1].second));
  for (int i = 0, n = int(1800 * d) + 100; i < n; ++i) {  // the sides, 10 cm deep round the outline
    const double at = rng.range(0, run.back());
    const size_t k = std::clamp<size_t>(size_t(std::lower_bound(run.begin(), run.end(), at) - run.begin()), 1, run.size() - 1);
    const auto [u0, v0] = outline[k - 1];
    const auto [u1, v1] = outline[k];
    const double t = (at - run[k - 1]) / std::max(1e-9, run[k] - run[k - 1]);
    b.splat(gp(u0 + (u1 - u0) * t, v0 + (v1 - v0) * t, rng.range(-0.1, 0)), normalized(ga * (v0 - v1) + gx * (u1 - u0)), 0.007 * sz,
            mahogany + noise(0.02), guitar, 0.06);
  }
  for (int i = 0, n = int(1400 * d) + 100; i < n; ++i) {  // the back
    const double u = rng.range(0, 0.55), v = rng.range(-0.19, 0.19);
    if (std::abs(v) > bout(u)) continue;
    b.splat(gp(u, v, -0.1), -gn, 0.008 * sz, mahogany * 0.9 + noise(0.02), guitar, 0.06);
  }
  const double nut = 0.98;
  auto neck_w = [&](double u) { return 0.027 - 0.005 * (u - 0.46) / (nut - 0.46); };  // its half width
  for (int i = 0, n = int(700 * d) + 100; i < n; ++i) {  // the fretboard
    const double u = rng.range(0.46, nut), v = rng.range(-1, 1) * neck_w(u);
    b.splat(gp(u, v, 0.008), gn, 0.004 * sz, rosewood + noise(0.015), guitar, 0.05);
  }
  for (int k = 1; k <= 14; ++k) {  // the frets
    const double u = nut - 0.65 * (1 - std::pow(2, -k / 12.0));
    for (double v = -neck_w(u); v <= neck_w(u); v += 0.006) b.strip(gp(u, v, 0.0095), gn, gx, 0.004, 0.0012, nickel, guitar, 0.1);
  }
  for (int i = 0, n = int(800 * d) + 100; i < n; ++i) {  // the neck's back, half round
    const double u = rng.range(0.55, nut), t = rng.range(0, M_PI), hw = neck_w(u);
    const double c = std::cos(t), sn = std::sin(t);
    b.splat(gp(u, hw * c, 0.006 - 0.022 * sn), normalized(gx * (c / hw) - gn * (sn / 0.022)), 0.005 * sz, mahogany + noise(0.02), guitar,
            0.06);
  }
  for (int i = 0, n = int(300 * d) + 60; i < n; ++i) {  // the headstock's face (the nut a white bar), its back
    const double u = rng.range(nut, 1.16), v = rng.range(-0.038, 0.038);
    const bool face = i % 3 != 0;
    const Vec3 c = face && u < nut + 0.006 ? Vec3{0.93, 0.91, 0.85} : rosewood * (face ? 0.8 : 1.6) + noise(0.015);
    b.splat(gp(u, v, face ? 0.0 : -0.018), face ? gn : -gn, 0.005 * sz, c, guitar, 0.08);
  }
  for (int k = 0; k < 3; ++k)  // the tuners: posts out of its sides, buttons
    for (double side : {-1.0, 1.0}) {
      const double u = nut + 0.04 + 0.045 * k;
      tube(b, gp(u, side * 0.038, -0.009), gp(u, side * 0.065, -0.009), 0.004, 0.004, 30, 0.003, nickel, guitar);
      ellipsoid(b, gp(u, side * 0.075, -0.009), {0.01, 0.006, 0.01}, 40, 0.004, [&](const Vec3&) { return nickel; }, guitar, 0.1);
    }
  for (int k = 0; k < 6; ++k) {  // the strings, bridge to nut
    const double v0 = -0.027 + 0.0108 * k, v1 = -0.018 + 0.0072 * k;
    for (double u = 0.145; u < nut; u += 0.01) {
      const double t = (u - 0.145) / (nut - 0.145);
      b.strip(gp(u, v0 + (v1 - v0) * t, 0.012), gn, ga, 0.006, 0.0008, Vec3{0.80, 0.76, 0.66}, guitar, 0.15);
    }
  }
  // The bed: a teal upholstered headboard against the wall, a grey base, a white mattress and
  // sheet, a quilted sage duvet turned back at the head.
  b.depth_jitter = 0.002;
  b.shape_jitter = 0.25;
  const double duvet_z = 0.56, turn_y = 1.72;
  const Vec3 teal{0.16, 0.36, 0.38}, linen{0.90, 0.89, 0.86}, sage{0.55, 0.62, 0.50}, base_grey{0.40, 0.40, 0.42};
  cuboid(b, {(bed_x0 + bed_x1) / 2, 2.345, 0.6}, {0.86, 0.045, 0.6}, int(5000 * d), 0.016 * sz,
         [&](const Vec3& p, const Vec3& n) {  // buttoned channels down its front
           return (n.y < -0.5 && std::fmod(p.x + 10, 0.2) < 0.012 ? teal * 0.7 : teal) + noise(0.02);
         },
         -1);
  for (double x : {bed_x0, bed_x1}) {  // the base's and the mattress's sides
    quad(b, {x, bed_y0, 0}, {x, bed_y1, 0}, {x, bed_y1, 0.3}, {x, bed_y0, 0.3}, {x < 0 ? -1.0 : 1.0, 0, 0}, int(1000 * d), 0.02 * sz,
         [&](double, double) { return base_grey + noise(0.02); }, -1, 0.02);
    quad(b, {x, turn_y, 0.3}, {x, bed_y1, 0.3}, {x, bed_y1, 0.5}, {x, turn_y, 0.5}, {x < 0 ? -1.0 : 1.0, 0, 0}, int(250 * d), 0.015 * sz,
         [&](double, double) { return white + noise(0.015); }, -1, 0.02);
  }
  quad(b, {bed_x0, bed_y0, 0}, {bed_x1, bed_y0, 0}, {bed_x1, bed_y0, 0.3}, {bed_x0, bed_y0, 0.3}, {0, -1, 0}, int(700 * d), 0.02 * sz,
       [&](double, double) { return base_grey + noise(0.02); }, -1, 0.02);
  quad(b, {bed_x0, turn_y, 0.5}, {bed_x1, turn_y, 0.5}, {bed_x1, bed_y1, 0.5}, {bed_x0, bed_y1, 0.5}, {0, 0, 1}, int(1200 * d), 0.015 * sz,
       [&](double, double) { return white + noise(0.015); }, -1, 0.02);  // the sheet under the pillows
  auto quilted = [&](double a, double c) {  // the duvet's 30 cm squares
    return (std::fmod(a + 10, 0.3) < 0.012 || std::fmod(c + 10, 0.3) < 0.012 ? sage * 0.85 : sage) + noise(0.02);
  };
  for (int i = 0, n = int(7000 * d); i < n; ++i) {  // the duvet's top, softly rumpled
    const double x = rng.range(bed_x0 - 0.05, bed_x1 + 0.05), y = rng.range(bed_y0 - 0.05, turn_y);
    const double z = duvet_z + 0.012 * std::sin(7 * x + 1) * std::sin(5 * y);
    const Vec3 nrm = normalized(Vec3{-0.084 * std::cos(7 * x + 1) * std::sin(5 * y), -0.06 * std::sin(7 * x + 1) * std::cos(5 * y), 1});
    b.splat({x, y, z}, nrm, 0.02 * sz, quilted(x, y), -1, 0.03);
  }
  for (double x : {bed_x0 - 0.05, bed_x1 + 0.05})  // its sides hanging down
    for (int i = 0, n = int(1500 * d); i < n; ++i) {
      const double y = rng.range(bed_y0 - 0.05, turn_y), z = rng.range(0.22, duvet_z);
      b.splat({x + 0.01 * std::sin(13 * y), y, z}, {x < 0 ? -1.0 : 1.0, 0, 0}, 0.018 * sz, quilted(y, z) * 0.95, -1, 0.03);
    }
  for (int i = 0, n = int(800 * d); i < n; ++i) {  // and its foot
    const double x = rng.range(bed_x0 - 0.05, bed_x1 + 0.05), z = rng.range(0.22, duvet_z);
    b.splat({x, bed_y0 - 0.05 + 0.01 * std::sin(11 * x), z}, {0, -1, 0}, 0.018 * sz, quilted(x, z) * 0.95, -1, 0.03);
  }
  for (int i = 0, n = int(1000 * d); i < n; ++i) {  // the turned-back band: its white lining on top, its edge
    const double x = rng.range(bed_x0 - 0.05, bed_x1 + 0.05);
    if (i % 4) b.splat({x, rng.range(turn_y - 0.18, turn_y), duvet_z + 0.04}, {0, 0, 1}, 0.015 * sz, linen + noise(0.015), -1, 0.03);
    else b.splat({x, turn_y - 0.18, rng.range(duvet_z, duvet_z + 0.04)}, {0, -1, 0}, 0.012 * sz, linen * 0.9 + noise(0.015), -1, 0.03);
  }
  // Two pillows leaning on the headboard, touching side by side, and a mustard cushion leaning
  // on both; each a rounded box, piped round its edge.
  b.shape_jitter = 0.2;
  const double tilt = 0.49;  // about 28 degrees back from upright
  const Vec3 pu{0, std::sin(tilt), std::cos(tilt)}, pn = cross(Vec3{1, 0, 0}, pu);  // up its face, out of it
  auto piped = [&](const Vec3& rgb) {
    return [&, rgb](const Vec3& l) { return (std::abs(l.z) < 0.12 ? rgb * 0.9 : rgb) + noise(0.015); };
  };
  int pillows[2];
  for (int k = 0; k < 2; ++k) {
    const Vec3 c{0.04 + 0.73 * k, 2.09, 0.76};
    pillows[k] = add_object(demo, k == 0 ? "pillow" : "pillow_right", c, 0.4f);
    rounded(c, {1, 0, 0}, pu, pn, {0.37, 0.24, 0.08}, {0.5, 0.5, 1.0}, int(4500 * d), 0.011 * sz, piped(linen), pillows[k], 0.03);
  }
  const double cushion_tilt = 0.52;
  const Vec3 cu{0, std::sin(cushion_tilt), std::cos(cushion_tilt)}, cn = cross(Vec3{1, 0, 0}, cu);
  const int cushion = add_object(demo, "cushion", {0.42, 1.924, 0.727}, 0.25f);
  rounded({0.42, 1.924, 0.727}, {1, 0, 0}, cu, cn, {0.21, 0.21, 0.07}, {0.5, 0.5, 1.0}, int(1500 * d), 0.01 * sz,
          piped(Vec3{0.80, 0.60, 0.16}), cushion, 0.03);
  // The bedside table: white drawers, an oak top; a lamp (a sage ceramic base, a linen shade).
  const double tb_x = 1.57, tb_y = 2.16, tb_h = 0.55;
  cuboid(b, {tb_x, tb_y, (tb_h - 0.03) / 2}, {0.25, 0.21, (tb_h - 0.03) / 2}, int(2200 * d), 0.012 * sz,
         [&](const Vec3& p, const Vec3& n) {  // a drawer's gap across the front
           return (n.y < -0.5 && std::abs(p.z - 0.02) < 0.008 ? white * 0.7 : white) + noise(0.015);
         },
         -1);
  cuboid(b, {tb_x, tb_y - 0.005, tb_h - 0.015}, {0.26, 0.215, 0.015}, int(1200 * d), 0.01 * sz,
         [&](const Vec3&, const Vec3& n) { return Vec3{0.70, 0.56, 0.38} * (n.z > 0.5 ? 1.0 : 0.9) + noise(0.02); }, -1);
  ellipsoid(b, {tb_x, tb_y - 0.215, 0.39}, {0.012, 0.012, 0.012}, 40, 0.004, [&](const Vec3&) { return Vec3{0.7, 0.6, 0.35}; }, -1, 0.1);
  ellipsoid(b, {1.68, 2.24, tb_h + 0.1}, {0.07, 0.07, 0.1}, int(500 * d) + 50, 0.008 * sz,
            [&](const Vec3&) { return sage * 0.9 + noise(0.02); }, -1, 0.1);
  tube(b, {1.68, 2.24, tb_h + 0.19}, {1.68, 2.24, tb_h + 0.26}, 0.006, 0.006, 30, 0.003, nickel, -1);
  tube(b, {1.68, 2.24, tb_h + 0.22}, {1.68, 2.24, tb_h + 0.4}, 0.15, 0.11, int(1200 * d) + 60, 0.01 * sz, linen * 0.97, -1);
  // The phone, lying on the table's top: a black screen in a coral case.
  b.depth_jitter = 0.0005;
  b.shape_jitter = 0.1;
  const Vec3 phone_c{1.46, 2.07, tb_h + 0.0045};
  const int phone = add_object(demo, "phone", phone_c, 0.09f);
  cuboid(b, phone_c, {0.037, 0.077, 0.0045}, int(500 * d) + 60, 0.004 * sz,
         [&](const Vec3& p, const Vec3& n) {
           const bool screen = n.z > 0.5 && std::abs(p.x) < 0.032 && std::abs(p.y) < 0.071;
           return (screen ? Vec3{0.05, 0.06, 0.08} : Vec3{0.86, 0.42, 0.36}) + noise(0.015);
         },
         phone);
  // A grey wool rug in front of the bed, under its foot, a darker border.
  b.depth_jitter = 0.002;
  b.shape_jitter = 0.2;
  const Vec3 wool{0.56, 0.56, 0.57};
  for (int i = 0, n = int(7000 * d); i < n; ++i) {
    const double x = rng.range(rug_x0, rug_x1), y = rng.range(rug_y0, rug_y1);
    if (x > bed_x0 - 0.05 && x < bed_x1 + 0.05 && y > bed_y0 - 0.05) continue;  // under the bed
    if (std::hypot((x - cat_c.x) / 0.19, (y - cat_c.y) / 0.13) < 1) continue;    // under the cat
    if (std::abs(x - pack_c.x) < 0.14 && std::abs(y - pack_c.y) < 0.08) continue;  // under the backpack
    const bool border = x < rug_x0 + 0.08 || x > rug_x1 - 0.08 || y < rug_y0 + 0.08 || y > rug_y1 - 0.08;
    b.splat({x, y, rug_z}, {0, 0, 1}, 0.018 * sz, (border ? wool * 0.85 : wool) + noise(0.03), -1, 0.01);
  }
  // A grey tabby cat curled up asleep on the rug, nearly the rug's grey: a body, its head tucked
  // at the front, ears, closed eyes, front paws, a tail round its front, faint darker stripes.
  b.depth_jitter = 0.001;
  b.shape_jitter = 0.2;
  const Vec3 fur{0.54, 0.54, 0.55};
  const int cat = add_object(demo, "cat", cat_c + Vec3{0, 0, 0.08}, 0.25f);
  auto tabby = [&](const Vec3& l) { return (std::sin(l.x * 45 + 4 * std::sin(l.y * 12)) > 0.55 ? fur * 0.84 : fur) + noise(0.03); };
  ellipsoid(b, cat_c + Vec3{0, 0, 0.075}, {0.2, 0.14, 0.085}, int(2600 * d) + 100, 0.008 * sz, tabby, cat, 0.02);
  const Vec3 head = cat_c + Vec3{-0.17, -0.09, 0.07};
  ellipsoid(b, head, {0.065, 0.06, 0.055}, int(600 * d) + 60, 0.006 * sz, tabby, cat, 0.02);
  for (double side : {-1.0, 1.0}) {
    const Vec3 ear = head + Vec3{side * 0.035, 0.01, 0.04};
    tube(b, ear, ear + Vec3{side * 0.012, 0.005, 0.035}, 0.018, 0.002, 60, 0.004, fur * 0.9, cat);
    tube(b, head + Vec3{side * 0.025, -0.055, 0.012}, head + Vec3{side * 0.045, -0.048, 0.016}, 0.002, 0.002, 12, 0.002,
         {0.15, 0.15, 0.15}, cat);  // a closed eye
    ellipsoid(b, cat_c + Vec3{-0.06 + side * 0.03, -0.14, 0.018}, {0.03, 0.02, 0.015}, 60, 0.004,
              [&](const Vec3&) { return fur * 1.08 + noise(0.02); }, cat, 0.02);  // a front paw
  }
  ellipsoid(b, head + Vec3{0, -0.06, -0.005}, {0.008, 0.005, 0.006}, 15, 0.003, [&](const Vec3&) { return Vec3{0.75, 0.5, 0.5}; }, cat);
  for (int k = 0; k < 24; ++k) {  // the tail, from its right side round its front
    const double a0 = (-15 - 4.5 * k) * M_PI / 180, a1 = (-15 - 4.5 * (k + 1)) * M_PI / 180, r = 0.022 - 0.0004 * k;
    const Vec3 p0 = cat_c + Vec3{0.22 * std::cos(a0), 0.16 * std::sin(a0), r};
    const Vec3 p1 = cat_c + Vec3{0.22 * std::cos(a1), 0.16 * std::sin(a1), r};
    tube(b, p0, p1, r, r, 40, 0.004, k % 5 < 2 ? fur * 0.84 : fur, cat);
  }
  // A backpack standing on the rug beside the foot of the bed: a dark red body with a rounded
  // top and a zip over it, a front pocket, a grab handle, two straps at its back.
  b.depth_jitter = 0.0015;
  b.shape_jitter = 0.2;
  const Vec3 canvas{0.55, 0.15, 0.13}, zip{0.12, 0.12, 0.12};
  const int pack = add_object(demo, "backpack", pack_c, 0.3f);
  const Vec3 ex{1, 0, 0}, ey{0, 1, 0}, ez{0, 0, 1};
  rounded(pack_c, ex, ey, ez, {0.15, 0.09, 0.22}, {0.45, 0.8, 0.45}, int(3000 * d) + 100, 0.009 * sz,
          [&](const Vec3& l) { return (std::abs(l.y) < 0.08 && l.z > 0.3 ? zip : canvas) + noise(0.02); }, pack, 0.04);
  const Vec3 pocket_c = pack_c + Vec3{0, -0.11, -0.08};
  rounded(pocket_c, ex, ey, ez, {0.11, 0.035, 0.1}, {0.45, 0.8, 0.45}, int(900 * d) + 60, 0.007 * sz,
          [&](const Vec3& l) { return (l.z > 0.85 && l.y < 0 ? zip : canvas * 0.9) + noise(0.02); }, pack, 0.04);
  for (int k = 0; k < 12; ++k) {  // the handle, a loop on top
    const double a0 = M_PI * k / 12, a1 = M_PI * (k + 1) / 12;
    tube(b, pack_c + Vec3{0.04 * std::cos(a0), 0.03, 0.215 + 0.03 * std::sin(a0)},
         pack_c + Vec3{0.04 * std::cos(a1), 0.03, 0.215 + 0.03 * std::sin(a1)}, 0.007, 0.007, 20, 0.003, zip, pack);
  }
  for (double side : {-1.0, 1.0})  // the straps, down its back
    for (double z = -0.18; z < 0.19; z += 0.01)
      b.strip(pack_c + Vec3{side * 0.08, 0.095 + 0.02 * std::cos(z * 7), z}, {0, 1, 0}, {0, 0, 1}, 0.008, 0.02, zip * 1.5, pack, 0.03);
  // A rattan armchair at the right, turned towards the bed: a woven seat on four legs with
  // stretchers, arms of bent cane, and a curved back of cane strips in an open diamond lattice
  // inside a thick frame, 80 cm in front of the wall, which shows through its gaps.
  b.depth_jitter = 0.001;
  b.shape_jitter = 0.15;
  const Vec3 chair_c{2.1, 1.2, 0};
  const double yaw = 25 * M_PI / 180;
  const Vec3 cx{std::cos(yaw), -std::sin(yaw), 0}, cy{std::sin(yaw), std::cos(yaw), 0};  // its right and its back
  auto cw = [&](double x, double y, double z) { return chair_c + cx * x + cy * y + Vec3{0, 0, z}; };
  const int chair = add_object(demo, "wicker_chair", cw(0, 0.05, 0.55), 0.6f);
  const Vec3 cane{0.78, 0.60, 0.36};
  for (int i = 0, n = int(2000 * d) + 100; i < n; ++i) {  // the woven seat
    const double x = rng.range(-0.28, 0.28), y = rng.range(-0.26, 0.22);
    const bool over = (int(std::floor((x + 1) / 0.015)) + int(std::floor((y + 1) / 0.015))) & 1;
    b.splat(cw(x, y, 0.42), {0, 0, 1}, 0.006 * sz, (over ? cane : cane * 0.85) + noise(0.03), chair, 0.04);
  }
  auto rattan = [&](const Vec3& p0, const Vec3& p1, double r) {  // a cane tube
    tube(b, p0, p1, r, r, int(norm(p1 - p0) * 900 * d) + 30, 0.005 * sz, cane * 0.9, chair);
  };
  rattan(cw(-0.29, -0.27, 0.42), cw(0.29, -0.27, 0.42), 0.018);  // the seat's rim
  rattan(cw(-0.29, 0.23, 0.42), cw(0.29, 0.23, 0.42), 0.018);
  for (double side : {-1.0, 1.0}) {
    rattan(cw(side * 0.29, -0.27, 0.42), cw(side * 0.29, 0.23, 0.42), 0.018);
    for (double y : {-0.25, 0.21}) rattan(cw(side * 0.27, y, 0.42), cw(side * 0.3, y + (y < 0 ? -0.03 : 0.03), 0), 0.017);  // legs
    rattan(cw(side * 0.285, -0.265, 0.12), cw(side * 0.285, 0.225, 0.12), 0.01);  // a stretcher
    rattan(cw(side * 0.29, -0.26, 0.42), cw(side * 0.32, -0.2, 0.64), 0.016);      // an arm
    rattan(cw(side * 0.32, -0.2, 0.64), cw(side * 0.32, 0.15, 0.66), 0.016);
  }
  rattan(cw(-0.285, -0.265, 0.12), cw(0.285, -0.265, 0.12), 0.01);
  auto back_y = [](double x) { return 0.24 - 0.1 * (x / 0.32) * (x / 0.32); };  // its back curves forward at the sides
  auto back_top = [](double x) { return 0.98 + 0.06 * (1 - (x / 0.32) * (x / 0.32)); };
  for (int k = 0; k < 16; ++k) {  // the frame: over the top, down the sides
    const double x0 = -0.32 + 0.04 * k, x1 = x0 + 0.04;
    rattan(cw(x0, back_y(x0), back_top(x0)), cw(x1, back_y(x1), back_top(x1)), 0.016);
  }
  for (double side : {-1.0, 1.0}) rattan(cw(side * 0.32, back_y(0.32), 0.42), cw(side * 0.32, back_y(0.32), back_top(0.32)), 0.016);
  for (double sign : {-1.0, 1.0})  // the lattice: strands along x + z and x - z every 8 cm
    for (int k = -20; k <= 20; ++k) {
      const Vec3 tint = cane * (0.9 + 0.1 * cell_noise(k, int(sign)));
      for (double x = -0.315; x < 0.315; x += 0.007) {
        const double z = 0.08 * k * sign + 0.77 - sign * x;  // strand k crosses x = 0 at 0.77 + 8k cm
        if (z < 0.43 || z > back_top(x) - 0.01) continue;
        const double slope = -0.2 * x / (0.32 * 0.32);  // d back_y / dx
        const Vec3 nrm = normalized(cx * slope - cy);
        b.strip(cw(x, back_y(x), z), nrm, cx + cy * slope - Vec3{0, 0, sign}, 0.007, 0.0045, tint + noise(0.03), chair, 0.04);
      }
    }
  // Floaters: faint blobs in the air a trainer leaves, none by the cameras (all within 2.4 m of
  // the middle the cameras circle, 3 m or more away).
  const Vec3 focus{0.35, 1.3, 0.6};
  b.depth_jitter = 0;
  b.shape_jitter = 0;
  for (int i = 0, n = int(150 * d); i < n; ++i) {
    Vec3 p;
    do p = {rng.range(-3.0, 3.2), rng.range(-0.3, 2.3), rng.range(0.1, 2.5)};
    while (std::hypot(p.x - focus.x, p.y - focus.y) > 2.4);
    b.floater(p, rng.range(0.02, 0.07) * sz, paint * rng.range(0.6, 1.1), rng.range(0.05, 0.3));
  }
  // The capture: 24 cameras on an arc of 110 degrees, alternately at 1.3 m and 1.7 m, every
  // third nearer, held by hand (their own random stream: the Gaussians do not move with it).
  SplitMix64 hand(311);
  for (int id = 0; id < 24; ++id) {
    const double a = (-55 + 110.0 * id / 23) * M_PI / 180, r = id % 3 == 1 ? 3.0 : 3.5;
    const Vec3 wobble{hand.range(-0.04, 0.04), hand.range(-0.04, 0.04), hand.range(-0.04, 0.04)};
    const Vec3 aim{hand.range(-0.12, 0.12), hand.range(-0.05, 0.05), hand.range(-0.07, 0.07)};
    const Vec3 eye = Vec3{focus.x + r * std::sin(a), focus.y - r * std::cos(a), id % 2 ? 1.7 : 1.3} + wobble;
    demo.bundle.cameras.push_back(named(Camera::look_at(eye, focus + aim, {0, 0, 1}, opt.width, opt.height, 64.0), id, "arc"));
  }
  add_task(s, "wicker_chair",
           "rattan armchair clicked on its open lattice back, the wall showing through the gaps (truth: the whole chair: back, "
           "frame, arms, seat, legs)",
           chair, cw(0, back_y(0) - 0.004, 0.77), 7);
  add_task(s, "backpack",
           "backpack on the floor beside the bed's foot, the clicked point hidden by the bed from the right of the arc (truth: the "
           "backpack with its pocket, handle and straps)",
           pack, pocket_c + Vec3{0, -0.036, 0}, 6);
  add_task(s, "vase", "vase on a window sill seen through a net curtain (truth: the vase)", vase,
           vase_c + Vec3{0, -0.096, 0.15}, 13, 20);
  add_task(s, "curtain_rod",
           "thin curtain rod near the top of the frame, its ends out of some views, the curtain's tabs over it (truth: the rod, "
           "its finials and brackets, not the curtain)",
           rod, Vec3{-1.2, cur_y - 0.014, rod_z}, 18);
  add_task(s, "phone", "tiny phone lying flat on a bedside table (truth: the phone)", phone, phone_c + Vec3{0, 0, 0.0045}, 14);
  add_task(s, "guitar",
           "compound object: an acoustic guitar clicked on its body (truth: the whole guitar: body, neck, headstock, tuners, "
           "strings)",
           guitar, gp(0.3, -0.06, 0.001), 5);
  add_task(s, "pillow", "the left one of two pillows touching each other, the headboard and a cushion (truth: that pillow only)",
           pillows[0], Vec3{0.04 - 0.15, 2.09, 0.76} + pu * 0.05 + pn * 0.078, 10);
  add_task(s, "cat", "grey cat curled up asleep on a grey rug of nearly its colour (truth: the cat)", cat,
           cat_c + Vec3{0.03, -0.08, 0.14}, 12);
  return std::move(s);
}

// A bathroom filmed by hand from its doorway in a serpentine sweep (27 cameras in three passes of
// nine across the room: low from left to right, a step nearer and higher from right to left, higher
// again from left to right; each a little off its path and its aim), with jittered Gaussians,
// coarse walls and faint floaters, built as a held-out check by a session that had not seen the
// segmentation method or its tuning: a chrome towel ladder 7 cm off the tiled wall, clicked on a
// bare lower bar, the white tiles showing between its bars and a bath towel over its top bars; a
// toilet brush in its holder beside the toilet, the clicked point hidden by the pan from the left
// of the sweep; a chrome shower riser rail over the bath near the frame's left edge (out of the
// right views), clicked on its pole (the truth is the shower set: pole, brackets, slider, hand
// shower and hose); a bar of soap in a dish on the basin; a toilet clicked on its closed lid (the
// truth is all of it); the right one of two bottles of the same range touching on the bath's rim;
// a white hand towel on a ring against white tiles; and a golden pothos on a shelf whose vines hang
// over the shelf's front in front of the wall (the truth is the plant and its pot).
EvalScene bathroom(const EvalSetOptions& opt) {
  SceneStart start("bathroom", 401);
  auto& [s, demo, g, rng, b] = start;
  const double d = opt.density, sz = 1 / std::sqrt(d);
  const double wall_y = 1.6, side_x = 2.1, front_y = -1.9, room_h = 2.6, tile_z = 1.2, shower_z = 2.1;
  auto noise = [&](double a) { return Vec3{1, 1, 1} * (a * rng.normal()); };
  const Vec3 white{0.93, 0.93, 0.91}, grout{0.70, 0.70, 0.68}, porcelain{0.95, 0.95, 0.94}, chrome{0.70, 0.71, 0.73};
  const double glaze = 0.04;  // the view dependence of the glazed and acrylic whites (more would speckle them)
  // Chrome and glazed parts catch the two lights (the ceiling light, the doorway behind the
  // cameras) as the view moves.
  const std::vector<std::pair<Vec3, Vec3>> lights = {{{0.2, -0.3, 1}, {0.35, 0.35, 0.33}}, {{0, -1, 0.1}, {0.2, 0.2, 0.2}}};
  auto chrome_tube = [&](const Vec3& p0, const Vec3& p1, double r, int n, int label) {
    const Vec3 axis = normalized(p1 - p0);
    const Vec3 side = normalized(cross(axis, std::abs(axis.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0}));
    const Vec3 up = cross(side, axis);
    for (int i = 0; i < n; ++i) {
      const double t = rng.uniform(), a = rng.range(0, 2 * M_PI);
      const Vec3 radial = side * std::cos(a) + up * std::sin(a);
      b.splat(p0 + (p1 - p0) * t + radial * r, radial, 0.004 * sz, chrome + noise(0.02), label, 0.05);
      gloss(g, radial, lights, 0.8, 0.6);
    }
  };
  // Where the bath, the basket, the toilet and the basin stand.
  const double bath_x0 = -side_x, bath_x1 = -0.4, bath_y0 = 0.85, bath_z = 0.55, rim = 0.09;
  const Vec3 basket_c{-0.15, 1.33, 0}, toilet_c{0.30, 1.2, 0}, basin_c{1.78, 1.33, 0.85};
  const double pan_rx = 0.18, pan_ry = 0.26, pan_h = 0.38;
  const double mat_x0 = -1.55, mat_x1 = -0.85, mat_y0 = 0.3, mat_y1 = 0.8;
  // The room: white 15 cm wall tiles with grey grout up to 1.2 m (up to 2.1 m round the bath),
  // pale sage paint above, a frosted window over the bath; large grey floor tiles; coarse, loose
  // Gaussians (the flat glazed tiles a little less loose than paint).
  b.depth_jitter = 0.003;
  b.shape_jitter = 0.25;
  const Vec3 sage{0.76, 0.80, 0.74};
  auto wall_rgb = [&](double u, double z, bool shower) {
    if (z > (shower ? shower_z : tile_z)) {
      const double blotch = 0.04 * cell_noise(int(std::floor((u + 20) / 0.4)), int(std::floor(z / 0.4)));
      return sage * (0.95 + 0.02 * z) + Vec3{1, 1, 1} * blotch + noise(0.02);
    }
    return white + Vec3{1, 1, 1} * (0.03 * cell_noise(int((u + 20) / 0.15), int(z / 0.15))) + noise(0.012);
  };
  const double win_x0 = -1.45, win_x1 = -0.85, win_z0 = 1.5, win_z1 = 2.05;
  const double mir_x0 = 1.58, mir_x1 = 1.98, mir_z0 = 1.15, mir_z1 = 1.8;
  back_wall(b, side_x, wall_y, room_h, int(16000 * d), 0.04 * sz, 0.03,
            {{win_x0, win_x1, win_z0, win_z1}, {mir_x0, mir_x1, mir_z0, mir_z1}},  // the window, the mirror
            [&](double x, double z) { return wall_rgb(x, z, x < bath_x1); });  // up past every view
  b.depth_jitter = 0.001;
  b.shape_jitter = 0.2;
  // The grout on the back wall, lines every 15 cm across and up (where wall_rgb's tiles meet),
  // none over the window and the mirror; 1 cm in front of the tiles' centres, as a trainer
  // leaves thin dark lines on a bright surface (behind its loose Gaussians they would not show).
  auto tiled = [&](double x, double z) {
    return z < (x < bath_x1 ? shower_z : tile_z) + 0.001 && !(x > win_x0 && x < win_x1 && z > win_z0) &&
           !(x > mir_x0 && x < mir_x1 && z > mir_z0);
  };
  for (int row = 1; row * 0.15 < shower_z + 0.001; ++row)
    for (double x = -side_x; x < side_x; x += 0.02)
      if (tiled(x, row * 0.15))
        b.strip({x, wall_y - 0.012, row * 0.15}, {0, -1, 0}, {1, 0, 0}, 0.012, 0.005, grout + noise(0.02), -1, 0.02);
  for (int col = int(std::ceil((20 - side_x) / 0.15)); col * 0.15 - 20 < side_x; ++col)
    for (double z = 0.01; z < shower_z; z += 0.02)
      if (tiled(col * 0.15 - 20, z))
        b.strip({col * 0.15 - 20, wall_y - 0.012, z}, {0, -1, 0}, {0, 0, 1}, 0.012, 0.005, grout + noise(0.02), -1, 0.02);
  b.depth_jitter = 0.006;
  b.shape_jitter = 0.35;
  b.size_scale = 1.5;  // the side walls only as far forward as any camera sees
  for (double x : {-side_x, side_x})
    for (int i = 0, n = int(4000 * d); i < n; ++i) {
      const Vec3 p{x, rng.range(front_y, wall_y), rng.range(0, room_h)};
      b.splat(p, {x < 0 ? 1.0 : -1.0, 0, 0}, 0.045 * sz, wall_rgb(p.y, p.z, x < 0 && p.y > bath_y0) * 0.95, -1, 0.03);
    }
  b.size_scale = 1.25;
  b.depth_jitter = 0.004;
  for (int i = 0, n = int(9000 * d); i < n; ++i) {  // 30 cm floor tiles, none under the bath, the mat, the basket
    const Vec3 p{rng.range(-side_x, side_x), rng.range(front_y - 0.2, wall_y), 0};
    if ((p.x < bath_x1 && p.y > bath_y0) || (p.x > mat_x0 && p.x < mat_x1 && p.y > mat_y0 && p.y < mat_y1) ||
        std::hypot(p.x - basket_c.x, p.y - basket_c.y) < 0.16)
      continue;
    const bool joint = std::fmod(p.x + 20, 0.3) < 0.008 || std::fmod(p.y + 20, 0.3) < 0.008;
    const Vec3 c = Vec3{0.66, 0.65, 0.62} + Vec3{1, 1, 1} * (0.06 * cell_noise(int((p.x + 20) / 0.3), int((p.y + 20) / 0.3)));
    b.splat(p, {0, 0, 1}, 0.045 * sz, (joint ? Vec3{0.42, 0.41, 0.40} : c) + noise(0.015), -1, 0.05);
  }
  b.size_scale = 1.0;
  b.depth_jitter = 0.002;
  b.shape_jitter = 0.2;
  for (int i = 0, n = int(1200 * d); i < n; ++i) {  // the window: frosted glass, brightest at the top, a white frame and bar
    const double x = rng.range(win_x0, win_x1), z = rng.range(win_z0, win_z1);
    const bool frame = x < win_x0 + 0.04 || x > win_x1 - 0.04 || z < win_z0 + 0.04 || z > win_z1 - 0.04 || std::abs(z - 1.78) < 0.015;
    const Vec3 glass = Vec3{0.84, 0.88, 0.92} + Vec3{1, 1, 1} * (0.08 * (z - win_z0));
    b.splat({x, wall_y + (frame ? -0.01 : 0.02), z}, {0, -1, 0}, 0.02 * sz, (frame ? porcelain : glass) + noise(0.012), -1,
            frame ? 0.03 : 0.1);
  }
  for (int i = 0, n = int(1500 * d); i < n; ++i) {  // the mirror: a soft blur of the room behind the cameras, a thin steel frame
    const double x = rng.range(mir_x0, mir_x1), z = rng.range(mir_z0, mir_z1);
    const bool frame = x < mir_x0 + 0.015 || x > mir_x1 - 0.015 || z < mir_z0 + 0.015 || z > mir_z1 - 0.015;
    Vec3 c = Vec3{0.58, 0.62, 0.63} + Vec3{1, 1, 1} * (0.12 * (z - mir_z0));
    if (x > 1.7 && x < 1.84 && z < 1.62) c = Vec3{0.70, 0.70, 0.66};  // the doorway behind the cameras, lit
    b.splat({x, wall_y - 0.012, z}, {0, -1, 0}, 0.014 * sz, (frame ? chrome : c) + noise(0.015), -1, 0.15);
  }
  for (int i = 0, n = int(2500 * d); i < n; ++i) {  // a blue-grey bath mat in front of the bath
    const Vec3 p{rng.range(mat_x0, mat_x1), rng.range(mat_y0, mat_y1), 0.012};
    b.splat(p, {0, 0, 1}, 0.012 * sz, Vec3{0.44, 0.51, 0.57} + noise(0.03), -1, 0.01);
  }
  // The bath: white acrylic, its front and end panels, a rim, a tub sloping to its bottom; a
  // chrome spout and mixer on the wall.
  quad(b, {bath_x0, bath_y0, 0}, {bath_x1, bath_y0, 0}, {bath_x1, bath_y0, bath_z}, {bath_x0, bath_y0, bath_z}, {0, -1, 0},
       int(2500 * d), 0.02 * sz, [&](double, double v) { return porcelain * (0.9 + 0.06 * v) + noise(0.012); }, -1, glaze);
  quad(b, {bath_x1, bath_y0, 0}, {bath_x1, wall_y, 0}, {bath_x1, wall_y, bath_z}, {bath_x1, bath_y0, bath_z}, {1, 0, 0},
       int(1000 * d), 0.02 * sz, [&](double, double) { return porcelain * 0.9 + noise(0.012); }, -1, glaze);
  const double ix0 = bath_x0 + rim, ix1 = bath_x1 - rim, iy0 = bath_y0 + rim, iy1 = wall_y - rim;
  for (int i = 0, n = int(2000 * d); i < n; ++i) {  // the rim
    const Vec3 p{rng.range(bath_x0, bath_x1), rng.range(bath_y0, wall_y), bath_z};
    if (p.x > ix0 && p.x < ix1 && p.y > iy0 && p.y < iy1) continue;
    b.splat(p, {0, 0, 1}, 0.012 * sz, porcelain + noise(0.012), -1, glaze);
  }
  {
    const double bx0 = ix0 + 0.1, bx1 = ix1 - 0.1, by0 = iy0 + 0.08, by1 = iy1 - 0.06, bz = 0.18, tz = bath_z - 0.01;
    const Vec3 top[4] = {{ix0, iy0, tz}, {ix1, iy0, tz}, {ix1, iy1, tz}, {ix0, iy1, tz}};
    const Vec3 bottom[4] = {{bx0, by0, bz}, {bx1, by0, bz}, {bx1, by1, bz}, {bx0, by1, bz}};
    const Vec3 inside{(ix0 + ix1) / 2, (iy0 + iy1) / 2, bath_z};
    auto tub = [&](double, double) { return porcelain * 0.88 + noise(0.012); };
    quad(b, bottom[0], bottom[1], bottom[2], bottom[3], {0, 0, 1}, int(1500 * d), 0.02 * sz, tub, -1, glaze);
    for (int k = 0; k < 4; ++k) {  // the four sloping sides, facing into the tub
      const Vec3 &a0 = top[k], &a1 = top[(k + 1) % 4], &c1 = bottom[(k + 1) % 4], &c0 = bottom[k];
      Vec3 nrm = normalized(cross(a1 - a0, c0 - a0));
      if (dot(nrm, inside - (a0 + c1) * 0.5) < 0) nrm = -nrm;
      quad(b, a0, a1, c1, c0, nrm, int(900 * d), 0.02 * sz, tub, -1, glaze);
    }
  }
  const Vec3 mixer{-1.15, wall_y - 0.03, 0.78};
  cylinder(b, mixer + Vec3{0, 0, -0.035}, 0.03, 0.03, 0.07, 200, 0.004, chrome, -1, true);
  chrome_tube({-0.95, wall_y, 0.68}, {-0.95, wall_y - 0.16, 0.66}, 0.014, 250, -1);  // the spout
  // Shampoo and conditioner of one range on the bath's back rim, touching: white bottles, a
  // navy label on one, a pale blue one on the other, a navy and a white flip cap.
  b.depth_jitter = 0.001;
  b.shape_jitter = 0.15;
  auto bottle = [&](const Vec3& c, double r, double h, const Vec3& band, const Vec3& cap, int label) {
    for (int i = 0, n = int(900 * d) + 80; i < n; ++i) {
      if (rng.uniform() < 0.12) {  // its shoulder
        const double rr = r * std::sqrt(rng.uniform()), a = rng.range(0, 2 * M_PI);
        b.splat(c + Vec3{rr * std::cos(a), rr * std::sin(a), h}, {0, 0, 1}, 0.005 * sz, porcelain + noise(0.015), label, glaze);
        continue;
      }
      const double a = rng.range(0, 2 * M_PI), z = rng.range(0, h);
      const Vec3 radial{std::cos(a), std::sin(a), 0};
      const bool printed = z > 0.3 * h && z < 0.75 * h;
      b.splat(c + radial * r + Vec3{0, 0, z}, radial, 0.005 * sz, (printed ? band : porcelain) + noise(0.015), label, glaze);
    }
    cylinder(b, c + Vec3{0, 0, h}, 0.019, 0.017, 0.028, 160, 0.004, cap, label, true);
  };
  const double bottle_r = 0.032, bottle_y = wall_y - 0.046;
  bottle({-0.78, bottle_y, bath_z}, bottle_r, 0.2, {0.12, 0.20, 0.45}, {0.12, 0.20, 0.45}, -1);
  const Vec3 cond_c{-0.78 + 2 * bottle_r, bottle_y, bath_z};
  const int conditioner = add_object(demo, "conditioner", cond_c + Vec3{0, 0, 0.09}, 0.11f);
  bottle(cond_c, bottle_r, 0.17, {0.50, 0.66, 0.84}, porcelain, conditioner);
  // The shower set over the bath near the left wall: a chrome riser rail on two wall brackets, a
  // slider holding a hand shower, its hose hanging in a loop to the mixer.
  const double riser_x = -1.5, riser_y = wall_y - 0.045, riser_z0 = 1.0, riser_z1 = 2.05;
  const int shower = add_object(demo, "shower", {riser_x, riser_y, 1.5}, 0.6f);
  chrome_tube({riser_x, riser_y, riser_z0}, {riser_x, riser_y, riser_z1}, 0.011, int(1400 * d) + 100, shower);
  for (double z : {riser_z0 + 0.03, riser_z1 - 0.03}) {
    chrome_tube({riser_x, wall_y, z}, {riser_x, riser_y, z}, 0.013, 120, shower);
    cylinder(b, {riser_x, riser_y, z - 0.025}, 0.016, 0.016, 0.05, 100, 0.004, chrome * 0.9, shower, false);
  }
  for (double z : {riser_z0, riser_z1})  // the end caps
    ellipsoid(b, {riser_x, riser_y, z}, {0.013, 0.013, 0.01}, 60, 0.004, [&](const Vec3&) { return chrome + noise(0.02); }, shower);
  const Vec3 slider{riser_x, riser_y, 1.62};
  cylinder(b, slider - Vec3{0, 0, 0.03}, 0.02, 0.02, 0.06, 200, 0.004, Vec3{0.25, 0.25, 0.27}, shower, false);
  const Vec3 grip0 = slider + Vec3{0, -0.035, -0.03}, grip1 = grip0 + Vec3{0.0, -0.05, 0.19};
  chrome_tube(grip0, grip1, 0.014, 400, shower);
  ellipsoid(b, grip1 + Vec3{0, -0.01, 0.015}, {0.055, 0.055, 0.018}, 700, 0.005,
            [&](const Vec3& l) { return (l.z < -0.01 ? Vec3{0.35, 0.36, 0.38} : chrome) + noise(0.02); }, shower, 0.1);
  {
    const Vec3 a = grip0 - Vec3{0, 0, 0.01}, c = mixer + Vec3{0, -0.035, 0};
    Vec3 prev = a;
    for (int k = 1; k <= 40; ++k) {  // the hose: a loop sagging 35 cm below the line between its ends
      const double t = k / 40.0;
      const Vec3 p = a + (c - a) * t + Vec3{0, -0.07, -0.35} * std::sin(M_PI * t);
      tube(b, prev, p, 0.007, 0.007, 45, 0.003, k % 2 ? chrome * 0.9 : chrome * 0.8, shower);
      prev = p;
    }
  }
  // A wicker laundry basket with a lid between the bath and the toilet.
  b.depth_jitter = 0.0015;
  for (int i = 0, n = int(3000 * d); i < n; ++i) {
    const double a = rng.range(0, 2 * M_PI), z = rng.range(0, 0.52), r = 0.17 + 0.02 * z / 0.52;
    const bool weave = (int(std::floor(a * 0.17 / 0.02)) + int(std::floor(z / 0.02))) & 1;
    const Vec3 radial{std::cos(a), std::sin(a), 0};
    b.splat(basket_c + radial * r + Vec3{0, 0, z}, radial, 0.007 * sz, Vec3{0.70, 0.58, 0.40} * (weave ? 1.0 : 0.85) + noise(0.03), -1,
            0.03);
  }
  cylinder(b, basket_c + Vec3{0, 0, 0.52}, 0.2, 0.19, 0.03, int(1200 * d), 0.008 * sz, {0.66, 0.55, 0.38}, -1, true);
  // The toilet: a pan narrowing to its foot, a white seat and a closed lid, two chrome hinges, a
  // cistern against the wall with its lid and a flush button.
  b.depth_jitter = 0.001;
  b.shape_jitter = 0.15;
  const int toilet = add_object(demo, "toilet", toilet_c + Vec3{0, 0.1, 0.4}, 0.45f);
  const double cis_y0 = 1.42, lid_z = pan_h + 0.035;
  for (int i = 0, n = int(3500 * d) + 100; i < n; ++i) {  // the pan
    const double a = rng.range(0, 2 * M_PI), z = rng.range(0, pan_h), f = 0.62 + 0.38 * std::sqrt(z / pan_h);
    const Vec3 p = toilet_c + Vec3{pan_rx * f * std::cos(a), pan_ry * f * std::sin(a), z};
    if (p.y > cis_y0 + 0.03) continue;
    const Vec3 nrm = normalized(Vec3{std::cos(a) / pan_rx, std::sin(a) / pan_ry, -1.2});
    b.splat(p, normalized(Vec3{nrm.x, nrm.y, z < 0.1 ? 0.0 : -0.3 * std::abs(nrm.z)}), 0.008 * sz, porcelain * 0.97 + noise(0.012),
            toilet, glaze);
  }
  for (int i = 0, n = int(1800 * d) + 100; i < n; ++i) {  // the lid, a low dome, its back cut square at the hinges
    const double a = rng.range(0, 2 * M_PI), q = std::sqrt(rng.uniform());
    const Vec3 p = toilet_c + Vec3{pan_rx * q * std::cos(a), (pan_ry - 0.01) * q * std::sin(a) - 0.01, lid_z + 0.012 * (1 - q * q)};
    if (p.y > cis_y0 - 0.01) continue;
    b.splat(p, normalized(Vec3{q * std::cos(a) * 0.2, q * std::sin(a) * 0.2, 1}), 0.008 * sz, porcelain + noise(0.012), toilet, glaze);
    gloss(g, {0, 0, 1}, lights, 0.5, 0.3);
  }
  for (int i = 0, n = int(1200 * d) + 60; i < n; ++i) {  // the edges of the seat and the lid, a shaded gap between them
    const double a = rng.range(0, 2 * M_PI), z = rng.range(pan_h, lid_z);
    const Vec3 radial{std::cos(a), std::sin(a), 0};
    const Vec3 p = toilet_c + Vec3{pan_rx * std::cos(a), (pan_ry - 0.01) * std::sin(a) - 0.01, z};
    if (p.y > cis_y0 - 0.01) continue;
    const double gap = std::abs(z - (pan_h + 0.018));
    b.splat(p, radial, 0.004 * sz, (gap < 0.004 ? porcelain * 0.62 : porcelain * 0.93) + noise(0.012), toilet, glaze);
  }
  for (double x : {toilet_c.x - 0.08, toilet_c.x + 0.08})
    chrome_tube({x - 0.02, cis_y0 - 0.02, pan_h + 0.02}, {x + 0.02, cis_y0 - 0.02, pan_h + 0.02}, 0.012, 80, toilet);
  const Vec3 cis_c{toilet_c.x, (cis_y0 + wall_y) / 2, 0.6};
  cuboid(b, cis_c, {0.18, (wall_y - cis_y0) / 2, 0.2}, int(3000 * d) + 100, 0.008 * sz,
         [&](const Vec3&, const Vec3&) { return porcelain * 0.96 + noise(0.012); }, toilet);
  cuboid(b, cis_c + Vec3{0, -0.005, 0.2}, {0.19, (wall_y - cis_y0) / 2 + 0.005, 0.012}, int(1200 * d) + 60, 0.007 * sz,
         [&](const Vec3&, const Vec3&) { return porcelain + noise(0.012); }, toilet);
  cylinder(b, cis_c + Vec3{0, -0.01, 0.212}, 0.026, 0.026, 0.008, 150, 0.004, chrome, toilet, true);
  // A toilet brush in a brushed-steel holder on the floor beside the pan, right of the cistern.
  const Vec3 brush_c{0.57, 1.46, 0};
  const int brush = add_object(demo, "toilet_brush", brush_c + Vec3{0, 0, 0.25}, 0.3f);
  const Vec3 steel{0.62, 0.63, 0.64};
  cylinder(b, brush_c, 0.048, 0.052, 0.34, int(1500 * d) + 100, 0.005 * sz, steel, brush, false, 0.3);
  for (int i = 0; i < 150; ++i) {  // the open top, dark inside
    const double rr = 0.048 * std::sqrt(rng.uniform()), a = rng.range(0, 2 * M_PI);
    b.splat(brush_c + Vec3{rr * std::cos(a), rr * std::sin(a), 0.33}, {0, 0, 1}, 0.005, Vec3{0.15, 0.15, 0.16} + noise(0.02), brush,
            0.02);
  }
  tube(b, brush_c + Vec3{0, 0, 0.3}, brush_c + Vec3{0, 0, 0.56}, 0.009, 0.009, 300, 0.004, steel * 1.1, brush);
  ellipsoid(b, brush_c + Vec3{0, 0, 0.565}, {0.016, 0.016, 0.012}, 80, 0.004, [&](const Vec3&) { return steel + noise(0.02); }, brush);
  // A chrome towel ladder 7 cm off the wall between the toilet and the basin: two uprights on
  // four brackets, twelve bars; a teal bath towel folded over its two top bars.
  const double rail_x0 = 0.70, rail_x1 = 1.18, rail_y = wall_y - 0.07, rail_z0 = 0.3, rail_z1 = 1.5;
  const int rail = add_object(demo, "towel_rail", {(rail_x0 + rail_x1) / 2, rail_y, (rail_z0 + rail_z1) / 2}, 0.65f);
  for (double x : {rail_x0, rail_x1}) {
    chrome_tube({x, rail_y, rail_z0}, {x, rail_y, rail_z1}, 0.016, int(1200 * d) + 100, rail);
    for (double z : {rail_z0, rail_z1})
      ellipsoid(b, {x, rail_y, z}, {0.017, 0.017, 0.012}, 60, 0.004, [&](const Vec3&) { return chrome + noise(0.02); }, rail);
    for (double z : {rail_z0 + 0.1, rail_z1 - 0.1}) {
      chrome_tube({x, wall_y, z}, {x, rail_y, z}, 0.01, 100, rail);
      chrome_tube({x, wall_y, z}, {x, wall_y - 0.012, z}, 0.028, 80, rail);  // the wall rose
    }
  }
  for (double z = rail_z0 + 0.05; z < rail_z1; z += 0.1)
    chrome_tube({rail_x0, rail_y, z}, {rail_x1, rail_y, z}, 0.011, int(300 * d) + 40, rail);
  {
    const Vec3 teal{0.16, 0.44, 0.47};
    const double tx0 = rail_x0 + 0.035, tx1 = rail_x1 - 0.035, fold_z = rail_z1 - 0.05, front_z = 0.98, back_z = 1.1;
    for (int i = 0, n = int(4000 * d) + 100; i < n; ++i) {
      const double x = rng.range(tx0, tx1), pick = rng.uniform();
      const Vec3 c = teal * (std::fmod(x - tx0, 0.06) < 0.03 ? 1.0 : 0.92) + noise(0.03);  // the folds, lit and shaded
      if (pick < 0.6) {  // the front half, hanging in soft folds
        const double z = rng.range(front_z, fold_z);
        const bool hem = z < front_z + 0.035;
        b.splat({x, rail_y - 0.026 + 0.008 * std::sin((x - tx0) * 52), z}, {0, -1, 0}, 0.01 * sz, hem ? teal * 1.2 + noise(0.02) : c, -1,
                0.01);
      } else if (pick < 0.85) {  // over the top bar
        const double t = rng.range(0, M_PI);
        const Vec3 r{0, -std::cos(t), std::sin(t)};
        b.splat(Vec3{x, rail_y, fold_z} + r * 0.026, r, 0.01 * sz, c, -1, 0.01);
      } else {  // the back half, behind the bars
        b.splat({x, rail_y + 0.026, rng.range(back_z, fold_z)}, {0, 1, 0}, 0.01 * sz, c, -1, 0.01);
      }
    }
  }
  // A white hand towel through a chrome ring on the tiles right of the ladder.
  const Vec3 ring_c{1.36, wall_y - 0.055, 1.08};
  chrome_tube({ring_c.x, wall_y, 1.15}, {ring_c.x, ring_c.y, 1.15}, 0.01, 100, -1);
  for (int k = 0; k < 24; ++k) {
    const double a0 = 2 * M_PI * k / 24, a1 = 2 * M_PI * (k + 1) / 24;
    chrome_tube(ring_c + Vec3{0.065 * std::cos(a0), 0, 0.065 * std::sin(a0)}, ring_c + Vec3{0.065 * std::cos(a1), 0, 0.065 * std::sin(a1)},
                0.005, 20, -1);
  }
  const int towel = add_object(demo, "hand_towel", {ring_c.x, ring_c.y - 0.01, 0.8}, 0.3f);
  const Vec3 terry{0.94, 0.94, 0.92};
  for (int i = 0, n = int(3000 * d) + 100; i < n; ++i) {
    const double v = rng.uniform();  // from the ring down
    const bool back = rng.uniform() < 0.25;
    const double half = 0.13 * (0.4 + 0.6 * std::min(1.0, v * 4)), x = rng.range(-half, half);
    const double z = ring_c.z - 0.065 - v * (back ? 0.36 : 0.46);
    const double y = back ? ring_c.y + 0.012 : ring_c.y - 0.014 + 0.007 * std::sin(x * 60) - 0.01 * (1 - v);
    const bool band = v > 0.84 && v < 0.88;
    b.splat(ring_c + Vec3{x, y - ring_c.y, z - ring_c.z}, {0, back ? 1.0 : -1.0, 0}, 0.009 * sz,
            (band ? Vec3{0.84, 0.83, 0.79} : terry) + noise(0.025), towel, 0.01);
  }
  // The basin on its pedestal: a ceramic deck round an oval bowl, an apron and sides, a chrome
  // mixer tap; a soap dish on the deck behind the bowl, a bar of soap on it.
  const double bx0 = basin_c.x - 0.22, bx1 = basin_c.x + 0.22, by0 = 1.15, bowl_rx = 0.17, bowl_ry = 0.13;
  const Vec3 bowl_c{basin_c.x, 1.31, basin_c.z};
  cylinder(b, {basin_c.x, 1.47, 0}, 0.085, 0.075, 0.72, int(1500 * d), 0.008 * sz, porcelain * 0.95, -1, false);
  for (int i = 0, n = int(2000 * d); i < n; ++i) {  // the deck
    const Vec3 p{rng.range(bx0, bx1), rng.range(by0, wall_y), basin_c.z};
    if (std::hypot((p.x - bowl_c.x) / bowl_rx, (p.y - bowl_c.y) / bowl_ry) < 1) continue;
    b.splat(p, {0, 0, 1}, 0.008 * sz, porcelain + noise(0.012), -1, glaze);
  }
  for (int i = 0, n = int(1500 * d); i < n; ++i) {  // the bowl
    const double a = rng.range(0, 2 * M_PI), w = rng.uniform(), f = std::sqrt(1 - w * w);
    const Vec3 p = bowl_c + Vec3{bowl_rx * f * std::cos(a), bowl_ry * f * std::sin(a), -0.12 * w};
    const bool drain = f < 0.12;
    b.splat(p, normalized(Vec3{-f * std::cos(a) / bowl_rx, -f * std::sin(a) / bowl_ry, w / 0.12}), 0.007 * sz,
            drain ? chrome * 0.6 : porcelain * 0.9 + noise(0.012), -1, glaze);
  }
  quad(b, {bx0, by0, 0.7}, {bx1, by0, 0.7}, {bx1, by0, basin_c.z}, {bx0, by0, basin_c.z}, {0, -1, 0}, int(800 * d), 0.008 * sz,
       [&](double, double) { return porcelain * 0.93 + noise(0.012); }, -1, glaze);
  for (double x : {bx0, bx1})
    quad(b, {x, by0, 0.7}, {x, wall_y, 0.7}, {x, wall_y, basin_c.z}, {x, by0, basin_c.z}, {x < basin_c.x ? -1.0 : 1.0, 0, 0},
         int(600 * d), 0.008 * sz, [&](double, double) { return porcelain * 0.9 + noise(0.012); }, -1, glaze);
  chrome_tube({basin_c.x, 1.54, basin_c.z}, {basin_c.x, 1.54, basin_c.z + 0.14}, 0.018, 300, -1);
  chrome_tube({basin_c.x, 1.54, basin_c.z + 0.13}, {basin_c.x, 1.43, basin_c.z + 0.12}, 0.012, 200, -1);
  chrome_tube({basin_c.x, 1.55, basin_c.z + 0.15}, {basin_c.x, 1.6, basin_c.z + 0.17}, 0.006, 60, -1);  // the lever
  const Vec3 dish_c{1.635, 1.545, basin_c.z};
  cuboid(b, dish_c + Vec3{0, 0, 0.004}, {0.055, 0.04, 0.004}, 300, 0.005, one_colour(porcelain * 0.92), -1);
  const Vec3 soap_c = dish_c + Vec3{0, 0, 0.022};
  const int soap = add_object(demo, "soap", soap_c, 0.05f);
  ellipsoid(b, soap_c, {0.045, 0.03, 0.014}, int(700 * d) + 60, 0.005 * sz,
            [&](const Vec3&) { return Vec3{0.76, 0.68, 0.84} + noise(0.015); }, soap, 0.04);
  // A small steel pedal bin under the hand towel.
  cylinder(b, {1.36, 1.36, 0}, 0.11, 0.11, 0.3, int(1200 * d), 0.007 * sz, Vec3{0.52, 0.53, 0.55}, -1, true);
  // An oak shelf on the wall over the cistern: a candle in an amber jar, a golden pothos in a
  // terracotta pot whose vines hang over the shelf's front, 20 cm off the wall.
  const double shelf_x0 = 0.02, shelf_x1 = 0.58, shelf_y0 = 1.4, shelf_z = 1.38;
  const Vec3 oak{0.64, 0.47, 0.30};
  cuboid(b, {(shelf_x0 + shelf_x1) / 2, (shelf_y0 + wall_y) / 2, shelf_z - 0.0125},
         {(shelf_x1 - shelf_x0) / 2, (wall_y - shelf_y0) / 2, 0.0125}, int(1200 * d), 0.008 * sz,
         [&](const Vec3&, const Vec3&) { return oak + noise(0.02); }, -1);
  quad(b, {shelf_x0, shelf_y0, shelf_z - 0.025}, {shelf_x1, shelf_y0, shelf_z - 0.025}, {shelf_x1, wall_y, shelf_z - 0.025},
       {shelf_x0, wall_y, shelf_z - 0.025}, {0, 0, -1}, int(500 * d), 0.008 * sz, [&](double, double) { return oak * 0.7 + noise(0.02); },
       -1, 0.02);
  cylinder(b, {0.1, 1.5, shelf_z}, 0.04, 0.04, 0.085, 400, 0.005, Vec3{0.72, 0.45, 0.20}, -1, true);
  const Vec3 pot_c{0.36, 1.5, shelf_z};
  const int pothos = add_object(demo, "pothos", pot_c + Vec3{0, -0.05, 0.0}, 0.45f);
  cylinder(b, pot_c, 0.058, 0.075, 0.11, int(1200 * d) + 100, 0.006 * sz, Vec3{0.72, 0.40, 0.28}, pothos, false, 0.09);
  for (int i = 0; i < 200; ++i) {  // the soil
    const double rr = 0.07 * std::sqrt(rng.uniform()), a = rng.range(0, 2 * M_PI);
    b.splat(pot_c + Vec3{rr * std::cos(a), rr * std::sin(a), 0.1}, {0, 0, 1}, 0.006, Vec3{0.22, 0.16, 0.11} + noise(0.02), pothos, 0.01);
  }
  const Vec3 leaf_lo{0.18, 0.38, 0.10}, leaf_hi{0.46, 0.62, 0.22};
  Leaves crown;
  crown.radii = {0.14, 0.1, 0.07};
  crown.tilt = 0.7;
  crown.spacing = 0.011;
  crown.length = 0.011;
  crown.width = 0.013;
  crown.lo = leaf_lo;
  crown.hi = leaf_hi;
  leaves(b, pot_c + Vec3{0, -0.01, 0.17}, crown, int(40 * d) + 10, pothos);
  auto leaf = [&](const Vec3& at, const Vec3& dir, const Vec3& nrm) {  // a heart-shaped leaf of four strips from its stalk
    const Vec3 col{rng.range(leaf_lo.x, leaf_hi.x), rng.range(leaf_lo.y, leaf_hi.y), rng.range(leaf_lo.z, leaf_hi.z)};
    for (int k = 0; k < 4; ++k)
      b.strip(at + dir * (0.012 * k), nrm, dir, 0.011, 0.014 * (k == 0 ? 0.8 : 1 - 0.2 * (k - 1)), col, pothos, 0.05);
  };
  Vec3 clicked_leaf;
  const double vine_x[4] = {0.24, 0.31, 0.40, 0.47}, vine_len[4] = {0.3, 0.46, 0.38, 0.22};
  for (int v = 0; v < 4; ++v) {
    // Over the pot's rim, over the shelf's front edge, then down with a little sway.
    std::vector<Vec3> path = {{vine_x[v], pot_c.y - 0.05, shelf_z + 0.11}, {vine_x[v], shelf_y0 - 0.01, shelf_z + 0.01}};
    for (double t = 0.05; t <= vine_len[v] + 1e-9; t += 0.05)
      path.push_back({vine_x[v] + 0.03 * std::sin(t * 9 + v), shelf_y0 - 0.015 - 0.03 * t, shelf_z - t});
    for (size_t k = 1; k < path.size(); ++k) {
      tube(b, path[k - 1], path[k], 0.0025, 0.0025, 30, 0.002, Vec3{0.40, 0.52, 0.22}, pothos);
      const double side = k % 2 ? 1.0 : -1.0;
      const Vec3 dir = normalized(Vec3{side * 0.8, -0.3, -0.6});
      const Vec3 at = path[k] + Vec3{side * 0.008, -0.006, 0};
      leaf(at, dir, normalized(Vec3{side * 0.2, -1, 0.25}));
      if (v == 1 && k == 4) clicked_leaf = at + dir * 0.018 + Vec3{0, -0.003, 0};
    }
  }
  // Floaters: faint blobs in the air a trainer leaves, none by the cameras (all 1 m or more from them).
  b.depth_jitter = 0;
  b.shape_jitter = 0;
  for (int i = 0, n = int(60 * d); i < n; ++i) {  // fewer than in a larger room: as many in its smaller air would fog it
    const Vec3 p{rng.range(-2.0, 2.0), rng.range(0.1, 1.5), rng.range(0.1, 2.4)};
    b.floater(p, rng.range(0.015, 0.05) * sz, white * rng.range(0.6, 1.05), rng.range(0.05, 0.3));
  }
  // The capture: a serpentine sweep from the doorway, 27 cameras in three passes of nine across
  // the room (each pass 1.7 m wide, at 1.15, 1.45 and 1.75 m, the middle one a step nearer), each
  // turned a little towards the side it is on, held by hand (their own random stream).
  const Vec3 focus{0.0, 1.3, 0.85};
  SplitMix64 hand(409);
  for (int id = 0; id < 27; ++id) {
    const int pass = id / 9, k = id % 9;
    const double x = -0.85 + 1.7 * (pass == 1 ? 8 - k : k) / 8.0;
    const Vec3 wobble{hand.range(-0.04, 0.04), hand.range(-0.04, 0.04), hand.range(-0.04, 0.04)};
    const Vec3 aim{hand.range(-0.1, 0.1), 0, hand.range(-0.06, 0.06)};
    const Vec3 eye = Vec3{x, pass == 1 ? -0.8 : -0.95, 1.15 + 0.3 * pass} + wobble;
    demo.bundle.cameras.push_back(
        named(Camera::look_at(eye, focus + Vec3{0.3 * x, 0, 0} + aim, {0, 0, 1}, opt.width, opt.height, 68.0), id, "sweep"));
  }
  add_task(s, "towel_rail",
           "chrome towel ladder 7 cm off the tiled wall clicked on a bare lower bar, the white tiles showing between its bars, "
           "a bath towel over its top bars (truth: the ladder: uprights, bars, brackets, not the towel)",
           rail, {(rail_x0 + rail_x1) / 2, rail_y - 0.011, rail_z0 + 0.35}, 4);
  add_task(s, "toilet_brush",
           "toilet brush in its holder beside the toilet, the clicked point hidden by the pan from the left of the sweep (truth: "
           "the holder and the brush)",
           brush, brush_c + Vec3{0.052 * std::cos(-1.9), 0.052 * std::sin(-1.9), 0.2}, 9);
  add_task(s, "shower",
           "thin chrome shower riser rail over the bath near the frame's left edge, out of the right views, clicked on its pole "
           "(truth: the shower set: pole, brackets, slider, hand shower, hose)",
           shower, {riser_x, riser_y - 0.011, 1.4}, 13);
  add_task(s, "soap", "tiny bar of soap in a dish on the basin's deck (truth: the soap, not the dish)", soap,
           soap_c + Vec3{0, 0, 0.014}, 22);
  add_task(s, "toilet",
           "compound object: a toilet clicked on its closed lid (truth: the whole toilet: pan, seat, lid, hinges, cistern and its "
           "lid, flush button)",
           toilet, toilet_c + Vec3{0, -0.05, lid_z + 0.011}, 22);
  add_task(s, "conditioner",
           "the right one of two bottles of the same range touching on the bath's rim (truth: that bottle only)", conditioner,
           cond_c + Vec3{0, -bottle_r, 0.08}, 11);
  add_task(s, "hand_towel", "white hand towel on a chrome ring against white tiles of nearly its colour (truth: the towel, not the ring)",
           towel, {ring_c.x, ring_c.y - 0.02, 0.8}, 16);
  add_task(s, "pothos",
           "golden pothos on a shelf clicked on a leaf of a vine hanging over the shelf's front, the wall showing between its "
           "leaves (truth: the plant and its pot)",
           pothos, clicked_leaf, 20);
  return std::move(s);
}

// A laundry room filmed by hand from its doorway as LLFF scenes are taken (24 cameras on a
// small spiral in one plane, winding outwards, all looking the same way, each a little off the
// spiral and its aim), with jittered Gaussians, coarse walls and faint floaters, built as a
// held-out check by a session that had not seen the segmentation method or its tuning: a
// folding A-frame clothes airer in front of the wall, clicked on a bare rail, two socks over its
// top rail; a red step stool parked behind the airer, seen only through its rails; a plastic
// bucket behind a laundry basket heaped with clothes, the clicked point hidden by the basket from
// the left and lower views; a mop leaning on the wall at the frame's left edge, out of the
// right views, clicked on its handle; a wool dryer ball on the washing machine; the washing
// machine clicked on its front (the truth is all of it: body, door, panel, knob, drawer, feet);
// the middle one of three folded towels of one set stacked on a shelf; and a white jug of laundry
// liquid standing on the white machine in front of an off-white wall.
EvalScene laundry(const EvalSetOptions& opt) {
  SceneStart start("laundry", 503);
  auto& [s, demo, g, rng, b] = start;
  const double d = opt.density, sz = 1 / std::sqrt(d);
  const double wall_y = 1.6, side_x = 2.0, room_h = 2.5;
  auto noise = [&](double a) { return Vec3{1, 1, 1} * (a * rng.normal()); };
  const Vec3 white{0.92, 0.92, 0.91}, enamel{0.93, 0.93, 0.92}, steel{0.60, 0.62, 0.65};
  // Metal and glass catch the two lights (the ceiling light, the window at the right) as the view moves.
  const std::vector<std::pair<Vec3, Vec3>> lights = {{{-0.2, -0.3, 1}, {0.3, 0.3, 0.28}}, {{0.7, 0.4, 0.5}, {0.22, 0.24, 0.28}}};
  auto metal_tube = [&](const Vec3& p0, const Vec3& p1, double r, int n, const Vec3& rgb, double shine, int label, double size = 0.004) {
    const Vec3 axis = normalized(p1 - p0);
    const Vec3 side = normalized(cross(axis, std::abs(axis.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0}));
    const Vec3 up = cross(side, axis);
    for (int i = 0; i < n; ++i) {
      const double t = rng.uniform(), a = rng.range(0, 2 * M_PI);
      const Vec3 radial = side * std::cos(a) + up * std::sin(a);
      b.splat(p0 + (p1 - p0) * t + radial * r, radial, size * sz, rgb + noise(0.015), label, 0.04);
      gloss(g, radial, lights, shine, shine * 0.7);
    }
  };
  // Where the washing machine, the laundry basket, the bucket, the airer and the stool stand.
  const Vec3 washer_c{0.25, 1.3, 0};
  const double washer_h = 0.85, washer_front = 1.0;
  const double basket_x0 = 0.72, basket_x1 = 1.2, basket_y0 = 0.55, basket_y1 = 0.93, basket_h = 0.33;
  const Vec3 bucket_c{1.36, 1.3, 0}, stool_c{-0.68, 1.3, 0};
  const double airer_x0 = -1.1, airer_x1 = -0.25, airer_top = 0.92;
  // The room: off-white paint, blotchy, a window at the right of the back wall; grey floor
  // tiles; coarse, loose Gaussians.
  b.depth_jitter = 0.006;
  b.shape_jitter = 0.35;
  const Vec3 paint{0.85, 0.84, 0.80};
  auto wall_rgb = [&](double u, double z) {
    const double blotch = 0.035 * cell_noise(int(std::floor((u + 20) / 0.5)), int(std::floor(z / 0.5)));
    return paint * (0.95 + 0.02 * z) + Vec3{1, 1, 1} * blotch + noise(0.02);
  };
  const double win_x0 = 1.0, win_x1 = 1.8, win_z0 = 1.05, win_z1 = 1.85;
  back_wall(b, side_x, wall_y, room_h, int(14000 * d), 0.045 * sz, 0.02, {{win_x0, win_x1, win_z0, win_z1}},
            wall_rgb);  // up past every view
  b.size_scale = 1.3;  // the side walls only as far forward as any camera sees
  for (double x : {-side_x, side_x})
    for (int i = 0, n = int(1500 * d); i < n; ++i) {
      const Vec3 p{x, rng.range(0.9, wall_y), rng.range(0, room_h)};
      b.splat(p, {x < 0 ? 1.0 : -1.0, 0, 0}, 0.045 * sz, wall_rgb(p.y, p.z) * 0.93, -1, 0.02);
    }
  b.size_scale = 1.25;
  b.depth_jitter = 0.004;
  b.shape_jitter = 0.25;  // looser would fog the lowest 20 cm of everything standing on it
  for (int i = 0, n = int(9000 * d); i < n; ++i) {  // 30 cm floor tiles, none under the machine and the basket
    const Vec3 p{rng.range(-side_x, side_x), rng.range(-0.3, wall_y), 0};
    if ((std::abs(p.x - washer_c.x) < 0.3 && p.y > washer_front) ||
        (p.x > basket_x0 && p.x < basket_x1 && p.y > basket_y0 && p.y < basket_y1))
      continue;
    const bool joint = std::fmod(p.x + 20, 0.3) < 0.015 || std::fmod(p.y + 20, 0.3) < 0.015;
    const Vec3 c = Vec3{0.52, 0.51, 0.49} + Vec3{1, 1, 1} * (0.12 * cell_noise(int((p.x + 20) / 0.3), int((p.y + 20) / 0.3)));
    b.splat(p, {0, 0, 1}, 0.04 * sz, (joint ? Vec3{0.33, 0.32, 0.31} : c) + noise(0.015), -1, 0.04);
  }
  b.size_scale = 1.0;
  b.depth_jitter = 0.002;
  b.shape_jitter = 0.2;
  for (int i = 0, n = int(800 * d); i < n; ++i)  // white skirting board
    b.strip({rng.range(-side_x, side_x), wall_y - 0.012, rng.range(0, 0.08)}, {0, -1, 0}, {1, 0, 0}, 0.03, 0.02, white + noise(0.02), -1,
            0.04);
  for (int i = 0, n = int(1400 * d); i < n; ++i) {  // the window: white frame and a bar, a garden's green under a pale sky
    const double x = rng.range(win_x0, win_x1), z = rng.range(win_z0, win_z1);
    const bool frame = x < win_x0 + 0.045 || x > win_x1 - 0.045 || z < win_z0 + 0.045 || z > win_z1 - 0.045 ||
                       std::abs(x - (win_x0 + win_x1) / 2) < 0.02;
    const Vec3 view = z < 1.35 + 0.1 * std::sin(x * 11) ? Vec3{0.45, 0.55, 0.38} : Vec3{0.80, 0.86, 0.93};
    b.splat({x, wall_y + (frame ? -0.01 : 0.03), z}, {0, -1, 0}, 0.02 * sz, (frame ? white : view) + noise(0.015), -1,
            frame ? 0.03 : 0.08);
  }
  quad(b, {win_x0 - 0.06, wall_y - 0.12, win_z0 - 0.02}, {win_x1 + 0.06, wall_y - 0.12, win_z0 - 0.02},
       {win_x1 + 0.06, wall_y, win_z0 - 0.02}, {win_x0 - 0.06, wall_y, win_z0 - 0.02}, {0, 0, 1}, int(400 * d), 0.015 * sz,
       [&](double, double) { return white + noise(0.015); }, -1, 0.04);  // the sill
  // A peg bag hanging from a hook over the airer: floral cotton, a dark mouth.
  ellipsoid(b, {-0.7, wall_y - 0.05, 1.4}, {0.14, 0.035, 0.17}, int(900 * d) + 60, 0.01 * sz,
            [&](const Vec3& l) {
              if (l.z > 0.1 && l.y < 0 && std::abs(l.x) < 0.08) return Vec3{0.12, 0.10, 0.10};
              return (std::sin(l.x * 60) * std::sin(l.z * 50) > 0.5 ? Vec3{0.85, 0.45, 0.50} : Vec3{0.35, 0.50, 0.62}) + noise(0.02);
            },
            -1, 0.02);
  metal_tube({-0.7, wall_y, 1.6}, {-0.7, wall_y - 0.05, 1.58}, 0.005, 40, steel, 0.5, -1);
  // The shelf over the machine (white, two steel brackets): three folded bath towels of one set
  // stacked on it, a glass jar of pegs, a box of washing powder.
  const double shelf_x0 = -0.3, shelf_x1 = 0.9, shelf_y0 = 1.3, shelf_z = 1.42;
  cuboid(b, {(shelf_x0 + shelf_x1) / 2, (shelf_y0 + wall_y) / 2, shelf_z - 0.0125},
         {(shelf_x1 - shelf_x0) / 2, (wall_y - shelf_y0) / 2, 0.0125}, int(1300 * d), 0.008 * sz,
         [&](const Vec3&, const Vec3& n) { return white * (n.z > 0.5 ? 1.0 : 0.9) + noise(0.015); }, -1);
  for (double x : {shelf_x0 + 0.15, shelf_x1 - 0.15})
    cuboid(b, {x, wall_y - 0.1, shelf_z - 0.1}, {0.012, 0.1, 0.075}, 200, 0.006, one_colour(steel), -1);
  b.depth_jitter = 0.0015;
  b.shape_jitter = 0.25;
  const Vec3 towel_rgb{0.56, 0.66, 0.60};  // sage
  const double towel_h = 0.09;
  auto folded = [&](const Vec3& c, const Vec3& rgb, int label) {  // a folded towel: layers showing at its front, its edges shaded
    cuboid(b, c, {0.17, 0.125, towel_h / 2}, int(3000 * d) + 100, 0.008 * sz,
           [&, rgb](const Vec3& p, const Vec3& n) {
             const double z = p.z / (towel_h / 2);
             Vec3 col = rgb;
             if (std::abs(z) > 0.82) col = rgb * 0.8;
             else if (n.y < -0.5 && (std::abs(z - 0.33) < 0.07 || std::abs(z + 0.33) < 0.07)) col = rgb * 0.86;
             else if (n.y < -0.5 && std::abs(p.x) > 0.14) col = rgb * 0.93;  // its woven border
             return col + noise(0.025);
           },
           label);
  };
  int towels[3];
  const double towel_dx[3] = {0.0, -0.018, 0.012}, towel_dy[3] = {0.0, -0.012, 0.006};
  const double towel_tint[3] = {1.0, 1.03, 0.98};
  for (int k = 0; k < 3; ++k) {
    const Vec3 c{0.17 + towel_dx[k], shelf_y0 + 0.15 + towel_dy[k], shelf_z + towel_h * (k + 0.5)};
    towels[k] = add_object(demo, k == 1 ? "towel" : k == 0 ? "towel_bottom" : "towel_top", c, 0.2f);
    folded(c, towel_rgb * towel_tint[k], towels[k]);
  }
  b.depth_jitter = 0.001;
  b.shape_jitter = 0.15;
  cylinder(b, {0.57, 1.45, shelf_z}, 0.055, 0.055, 0.16, 600, 0.006, Vec3{0.75, 0.80, 0.80}, -1, true);  // the jar
  for (int i = 0; i < 200; ++i) {  // its pegs, in colours
    const double a = rng.range(-M_PI, 0), z = rng.range(0.01, 0.13);
    const Vec3 c = i % 3 == 0 ? Vec3{0.85, 0.3, 0.3} : i % 3 == 1 ? Vec3{0.3, 0.6, 0.85} : Vec3{0.9, 0.8, 0.3};
    b.splat({0.57 + 0.05 * std::cos(a), 1.45 + 0.05 * std::sin(a), shelf_z + z}, {std::cos(a), std::sin(a), 0}, 0.008, c, -1, 0.04);
  }
  cuboid(b, {0.77, 1.46, shelf_z + 0.13}, {0.09, 0.06, 0.13}, int(1000 * d) + 60, 0.008 * sz,
         [&](const Vec3& p, const Vec3&) {
           return (p.z > 0.02 && p.z < 0.08 ? Vec3{0.90, 0.45, 0.12} : Vec3{0.20, 0.40, 0.75}) + noise(0.02);
         },
         -1);
  // The washing machine: a white body on four feet, a grey control panel along the top of its
  // front (a detergent drawer, a display, a knob), a round door (a steel ring round dark glass).
  const int washer = add_object(demo, "washing_machine", washer_c + Vec3{0, -0.05, 0.45}, 0.5f);
  const double wz0 = 0.02;
  cuboid(b, washer_c + Vec3{0, 0, (wz0 + washer_h) / 2}, {0.3, 0.3, (washer_h - wz0) / 2}, int(9000 * d) + 200, 0.013 * sz,
         [&](const Vec3& p, const Vec3& n) {
           if (n.y > -0.5) return enamel * (n.z > 0.5 ? 1.0 : 0.92) + noise(0.012);
           const double z = p.z + (wz0 + washer_h) / 2;  // up its front
           if (z > 0.745) return Vec3{0.83, 0.84, 0.86} + noise(0.012);
           if (z < 0.06) return enamel * 0.85 + noise(0.012);  // the kick plate
           return enamel * 0.97 + noise(0.012);
         },
         washer);
  for (int i = 0; i < 4; ++i)
    cylinder(b, washer_c + Vec3{i % 2 ? 0.25 : -0.25, i / 2 ? 0.25 : -0.25, 0}, 0.018, 0.018, wz0, 40, 0.004,
             Vec3{0.2, 0.2, 0.2}, washer, false);
  const double fy = washer_c.y - 0.3;  // its front's plane
  for (int i = 0, n = int(500 * d) + 40; i < n; ++i) {  // the drawer, its grip a dark slot
    const double x = washer_c.x + rng.range(-0.28, -0.08), z = rng.range(0.755, 0.835);
    b.splat({x, fy - 0.004, z}, {0, -1, 0}, 0.005 * sz, (z < 0.768 && x > washer_c.x - 0.24 && x < washer_c.x - 0.12 ? Vec3{0.3, 0.3, 0.32} : white) + noise(0.012),
            washer, 0.04);
  }
  for (int i = 0, n = int(250 * d) + 30; i < n; ++i) {  // the display, a few green digits
    const double x = washer_c.x + rng.range(-0.03, 0.09), z = rng.range(0.775, 0.815);
    const bool digit = std::sin(x * 220) > 0.6 && std::abs(z - 0.795) < 0.012;
    b.splat({x, fy - 0.003, z}, {0, -1, 0}, 0.004 * sz, digit ? Vec3{0.3, 0.85, 0.5} : Vec3{0.08, 0.09, 0.1}, washer, 0.1);
  }
  metal_tube({washer_c.x + 0.2, fy, 0.795}, {washer_c.x + 0.2, fy - 0.025, 0.795}, 0.028, 200, Vec3{0.78, 0.79, 0.8}, 0.4, washer);  // the knob
  ellipsoid(b, {washer_c.x + 0.2, fy - 0.025, 0.795}, {0.028, 0.004, 0.028}, 120, 0.005, [&](const Vec3& l) {
    return (std::abs(l.x) < 0.004 && l.z > 0 ? Vec3{0.3, 0.3, 0.3} : Vec3{0.82, 0.83, 0.84}) + noise(0.01);
  }, washer, 0.05);
  const Vec3 door_c{washer_c.x, fy - 0.015, 0.43};
  for (int i = 0, n = int(1800 * d) + 100; i < n; ++i) {  // the ring, bulging out
    const double r = std::sqrt(rng.range(0.15 * 0.15, 0.205 * 0.205)), a = rng.range(0, 2 * M_PI);
    const double bulge = std::sin(M_PI * (r - 0.15) / 0.055);
    const Vec3 nrm = normalized(Vec3{-std::cos(a) * 0.6 * std::cos(M_PI * (r - 0.15) / 0.055), -1, -std::sin(a) * 0.6 * std::cos(M_PI * (r - 0.15) / 0.055)});
    const bool grip = a > -0.35 && a < 0.35 && r > 0.19;
    b.splat(door_c + Vec3{r * std::cos(a), -0.008 * bulge, r * std::sin(a)}, nrm, 0.005 * sz,
            (grip ? Vec3{0.35, 0.36, 0.38} : Vec3{0.74, 0.75, 0.77}) + noise(0.015), washer, 0.05);
    gloss(g, nrm, lights, 0.8, 0.6);
  }
  for (int i = 0, n = int(1500 * d) + 100; i < n; ++i) {  // the glass, dark, domed a little into the drum
    const double r = 0.15 * std::sqrt(rng.uniform()), a = rng.range(0, 2 * M_PI);
    const Vec3 nrm = normalized(Vec3{-std::cos(a) * r * 0.8, -1, -std::sin(a) * r * 0.8});
    b.splat(door_c + Vec3{r * std::cos(a), 0.012 * (1 - r * r / 0.0225), r * std::sin(a)}, nrm, 0.006 * sz,
            Vec3{0.22, 0.25, 0.30} + noise(0.015), washer, 0.12);
    gloss(g, nrm, lights, 1.0, 0.8);
  }
  // On the machine: a wool dryer ball near its front, a white jug of laundry liquid (a white
  // cap, a handle, a small pale label) at the back.
  const Vec3 ball_c{washer_c.x - 0.18, 1.1, washer_h + 0.033};
  const int ball = add_object(demo, "dryer_ball", ball_c, 0.05f);
  ellipsoid(b, ball_c, {0.033, 0.033, 0.032}, int(500 * d) + 60, 0.005 * sz,
            [&](const Vec3&) { return Vec3{0.82, 0.56, 0.62} + noise(0.04); }, ball, 0.01);
  const Vec3 jug_c{washer_c.x + 0.17, 1.38, washer_h};
  const int jug = add_object(demo, "laundry_liquid", jug_c + Vec3{0, 0, 0.13}, 0.16f);
  b.depth_jitter = 0.001;
  cuboid(b, jug_c + Vec3{0, 0, 0.12}, {0.085, 0.055, 0.12}, int(2200 * d) + 100, 0.007 * sz,
         [&](const Vec3& p, const Vec3& n) {
           const bool label = n.y < -0.5 && p.z > -0.07 && p.z < 0.03 && std::abs(p.x) < 0.06;
           return (label ? Vec3{0.86, 0.88, 0.91} : Vec3{0.95, 0.95, 0.94}) + noise(0.012);
         },
         jug);
  cylinder(b, jug_c + Vec3{0.035, -0.02, 0.24}, 0.025, 0.024, 0.035, 200, 0.004, Vec3{0.95, 0.95, 0.95}, jug, true);
  for (int k = 0; k < 10; ++k) {  // the handle, a loop at the back corner
    const double a0 = M_PI * k / 10, a1 = M_PI * (k + 1) / 10;
    tube(b, jug_c + Vec3{-0.05, 0.02, 0.17 + 0.05 * std::cos(a0)} + Vec3{0, 0.03 * std::sin(a0), 0},
         jug_c + Vec3{-0.05, 0.02, 0.17 + 0.05 * std::cos(a1)} + Vec3{0, 0.03 * std::sin(a1), 0}, 0.011, 0.011, 30, 0.004,
         Vec3{0.94, 0.94, 0.93}, jug);
  }
  // The airer: a folding A-frame of grey coated steel, two panels of eleven rails between side
  // tubes, leaning together to a top bar; two socks hang over the front panel's top rail.
  const int airer = add_object(demo, "airer", {(airer_x0 + airer_x1) / 2, 0.78, 0.5}, 0.7f);
  auto panel_y = [&](int k, double z) { return k == 0 ? 0.5 + 0.28 * z / airer_top : 1.06 - 0.24 * z / airer_top; };
  const Vec3 grey_coat{0.58, 0.60, 0.63};
  for (int k = 0; k < 2; ++k) {
    for (double x : {airer_x0, airer_x1}) {
      metal_tube({x, panel_y(k, 0.02), 0.02}, {x, panel_y(k, airer_top), airer_top}, 0.01, int(500 * d) + 60, grey_coat, 0.3, airer, 0.007);
      ellipsoid(b, {x, panel_y(k, 0.0), 0.015}, {0.014, 0.014, 0.015}, 50, 0.004, [&](const Vec3&) { return Vec3{0.15, 0.15, 0.15}; },
                airer);  // a foot
    }
    for (int r = 0; r < 11; ++r) {
      const double z = 0.14 + 0.075 * r;
      metal_tube({airer_x0, panel_y(k, z), z}, {airer_x1, panel_y(k, z), z}, 0.007, int(450 * d) + 40, grey_coat, 0.3, airer, 0.007);
    }
  }
  metal_tube({airer_x0 - 0.02, 0.79, airer_top + 0.01}, {airer_x1 + 0.02, 0.79, airer_top + 0.01}, 0.011, int(500 * d) + 40,
             grey_coat * 0.9, 0.3, airer, 0.007);
  const double airer_n = std::hypot(0.28, airer_top);
  const Vec3 front_n{0, -airer_top / airer_n, 0.28 / airer_n}, front_up{0, 0.28 / airer_n, airer_top / airer_n};
  for (double x : {-0.44, -0.34}) {  // the socks, hanging from the top rail down the front panel
    const double z_top = 0.14 + 0.075 * 10;
    const Vec3 top{x, panel_y(0, z_top), z_top};
    const Vec3 rgb = x < -0.4 ? Vec3{0.14, 0.17, 0.30} : Vec3{0.72, 0.20, 0.22};
    for (int i = 0, n = int(500 * d) + 40; i < n; ++i) {
      const double along = rng.range(0, 0.24), across = rng.range(-0.035, 0.035);
      const double foot = along > 0.17 ? (along - 0.17) : 0;  // its foot turns sideways at the bottom
      const Vec3 p = top + front_n * 0.012 - front_up * (along - foot) + Vec3{across + foot * 1.2, 0, 0};
      b.splat(p, front_n, 0.008 * sz, (std::fmod(along, 0.05) < 0.01 ? rgb * 1.3 : rgb) + noise(0.02), -1, 0.01);
    }
  }
  // A red plastic two-step stool parked behind the airer: a tall back block, a low front step,
  // ribbed treads.
  b.depth_jitter = 0.001;
  const int stool = add_object(demo, "step_stool", stool_c + Vec3{0, 0, 0.2}, 0.28f);
  const Vec3 red{0.78, 0.20, 0.15};
  auto ribbed = [&](const Vec3& p, const Vec3& n) {
    return (n.z > 0.5 && std::fmod(p.y + 10, 0.03) < 0.008 ? red * 0.7 : n.z > 0.5 ? red : red * 0.9) + noise(0.02);
  };
  cuboid(b, stool_c + Vec3{0, 0.08, 0.2}, {0.17, 0.1, 0.2}, int(2500 * d) + 100, 0.007 * sz, ribbed, stool);
  cuboid(b, stool_c + Vec3{0, -0.1, 0.11}, {0.17, 0.08, 0.11}, int(1500 * d) + 100, 0.007 * sz, ribbed, stool);
  // A light blue plastic laundry basket on the floor right of the machine, heaped with clothes.
  b.depth_jitter = 0.0015;
  const Vec3 blue_plastic{0.52, 0.72, 0.86};
  auto slotted = [&](double u, double v) {  // rows of slots moulded into its walls
    return (std::fmod(u * 10 + 10, 1.0) < 0.35 && v > 0.25 && v < 0.8 && std::fmod(v * 6, 1.0) < 0.5 ? blue_plastic * 0.6
                                                                                                         : blue_plastic) +
           noise(0.015);
  };
  const double flare = 0.02;
  quad(b, {basket_x0 + flare, basket_y0 + flare, 0}, {basket_x1 - flare, basket_y0 + flare, 0}, {basket_x1, basket_y0, basket_h},
       {basket_x0, basket_y0, basket_h}, {0, -1, 0}, int(2500 * d), 0.007 * sz, slotted, -1, 0.05);
  quad(b, {basket_x0 + flare, basket_y1 - flare, 0}, {basket_x1 - flare, basket_y1 - flare, 0}, {basket_x1, basket_y1, basket_h},
       {basket_x0, basket_y1, basket_h}, {0, 1, 0}, int(1500 * d), 0.007 * sz, slotted, -1, 0.05);
  for (double x : {basket_x0, basket_x1}) {
    const double in = x < bucket_c.x - 0.3 ? flare : -flare;
    quad(b, {x + in, basket_y0 + flare, 0}, {x + in, basket_y1 - flare, 0}, {x, basket_y1, basket_h}, {x, basket_y0, basket_h},
         {x < bucket_c.x - 0.3 ? -1.0 : 1.0, 0, 0}, int(1500 * d), 0.007 * sz,
         [&](double u, double v) {  // a hand hole near its top
           return (std::abs(u - 0.5) < 0.2 && v > 0.75 && v < 0.9 ? Vec3{0.2, 0.25, 0.3} : blue_plastic * 0.95) + noise(0.015);
         },
         -1, 0.05);
  }
  const Vec3 clothes[6] = {{0.93, 0.92, 0.90}, {0.25, 0.35, 0.55}, {0.70, 0.22, 0.25}, {0.55, 0.55, 0.57}, {0.85, 0.75, 0.45}, {0.3, 0.45, 0.35}};
  for (int k = 0; k < 36; ++k) {  // the heap: crumpled garments
    const Vec3 c{rng.range(basket_x0 + 0.08, basket_x1 - 0.08), rng.range(basket_y0 + 0.07, basket_y1 - 0.07), rng.range(0.22, 0.31)};
    const Vec3 rgb = clothes[k % 6];
    const Vec3 r{rng.range(0.04, 0.08), rng.range(0.04, 0.07), rng.range(0.03, 0.05)};
    ellipsoid(b, c, r, int(300 * d) + 40, 0.008 * sz,  // lit from above, creased
              [&, r](const Vec3& l) { return rgb * (0.72 + 0.2 * l.z / r.z + 0.1 * std::sin(l.x * 150 + l.y * 110)) + noise(0.03); }, -1, 0.0);
  }
  // A yellow mop bucket behind the basket, under the window: a flared body, a rim, a dark
  // inside, a wire handle folded back onto its rim.
  const int bucket = add_object(demo, "bucket", bucket_c + Vec3{0, 0, 0.15}, 0.2f);
  const Vec3 yellow{0.93, 0.76, 0.16};
  const double bucket_r0 = 0.11, bucket_r1 = 0.14, bucket_h = 0.34;
  cylinder(b, bucket_c, bucket_r0, bucket_r1, bucket_h, int(2500 * d) + 100, 0.007 * sz, yellow, bucket, false, 0.07);
  cylinder(b, bucket_c + Vec3{0, 0, bucket_h - 0.012}, bucket_r1 + 0.006, bucket_r1 + 0.006, 0.016, 400, 0.005, yellow * 0.9, bucket,
           false);
  for (int i = 0; i < 500; ++i) {  // the inside, in shade
    const double a = rng.range(0, 2 * M_PI), z = rng.range(0.03, bucket_h);
    const double r = bucket_r0 + (bucket_r1 - bucket_r0) * z / bucket_h - 0.004;
    b.splat(bucket_c + Vec3{r * std::cos(a), r * std::sin(a), z}, {-std::cos(a), -std::sin(a), 0}, 0.007, yellow * 0.55 + noise(0.02),
            bucket, 0.03);
  }
  cylinder(b, bucket_c + Vec3{0, 0, 0.02}, bucket_r0 - 0.004, bucket_r0 - 0.004, 0.01, 200, 0.008, yellow * 0.45, bucket, true);
  {
    Vec3 prev;
    for (int k = 0; k <= 16; ++k) {  // the handle: a half circle between lugs at its sides, folded back 60 degrees
      const double a = M_PI * k / 16, r = bucket_r1 + 0.01;
      const Vec3 p = bucket_c + Vec3{r * std::cos(a), 0.866 * r * std::sin(a), bucket_h - 0.03 + 0.5 * r * std::sin(a)};
      if (k > 0) metal_tube(prev, p, 0.003, 30, steel, 0.5, bucket);
      prev = p;
    }
  }
  // A mop leaning on the back wall at the left: a string head on the floor, a green ferrule, a long
  // aluminium handle with a green grip resting on the back wall.
  b.depth_jitter = 0.001;
  b.shape_jitter = 0.2;
  const int mop = add_object(demo, "mop", {-1.65, 1.4, 0.6}, 0.75f);
  const Vec3 mop_foot{-1.5, 1.3, 0.1}, mop_top{-1.8, 1.585, 1.3}, green{0.25, 0.62, 0.35};
  const Vec3 along = normalized(mop_top - mop_foot);
  for (int i = 0, n = int(1500 * d) + 100; i < n; ++i) {  // the handle (larger Gaussians than metal_tube's: at 3 m it is 3 px wide)
    const Vec3 side = normalized(cross(along, Vec3{1, 0, 0})), up = cross(side, along);
    const double t = rng.range(0.06, norm(mop_top - mop_foot) - 0.14), a = rng.range(0, 2 * M_PI);
    const Vec3 radial = side * std::cos(a) + up * std::sin(a);
    b.splat(mop_foot + along * t + radial * 0.014, radial, 0.009 * sz, Vec3{0.72, 0.74, 0.78} + noise(0.015), mop, 0.04);
    gloss(g, radial, lights, 0.4, 0.3);
  }
  tube(b, mop_top - along * 0.14, mop_top, 0.017, 0.017, 200, 0.009, green, mop);
  tube(b, mop_foot - along * 0.02, mop_foot + along * 0.06, 0.035, 0.014, 200, 0.005, green, mop);
  for (int k = 0; k < 110; ++k) {  // the strings, from the ferrule down over the floor
    const double a = rng.range(0, 2 * M_PI), reach = rng.range(0.08, 0.17);
    const Vec3 end{mop_foot.x + reach * std::cos(a), mop_foot.y + reach * std::sin(a), 0.008};
    const Vec3 from = mop_foot + Vec3{0.02 * std::cos(a), 0.02 * std::sin(a), -0.02};
    const Vec3 rgb = Vec3{0.86, 0.84, 0.78} * rng.range(0.85, 1.0);
    for (int j = 0; j < 8; ++j) {
      const double t = (j + 0.5) / 8;
      const Vec3 p = from + (end - from) * t + Vec3{0, 0, 0.03 * std::sin(M_PI * t)};
      b.strip(p, normalized(Vec3{std::cos(a), std::sin(a), 0.8}), end - from, 0.014, 0.008, rgb + noise(0.02), mop, 0.01);
    }
  }
  // Floaters: faint blobs in the air a trainer leaves, none by the cameras (all 1.5 m or more from them).
  b.depth_jitter = 0;
  b.shape_jitter = 0;
  for (int i = 0, n = int(60 * d); i < n; ++i) {
    const Vec3 p{rng.range(-1.9, 1.9), rng.range(0.0, 1.5), rng.range(0.1, 2.3)};
    b.floater(p, rng.range(0.015, 0.05) * sz, paint * rng.range(0.6, 1.05), rng.range(0.05, 0.25));
  }
  // The capture: 24 cameras on a spiral of 2.75 turns in the plane 1.5 m in front of the doorway's
  // middle, winding out to 33 cm across and 20 cm up, all looking the same way (down 14 degrees),
  // held by hand (their own random stream).
  const Vec3 eye_c{0.0, -1.7, 1.45}, look = normalized(Vec3{0, 3.3, -0.8});
  SplitMix64 hand(521);
  for (int id = 0; id < 24; ++id) {
    const double t = id / 23.0, r = 0.05 + 0.28 * t, a = 2 * M_PI * 2.75 * t;
    const Vec3 wobble{hand.range(-0.02, 0.02), hand.range(-0.03, 0.03), hand.range(-0.02, 0.02)};
    const Vec3 aim{hand.range(-0.08, 0.08), 0, hand.range(-0.06, 0.06)};
    const Vec3 eye = eye_c + Vec3{r * std::cos(a), 0, 0.6 * r * std::sin(a)} + wobble;
    demo.bundle.cameras.push_back(
        named(Camera::look_at(eye, eye + look * 3.0 + aim, {0, 0, 1}, opt.width, opt.height, 66.0), id, "spiral"));
  }
  add_task(s, "airer",
           "folding clothes airer clicked on a bare rail, the floor, the wall and its back panel's rails showing between its rails, "
           "two socks over its top rail (truth: the airer: rails, side tubes, top bar, feet, not the socks)",
           airer, Vec3{-0.8, panel_y(0, 0.14 + 0.075 * 5), 0.14 + 0.075 * 5} + front_n * 0.005, 3);
  add_task(s, "step_stool", "red step stool parked behind the airer, seen only through its rails (truth: the stool)", stool,
           stool_c + Vec3{0.05, -0.021, 0.3}, 8, 20);
  add_task(s, "bucket",
           "yellow bucket behind a laundry basket heaped with clothes, the clicked point hidden by the basket from the left of "
           "the spiral (truth: the bucket with its handle)",
           bucket, bucket_c + Vec3{std::cos(-1.8), std::sin(-1.8), 0} * (bucket_r0 + (bucket_r1 - bucket_r0) * 0.21 / bucket_h + 0.002) + Vec3{0, 0, 0.21}, 9);
  add_task(s, "mop",
           "mop leaning into the corner at the frame's left edge, out of the right views, clicked on its thin handle (truth: the "
           "whole mop: handle, grip, ferrule, strings)",
           mop, mop_foot + along * 0.7 + Vec3{0, -0.012, 0}, 10);
  add_task(s, "dryer_ball", "tiny wool dryer ball on the washing machine (truth: the ball)", ball, ball_c + Vec3{0, -0.03, 0.012}, 5);
  add_task(s, "washing_machine",
           "compound object: a washing machine clicked on its white front below the door (truth: the whole machine: body, door "
           "ring and glass, control panel, drawer, knob, feet)",
           washer, {washer_c.x + 0.1, fy - 0.001, 0.17}, 16);
  add_task(s, "towel", "the middle one of three folded towels of one set stacked on a shelf (truth: that towel only)", towels[1],
           Vec3{0.17 + towel_dx[1], shelf_y0 + 0.15 + towel_dy[1] - 0.126, shelf_z + towel_h * 1.5}, 20);
  add_task(s, "laundry_liquid",
           "white jug of laundry liquid standing on the white washing machine, the off-white wall behind it (truth: the jug with "
           "its cap and handle)",
           jug, jug_c + Vec3{0, -0.056, 0.15}, 7);
  return std::move(s);
}

EvalScene orbit_demo(const EvalSetOptions& opt) {
  EvalScene s;
  s.name = "orbit";
  DemoSceneOptions o;
  o.width = opt.width;
  o.height = opt.height;
  o.density = opt.density;
  s.scene = make_demo_scene(o);
  for (size_t k = 0; k < s.scene.objects.size(); ++k) {
    EvalTaskSpec t;
    t.name = s.name + "/" + s.scene.objects[k].name;
    t.kind = "clean orbit object";
    t.object = int(k);
    if (!demo_click(s.scene, int(k), t.camera, t.x, t.y)) throw Error("evaluation set: no camera shows " + t.name);
    s.tasks.push_back(t);
  }
  return s;
}

}  // namespace

bool find_click(const DemoScene& demo, int object, const Vec3& anchor, int first_camera, double search_px,
                int& camera, double& x, double& y) {
  std::vector<bool> truth(demo.labels.size());
  for (size_t i = 0; i < truth.size(); ++i) truth[i] = demo.labels[i] == object;
  const size_t n = demo.bundle.cameras.size();
  for (size_t k = 0; k < n; ++k) {
    const size_t c = (size_t(std::max(0, first_camera)) + k) % n;
    const Camera& cam = demo.bundle.cameras[c];
    double u, v;
    if (!cam.project(anchor, u, v)) continue;
    const double margin = 0.04 * cam.width;
    if (u < margin || v < margin || u > cam.width - margin || v > cam.height - margin) continue;
    RenderSettings s;
    s.color = false;
    s.depth = false;
    const Image cover = render_selection(demo.bundle.gaussians, cam, truth, s);
    double best = 1e30;
    const int r = int(std::ceil(search_px));
    for (int py = int(v) - r; py <= int(v) + r; ++py)
      for (int px = int(u) - r; px <= int(u) + r; ++px) {
        if (px < 0 || py < 0 || px >= cam.width || py >= cam.height) continue;
        const double dd = (px + 0.5 - u) * (px + 0.5 - u) + (py + 0.5 - v) * (py + 0.5 - v);
        if (dd > search_px * search_px || dd >= best || cover.at(px, py) < 0.95f) continue;
        best = dd;
        x = px;
        y = py;
      }
    if (best < 1e30) {
      camera = int(c);
      return true;
    }
  }
  return false;
}

namespace {

// Spherical interpolation between unit quaternions (the shorter way round).
Quat slerp(Quat a, Quat b, double t) {
  double d = a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z;
  if (d < 0) {
    b = {-b.w, -b.x, -b.y, -b.z};
    d = -d;
  }
  double wa = 1 - t, wb = t;
  if (d < 0.9995) {
    const double angle = std::acos(d);
    wa = std::sin((1 - t) * angle) / std::sin(angle);
    wb = std::sin(t * angle) / std::sin(angle);
  }
  return Quat{wa * a.w + wb * b.w, wa * a.x + wb * b.x, wa * a.y + wb * b.y, wa * a.z + wb * b.z}.normalized();
}

}  // namespace

void densify_cameras(std::vector<Camera>& cams, int factor) {
  if (factor <= 1 || cams.size() < 2) return;
  std::vector<Camera> out;
  for (size_t i = 0; i < cams.size(); ++i) {
    out.push_back(cams[i]);
    if (i + 1 == cams.size()) break;
    const Camera& a = cams[i];
    const Camera& b = cams[i + 1];
    const Quat qa = Quat::from_matrix(a.R), qb = Quat::from_matrix(b.R);
    const Vec3 ca = a.center(), cb = b.center();
    for (int k = 1; k < factor; ++k) {
      const double t = double(k) / factor;
      Camera c = a;
      c.R = slerp(qa, qb, t).to_matrix();
      c.t = -(c.R * (ca + (cb - ca) * t));
      out.push_back(c);
    }
  }
  const size_t cut = cams[0].name.rfind('_');
  const std::string prefix = cut == std::string::npos ? cams[0].name : cams[0].name.substr(0, cut);
  for (size_t i = 0; i < out.size(); ++i) out[i] = named(out[i], int(i), prefix.c_str());
  cams = std::move(out);
}

std::vector<EvalScene> make_eval_scenes(const EvalSetOptions& opt) {
  std::vector<EvalScene> out;
  out.push_back(garden(opt));
  out.push_back(alcove(opt));
  out.push_back(courtyard(opt, false));
  out.push_back(courtyard(opt, true));
  out.push_back(orbit_demo(opt));
  out.push_back(patio(opt));
  out.push_back(study(opt));
  out.push_back(kitchen(opt));
  out.push_back(museum(opt));
  out.push_back(lounge(opt));
  out.push_back(porch(opt));
  out.push_back(workshop(opt));
  out.push_back(atrium(opt));
  out.push_back(playroom(opt));
  out.push_back(office(opt));
  out.push_back(garage(opt));
  out.push_back(bedroom(opt));
  out.push_back(bathroom(opt));
  out.push_back(laundry(opt));
  if (opt.camera_factor > 1)
    for (EvalScene& s : out) {
      densify_cameras(s.scene.bundle.cameras, opt.camera_factor);
      for (EvalTaskSpec& t : s.tasks) t.camera *= opt.camera_factor;  // camera i is now i * factor
    }
  return out;
}

std::vector<Click> task_clicks(const EvalScene& scene, const EvalTaskSpec& task, int count) {
  const Click own = pixel_centre_click(task.x, task.y, 1);
  if (count <= 1) return {own};
  const Camera& cam = scene.scene.bundle.cameras[size_t(task.camera)];
  const Image truth = render_selection(scene.scene.bundle.gaussians, cam, demo_object_mask(scene.scene, task.object));
  return clicks_drawn_on(truth, task.name, own, count);
}

std::vector<Click> clicks_drawn_on(const Image& mask, const std::string& name, const Click& own, int count, int inset) {
  std::vector<Click> clicks = {own};
  auto on = [&](int x, int y) {
    for (int c = 0; c < mask.channels; ++c)
      if (mask.at(x, y, c) > 0.5f) return true;
    return false;
  };
  std::vector<std::pair<int, int>> inside;
  for (int y = inset; y < mask.height - inset; ++y)
    for (int x = inset; x < mask.width - inset; ++x) {
      bool all = true;
      for (int dy = -inset; dy <= inset && all; ++dy)
        for (int dx = -inset; dx <= inset && all; ++dx) all = on(x + dx, y + dy);
      if (all) inside.push_back({x, y});
    }
  uint64_t seed = 1469598103934665603ull;  // FNV-1a of the name
  for (char ch : name) seed = (seed ^ uint8_t(ch)) * 1099511628211ull;
  SplitMix64 rng(seed);
  for (int k = 1; k < count && !inside.empty(); ++k) {
    const auto& [x, y] = inside[size_t(rng.uniform() * double(inside.size()))];
    clicks.push_back(pixel_centre_click(x, y, 1));
  }
  return clicks;
}

}  // namespace isegman
