#include "segment/background_gate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "core/random.h"

namespace isegman::segment {
namespace {

// A 64x64 view whose background is the plane with inverse depth `inv(x, y)` (affine in the
// pixel coordinates: any plane is), a mask square [24, 40)^2 and, inside it, an object at depth 3.
struct PlaneView {
  Image mask{64, 64, 1}, depth{64, 64, 1}, alpha{64, 64, 1, 1.f};
  static double inv(int x, int y) { return 0.2 + 0.0004 * x - 0.0003 * y; }
  PlaneView() {
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        const bool in = x >= 24 && x < 40 && y >= 24 && y < 40;
        mask.at(x, y) = in ? 1.f : 0.f;
        depth.at(x, y) = in ? 3.f : float(1.0 / inv(x, y));
      }
  }
};

TEST(BackgroundGate, InterpolatesThePlaneAroundTheMaskExactly) {
  PlaneView v;
  const Image bg = background_inverse_depth(v.mask, v.depth, v.alpha, 2.9);
  int estimated = 0;
  double worst = 0;
  for (int y = 24; y < 40; ++y)
    for (int x = 24; x < 40; ++x) {
      if (bg.at(x, y) <= 0) continue;
      ++estimated;
      worst = std::max(worst, std::abs(bg.at(x, y) - PlaneView::inv(x, y)) / PlaneView::inv(x, y));
    }
  std::printf("[ plane ] %d of 256 mask pixels estimated, worst relative error %.2g\n", estimated, worst);
  EXPECT_EQ(estimated, 256);
  EXPECT_LT(worst, 1e-5);
  for (int x = 0; x < 64; ++x) EXPECT_EQ(bg.at(x, 10), 0.f);  // nothing outside the mask
  // Background nearer than the limit (an occluder around the object) is no sample.
  const Image none = background_inverse_depth(v.mask, v.depth, v.alpha, 6.0);
  for (float b : none.data) EXPECT_EQ(b, 0.f);
}

TEST(BackgroundGate, AFloorComingNearerBelowTheMaskStillCounts) {
  // A floor seen at a grazing angle: its inverse depth grows fast downwards. The samples
  // just below the mask lie beyond the near limit, the pixels that show the floor goes on
  // further down are nearer than it, and they are still the floor.
  PlaneView v;
  auto inv = [](int y) { return 0.2 + 0.004 * y; };
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      if (v.mask.at(x, y) < 0.5f) v.depth.at(x, y) = float(1.0 / inv(y));
  const double limit = 0.99 / inv(42);  // just in front of the sample 2 pixels below the mask
  BackgroundOptions all_lines;
  all_lines.min_directions = 4;
  const Image bg = background_inverse_depth(v.mask, v.depth, v.alpha, limit, all_lines);
  int estimated = 0;
  for (int y = 24; y < 40; ++y)
    for (int x = 24; x < 40; ++x) {
      if (bg.at(x, y) <= 0) continue;
      ++estimated;
      EXPECT_NEAR(bg.at(x, y), inv(y), 1e-5 * inv(y));
    }
  std::printf("[ floor ] %d of 256 mask pixels estimated by all four lines\n", estimated);
  EXPECT_EQ(estimated, 256);
}

TEST(BackgroundGate, AThinBarInFrontOfThePlaneIsNoSurface) {
  // Rails 3 px high just above and below the mask, nearer than the plane (like the rails
  // of a screen whose one slat SAM masked): lines that end on them must not pull the
  // estimate forward. Estimates either do not exist or lie on the plane.
  PlaneView v;
  for (int y : {20, 21, 22, 41, 42, 43})
    for (int x = 0; x < 64; ++x) v.depth.at(x, y) = 4.0f;
  // One direction is enough here, so the rows (which see only the plane) give estimates.
  BackgroundOptions one;
  one.min_directions = 1;
  const Image bg = background_inverse_depth(v.mask, v.depth, v.alpha, 2.9, one);
  int estimated = 0;
  for (int y = 24; y < 40; ++y)
    for (int x = 24; x < 40; ++x) {
      if (bg.at(x, y) <= 0) continue;
      ++estimated;
      EXPECT_NEAR(bg.at(x, y), PlaneView::inv(x, y), 1e-5 * PlaneView::inv(x, y)) << x << "," << y;
    }
  std::printf("[ rails ] %d of 256 mask pixels estimated, all on the plane\n", estimated);
  EXPECT_EQ(estimated, 256);
  // Without the check that a sample's surface goes on, the columns end on the rails and
  // disagree with the rows: no pixel keeps an estimate on the plane.
  one.extent = 0;
  const Image unchecked = background_inverse_depth(v.mask, v.depth, v.alpha, 2.9, one);
  int on_plane = 0;
  for (int y = 24; y < 40; ++y)
    for (int x = 24; x < 40; ++x)
      on_plane += std::abs(unchecked.at(x, y) - PlaneView::inv(x, y)) < 1e-5 * PlaneView::inv(x, y);
  EXPECT_EQ(on_plane, 0);
}

// Gaussians seen in the middle of the mask of a camera at the origin looking along +z, in
// front of a wall at z = 5: scale (sx, sy, sz), no rotation.
struct GateScene {
  GaussianScene scene;
  Camera cam = Camera::look_at({0, 0, 0}, {0, 0, 1}, {0, -1, 0}, 64, 64, 60);
  Image mask{64, 64, 1}, depth{64, 64, 1, 5.f}, alpha{64, 64, 1, 1.f};
  ViewVotes positive;
  GateScene() {
    for (int y = 16; y < 48; ++y)
      for (int x = 16; x < 48; ++x) mask.at(x, y) = 1.f;
  }
  void add(double x, double y, double z, double sx, double sy, double sz) {
    const uint32_t g = uint32_t(scene.size());
    scene.positions.insert(scene.positions.end(), {float(x), float(y), float(z)});
    scene.scales.insert(scene.scales.end(), {std::log(float(sx)), std::log(float(sy)), std::log(float(sz))});
    scene.rotations.insert(scene.rotations.end(), {1, 0, 0, 0});
    scene.opacity.push_back(0);
    positive.index.push_back(g);
    positive.weight.push_back(int64_t(1) << 24);
  }
};

TEST(BackgroundGate, ARingsHoleTakesThePlaneTheSurroundingsLieOn) {
  // A ring lying on a floor, seen from above at a slant: the floor's inverse depth grows
  // downwards, and below the mask it is nearer than the ring's near side, so the column
  // and both diagonals through the hole end on refused samples and the rows alone do not
  // make the two lines an estimate needs. The floor around the mask lies on one plane.
  PlaneView v;
  auto inv = [](double x, double y) { return 0.2 + 0.0002 * x + 0.002 * y; };
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      if (v.mask.at(x, y) < 0.5f) v.depth.at(x, y) = float(1.0 / inv(x + 0.5, y + 0.5));
  const double limit = 1.0 / inv(32, 32);  // the ring's near side: the floor at the hole's depth
  BackgroundOptions lines_only;
  lines_only.plane = false;
  const Image before = background_inverse_depth(v.mask, v.depth, v.alpha, limit, lines_only);
  const Image after = background_inverse_depth(v.mask, v.depth, v.alpha, limit);
  int lines = 0, plane = 0;
  for (int y = 24; y < 40; ++y)
    for (int x = 24; x < 40; ++x) {
      lines += before.at(x, y) > 0;
      if (after.at(x, y) <= 0) continue;
      ++plane;
      EXPECT_NEAR(after.at(x, y), inv(x + 0.5, y + 0.5), 1e-5 * inv(x + 0.5, y + 0.5)) << x << "," << y;
      EXPECT_LE(after.at(x, y), 1.0 / limit * (1 + 1e-6));  // never nearer than the target's near side
    }
  std::printf("[ ring's hole ] %d of 256 mask pixels estimated by the lines, %d with the plane\n", lines, plane);
  EXPECT_LT(lines, 64);
  EXPECT_GE(plane, 120);  // the mask's far half, behind the near side
  EXPECT_GT(after.at(32, 26), 0.f);
  EXPECT_EQ(after.at(32, 38), 0.f);  // nearer than the ring's near side: no background there

  // Surroundings on no one plane (a clutter of depths): no plane, nothing added.
  PlaneView clutter;
  uint32_t h = 12345;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      if (clutter.mask.at(x, y) < 0.5f) {
        h = h * 1664525u + 1013904223u;
        clutter.depth.at(x, y) = 4.0f + float(h >> 8) / float(1 << 24) * 4.0f;
      }
  const Image none = background_inverse_depth(clutter.mask, clutter.depth, clutter.alpha, 2.0);
  for (float b : none.data) EXPECT_EQ(b, 0.f);

  // The plane on two sides only (left and above; clutter right and below) is not
  // extrapolated across the mask, however few samples the plane needs.
  PlaneView side = clutter;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      if (side.mask.at(x, y) < 0.5f && (x < 24 || y < 24)) side.depth.at(x, y) = float(1.0 / inv(x + 0.5, y + 0.5));
  BackgroundOptions any_share;
  any_share.plane_min_share = 0.01;
  const Image two_sides = background_inverse_depth(side.mask, side.depth, side.alpha, 2.0, any_share);
  int from_two_sides = 0;
  for (int y = 24; y < 40; ++y)
    for (int x = 24; x < 40; ++x) from_two_sides += two_sides.at(x, y) > 0 && x > 30 && y > 30;
  EXPECT_EQ(from_two_sides, 0);
}

TEST(BackgroundGate, OnlyGaussiansLyingInTheSurroundingSurfaceBecomeNeutral) {
  GateScene s;
  s.add(-0.2, -0.2, 5.0, 0.05, 0.05, 0.002);  // 0: a flat piece of the wall seen through a gap
  s.add(0.2, -0.2, 4.0, 0.05, 0.05, 0.002);   // 1: the object, 20 % nearer
  s.add(-0.2, 0.2, 5.0, 0.002, 0.05, 0.05);   // 2: standing across the wall (an object's side touching it)
  s.add(0.2, 0.2, 5.05, 0.03, 0.03, 0.03);    // 3: a round Gaussian just behind the wall's surface
  ASSERT_EQ(s.scene.size(), 4u);
  const Image bg = background_inverse_depth(s.mask, s.depth, s.alpha, 3.8);
  ViewVotes positive = s.positive, neutral;
  EXPECT_EQ(gate_background(s.scene, s.cam, bg, {}, positive, neutral), 2u);
  EXPECT_EQ(positive.index, (std::vector<uint32_t>{1, 2}));
  EXPECT_EQ(neutral.index, (std::vector<uint32_t>{0, 3}));
  EXPECT_EQ(neutral.weight[0], int64_t(1) << 24);
  // Into an existing neutral list, kept ascending.
  ViewVotes p2 = s.positive, n2;
  n2.index = {1};
  n2.weight = {5};
  p2.index = {0, 2, 3};
  p2.weight = {7, 8, 9};
  EXPECT_EQ(gate_background(s.scene, s.cam, bg, {}, p2, n2), 2u);
  EXPECT_EQ(n2.index, (std::vector<uint32_t>{0, 1, 3}));
  EXPECT_EQ(n2.weight, (std::vector<int64_t>{7, 5, 9}));
}

TEST(BackgroundGate, NeverTakesTheClickedSurfaceOrMostOfTheSelection) {
  GateScene s;
  s.add(-0.2, -0.2, 5.0, 0.05, 0.05, 0.002);
  s.add(0.2, -0.2, 4.0, 0.05, 0.05, 0.002);
  const Image bg = background_inverse_depth(s.mask, s.depth, s.alpha, 3.8);
  double u, v;
  ASSERT_TRUE(s.cam.project({-0.2, -0.2, 5.0}, u, v));
  // A click on the Gaussian that lies in the wall: the object is not told from the wall here.
  BackgroundTarget clicked;
  clicked.seeds.push_back({u, v});
  ViewVotes positive = s.positive, neutral;
  EXPECT_EQ(gate_background(s.scene, s.cam, bg, clicked, positive, neutral), 0u);
  EXPECT_EQ(positive.index.size(), 2u);
  EXPECT_TRUE(neutral.index.empty());
  // The current selection is that Gaussian: the same.
  const std::vector<bool> selection = {true, false};
  BackgroundTarget selected;
  selected.selection = &selection;
  EXPECT_EQ(gate_background(s.scene, s.cam, bg, selected, positive, neutral), 0u);
  // A click on the nearer Gaussian: the wall's becomes neutral.
  ASSERT_TRUE(s.cam.project({0.2, -0.2, 4.0}, u, v));
  BackgroundTarget other;
  other.seeds.push_back({u, v});
  EXPECT_EQ(gate_background(s.scene, s.cam, bg, other, positive, neutral), 1u);
  EXPECT_EQ(neutral.index, (std::vector<uint32_t>{0}));
}

TEST(BackgroundGate, NeverTakesAClickedSurfaceOnTheSurroundingsThatNoCentreLiesNear) {
  // A coarse target (a far pillar of a few large Gaussians, running from the floor to the
  // ceiling around it) may have no Gaussian centred within seed_radius of a click; the
  // clicked pixel's rendered depth still says whether the target lies in front of the
  // surroundings' surface.
  GateScene s;
  s.add(-0.2, -0.2, 5.0, 0.05, 0.05, 0.002);  // 0: lies in the surroundings' surface
  s.add(0.2, -0.2, 4.0, 0.05, 0.05, 0.002);   // 1: 20 % nearer
  const Image bg = background_inverse_depth(s.mask, s.depth, s.alpha, 3.8);
  const double u = 32.5, v = 40.5;  // about 10 pixels below both centres
  for (uint32_t g : {0u, 1u}) {
    double gu, gv;
    ASSERT_TRUE(s.cam.project(s.scene.position(g), gu, gv));
    ASSERT_GT(std::abs(gv - v), 2 * BackgroundOptions().seed_radius);
  }
  ASSERT_GT(bg.at(int(u), int(v)), 0.f);
  auto moved = [&](double clicked_depth) {
    BackgroundTarget t;
    t.seeds.push_back({u, v, clicked_depth});
    ViewVotes positive = s.positive, neutral;
    return gate_background(s.scene, s.cam, bg, t, positive, neutral);
  };
  EXPECT_EQ(moved(5.0), 0u);  // the clicked pixel on the surroundings' surface
  EXPECT_EQ(moved(5.3), 0u);  // ... or behind it
  EXPECT_EQ(moved(4.0), 1u);  // in front of it: the Gaussian lying in the surface goes
  EXPECT_EQ(moved(0.0), 1u);  // its depth not known: the centres near the click alone decide
}

TEST(BackgroundGate, StandsAsideWhenMostOfWhatItWouldMoveLiesFarBehindTheSurface) {
  // A background hides what lies behind it. A pillar running from the floor to the ceiling
  // around it has the surroundings' surface interpolated through it: its clicked front lies
  // just in front of that surface, much of the rest far behind it, which no real background
  // would let through. Behind a clearly nearer target (a fence's pickets) it is what the
  // gaps show.
  auto moved = [](double clicked_depth, int on_surface, int far_behind, const BackgroundOptions& o,
                  double behind_depth = 5.6) {  // 11 % behind
    GateScene s;
    s.add(0.2, -0.2, clicked_depth, 0.03, 0.03, 0.03);  // 0: the clicked front
    for (int i = 0; i < on_surface; ++i) s.add(-0.3 + 0.1 * i, -0.2, 5.0, 0.03, 0.03, 0.002);
    for (int i = 0; i < far_behind; ++i) s.add(-0.3 + 0.1 * i, 0.2, behind_depth, 0.03, 0.03, 0.03);
    const Image bg = background_inverse_depth(s.mask, s.depth, s.alpha, 3.8);
    double u, v;
    EXPECT_TRUE(s.cam.project({0.2, -0.2, clicked_depth}, u, v));
    BackgroundTarget clicked;
    clicked.seeds.push_back({u, v});
    ViewVotes positive = s.positive, neutral;
    return gate_background(s.scene, s.cam, bg, clicked, positive, neutral, o);
  };
  const BackgroundOptions o;
  const double pillar = 4.9;  // 2 % in front: outside the tolerance, not clearly in front
  EXPECT_EQ(moved(pillar, 3, 0, o), 3u);  // a wall seen through gaps
  EXPECT_EQ(moved(pillar, 3, 1, o), 4u);  // ... and a little seen far behind it: still a background
  EXPECT_EQ(moved(pillar, 1, 2, o), 0u);  // mostly far behind: the estimate runs through the target
  EXPECT_EQ(moved(pillar, 0, 3, o), 0u);
  EXPECT_EQ(moved(4.0, 1, 2, o), 3u);     // a front 20 % nearer: its gaps show them
  // Slats 0.8 % in front of a wall narrow the tolerance to 0.4 %; wall Gaussians 1.6 % behind
  // its surface are far behind that, but not behind the wall's own tolerance (1 %) thrice.
  EXPECT_EQ(moved(4.96, 1, 2, o, 5.08), 3u);
  BackgroundOptions off;
  off.max_far_behind = 1;
  EXPECT_EQ(moved(pillar, 1, 2, off), 3u);  // the rule off
}

TEST(BackgroundGate, ATargetJustInFrontOfTheWallNarrowsTheTolerance) {
  // Slats 4 cm before a wall 5 m away: 0.8 % nearer in inverse depth, inside the fixed 1 %.
  GateScene s;
  s.add(0.2, -0.2, 4.96, 0.05, 0.05, 0.05);   // 0: the clicked slat
  s.add(-0.2, -0.2, 5.005, 0.03, 0.03, 0.03); // 1: the wall seen between the slats, 0.1 % behind
  s.add(-0.2, 0.2, 4.99, 0.03, 0.03, 0.03);   // 2: wall noise, 0.2 % in front
  const Image bg = background_inverse_depth(s.mask, s.depth, s.alpha, 3.8);
  double u, v;
  ASSERT_TRUE(s.cam.project({0.2, -0.2, 4.96}, u, v));
  BackgroundTarget clicked;
  clicked.seeds.push_back({u, v});
  ViewVotes positive = s.positive, neutral;
  EXPECT_EQ(gate_background(s.scene, s.cam, bg, clicked, positive, neutral), 2u);
  EXPECT_EQ(positive.index, (std::vector<uint32_t>{0}));
  EXPECT_EQ(neutral.index, (std::vector<uint32_t>{1, 2}));
  // With the fixed tolerance the slat lies "in" the wall, so the gate stands aside.
  BackgroundOptions fixed;
  fixed.min_tolerance = 0;
  ViewVotes p2 = s.positive, n2;
  EXPECT_EQ(gate_background(s.scene, s.cam, bg, clicked, p2, n2, fixed), 0u);
  // A target lying in the surface itself (a poster on the wall) is not narrowed down to.
  GateScene poster;
  poster.add(0.2, -0.2, 4.999, 0.05, 0.05, 0.05);
  poster.add(-0.2, -0.2, 5.0, 0.03, 0.03, 0.03);
  ASSERT_TRUE(poster.cam.project({0.2, -0.2, 4.999}, u, v));
  BackgroundTarget on_wall;
  on_wall.seeds.push_back({u, v});
  ViewVotes p3 = poster.positive, n3;
  EXPECT_EQ(gate_background(poster.scene, poster.cam, bg, on_wall, p3, n3), 0u);
}

TEST(BackgroundGate, ClickedGaussiansWithoutAnEstimateAreJudgedByTheNearestWithOne) {
  // Where too few lines across the mask agree at the click there is no estimate, so the
  // clicked Gaussian tells nothing of where the target lies; the nearest Gaussians with an
  // estimate do. A rule lying on a bench: its part 8 px from the click lies in the bench's
  // surface, so the view cannot tell it from the bench and moves nothing. A target clearly
  // in front: the bench seen beside it goes.
  auto moved = [](double near_part_depth, const BackgroundOptions& o) {
    GateScene s;
    s.add(-1.15, -1.15, 5.0, 0.05, 0.05, 0.002);           // 0: the bench, lying in the surface, ~14 px off
    s.add(0.0, 0.1, near_part_depth, 0.05, 0.05, 0.002);   // 1: the clicked Gaussian
    s.add(0.67, 0.1, near_part_depth, 0.05, 0.05, 0.002);  // 2: the target 8-10 px to the right
    Image bg = background_inverse_depth(s.mask, s.depth, s.alpha, 3.8);
    double u, v, u2, v2;
    EXPECT_TRUE(s.cam.project(s.scene.position(1), u, v));
    EXPECT_TRUE(s.cam.project(s.scene.position(2), u2, v2));
    EXPECT_GT(std::abs(u2 - u), 2 * o.seed_radius);
    EXPECT_LT(std::abs(u2 - u), 4 * o.seed_radius);
    for (int y = int(v) - 3; y <= int(v) + 3; ++y)  // no estimate around the click
      for (int x = int(u) - 3; x <= int(u) + 3; ++x) bg.at(x, y) = 0.f;
    EXPECT_GT(bg.at(int(u2), int(v2)), 0.f);
    BackgroundTarget clicked;
    clicked.seeds.push_back({u, v});
    ViewVotes positive = s.positive, neutral;
    return gate_background(s.scene, s.cam, bg, clicked, positive, neutral, o);
  };
  const BackgroundOptions o;
  EXPECT_EQ(moved(4.99, o), 0u);  // the rule 0.2 % proud of the bench: nothing
  EXPECT_EQ(moved(4.0, o), 1u);   // 25 % in front: the bench beside it
  BackgroundOptions clicked_only = o;  // judged by the clicked Gaussian alone, which says nothing
  clicked_only.max_seed_radius = o.seed_radius;
  EXPECT_EQ(moved(4.99, clicked_only), 2u);  // the bench and the rule's part with it
  EXPECT_EQ(moved(4.0, clicked_only), 1u);
}

TEST(BackgroundGate, OffsetsCountFromWhereTheSurroundingsGaussiansLie) {
  // A clean wall renders in front of its Gaussians' centres (blending favours the nearer
  // ones): here it renders at 5 while its Gaussians lie at 5.05. A thin object 3.5 cm in
  // front of them (a ladle's handle) then lies 0.3 % behind the rendered surface, "in" the wall.
  auto build = [](double jitter, GateScene& s, ViewVotes& total) {
    SplitMix64 rng(11);
    for (int v = 0; v < 64; ++v)
      for (int u = 0; u < 64; ++u) {
        const int d = std::max({16 - u, u - 47, 16 - v, v - 47});  // pixels outside the mask square
        if (d < 3 || d > 10 || (u + v) % 3 != 0) continue;
        const double z = 5.05 + jitter * (2 * rng.uniform() - 1);
        s.add((u + 0.5 - s.cam.cx) * z / s.cam.fx, (v + 0.5 - s.cam.cy) * z / s.cam.fy, z, 0.02, 0.02, 0.002);
      }
    total = s.positive;
    s.positive = ViewVotes{};
    s.add(-0.2, -0.2, 5.05, 0.03, 0.03, 0.03);   // the wall's Gaussians seen through a gap
    s.add(0.2, -0.2, 5.015, 0.03, 0.03, 0.03);   // the object
    const ViewVotes mask_votes = s.positive;
    total.index.insert(total.index.end(), mask_votes.index.begin(), mask_votes.index.end());
    total.weight.insert(total.weight.end(), mask_votes.weight.begin(), mask_votes.weight.end());
  };
  GateScene s;
  ViewVotes total;
  build(0.0, s, total);
  const Image bg = background_inverse_depth(s.mask, s.depth, s.alpha, 3.8);
  const BackgroundOptions o;
  const SurroundingsSurface surface = surroundings_surface(s.scene, s.cam, s.mask, s.depth, s.alpha, total, 3.8, o);
  std::printf("[ clean wall ] the surroundings' Gaussians lie at %.4f, tolerance %.4f\n", surface.offset, surface.tolerance);
  EXPECT_NEAR(surface.offset, 5.0 / 5.05 - 1, 1e-4);
  EXPECT_DOUBLE_EQ(surface.tolerance, o.min_tolerance);
  const uint32_t wall = s.positive.index[0], object = s.positive.index[1];
  ViewVotes positive = s.positive, neutral;
  EXPECT_EQ(gate_background(s.scene, s.cam, bg, {}, positive, neutral, o, 1, surface), 1u);
  EXPECT_EQ(positive.index, (std::vector<uint32_t>{object}));
  EXPECT_EQ(neutral.index, (std::vector<uint32_t>{wall}));
  // Measured from the rendered surface, the object goes with the wall.
  ViewVotes p2 = s.positive, n2;
  EXPECT_EQ(gate_background(s.scene, s.cam, bg, {}, p2, n2, o, 1), 2u);
  // Threads do not change the measure.
  const SurroundingsSurface two = surroundings_surface(s.scene, s.cam, s.mask, s.depth, s.alpha, total, 3.8, o, 2);
  EXPECT_EQ(two.offset, surface.offset);
  EXPECT_EQ(two.tolerance, surface.tolerance);

  // A trained wall's Gaussians scatter +-1.2 % about it: the object is within that scatter,
  // the tolerance grows to the fixed one, and the object is not told from the wall.
  GateScene noisy;
  build(0.06, noisy, total);
  const SurroundingsSurface rough = surroundings_surface(noisy.scene, noisy.cam, noisy.mask, noisy.depth, noisy.alpha, total, 3.8, o);
  std::printf("[ noisy wall ] the surroundings' Gaussians lie at %.4f, tolerance %.4f\n", rough.offset, rough.tolerance);
  EXPECT_NEAR(rough.offset, 5.0 / 5.05 - 1, 2e-3);
  EXPECT_DOUBLE_EQ(rough.tolerance, o.tolerance);
  ViewVotes p3 = noisy.positive, n3;
  EXPECT_EQ(gate_background(noisy.scene, noisy.cam, bg, {}, p3, n3, o, 1, rough), 2u);

  // Too few Gaussians around the mask, or the measure switched off: the rendered surface.
  BackgroundOptions few = o;
  few.min_spread_samples = 100000;
  const SurroundingsSurface none = surroundings_surface(s.scene, s.cam, s.mask, s.depth, s.alpha, total, 3.8, few);
  EXPECT_EQ(none.offset, 0.0);
  EXPECT_LT(none.tolerance, 0.0);
  BackgroundOptions off = o;
  off.spread_scale = 0;
  EXPECT_LT(surroundings_surface(s.scene, s.cam, s.mask, s.depth, s.alpha, total, 3.8, off).tolerance, 0.0);
}

TEST(BackgroundGate, NearDepthIsTheWeightedNearSide) {
  GateScene s;
  s.add(0, 0, 2.0, 0.01, 0.01, 0.01);
  s.add(0, 0, 3.0, 0.01, 0.01, 0.01);
  s.add(0, 0, 4.0, 0.01, 0.01, 0.01);
  s.positive.weight = {1, 8, 1};
  EXPECT_NEAR(near_depth(s.scene, s.cam, s.positive, 0.05), 2.0, 1e-6);
  EXPECT_NEAR(near_depth(s.scene, s.cam, s.positive, 0.5), 3.0, 1e-6);
  EXPECT_EQ(near_depth(s.scene, s.cam, ViewVotes{}, 0.05), 0.0);
}

TEST(BackgroundGate, NearDepthMatchesTheSortedWalk) {
  // Many Gaussians on a few depths (ties), or on depths spread over a range with a few far
  // outliers (the histogram's bins then hold uneven shares), with uneven weights: the
  // selection finds the same depth as walking the (depth, weight)-sorted list until the
  // running weight reaches the share, on one worker and on all.
  SplitMix64 rng(7);
  for (int trial = 0; trial < 40; ++trial) {
    GateScene s;
    const bool spread = trial % 2 == 1;
    const int n = 1 + int(rng.next() % (spread ? 20000 : 400));
    s.positive = ViewVotes{};
    for (int i = 0; i < n; ++i) {
      const double z = spread ? (rng.next() % 50 == 0 ? 40.0 + double(rng.next() % 1000) : 2.0 + double(rng.next() % 100000) * 1e-5)
                              : 2.0 + double(rng.next() % 9) * 0.25;
      s.add(0, 0, z, 0.01, 0.01, 0.01);
      s.positive.weight.back() = int64_t(1 + rng.next() % 5000);
    }
    for (double share : {0.0, 0.05, 0.5, 0.97, 1.0}) {
      std::vector<std::pair<double, double>> dw;
      double total = 0;
      for (size_t k = 0; k < s.positive.index.size(); ++k) {
        const uint32_t g = s.positive.index[k];
        dw.push_back({s.cam.world_to_camera({s.scene.positions[3 * g], s.scene.positions[3 * g + 1],
                                             s.scene.positions[3 * g + 2]}).z,
                      double(s.positive.weight[k])});
        total += dw.back().second;
      }
      std::sort(dw.begin(), dw.end());
      double walk = dw.back().first, run = 0;
      for (const auto& [d, w] : dw)
        if ((run += w) >= share * total) {
          walk = d;
          break;
        }
      EXPECT_EQ(near_depth(s.scene, s.cam, s.positive, share), walk) << "trial " << trial << " share " << share;
      EXPECT_EQ(near_depth(s.scene, s.cam, s.positive, share, 0), walk) << "trial " << trial << " share " << share;
    }
  }
}

TEST(BackgroundGate, TheSurroundingsIndexReadsTheSameGaussiansAsAPassOverTheView) {
  // 600,000 Gaussians (every 2nd of the view's list is read) scattered about a wall at depth
  // 5 in a 300 x 200 view; small masks at random places. Read through the index (only the
  // cells around each mask), the surroundings' surface is the same, to the bit.
  SplitMix64 rng(5);
  const Camera cam = Camera::look_at({0, 0, 0}, {0, 0, 1}, {0, -1, 0}, 300, 200, 60);
  GaussianScene scene;
  ViewVotes total;
  for (uint32_t i = 0; i < 600000; ++i) {
    const double u = rng.uniform() * 340 - 20, v = rng.uniform() * 240 - 20, z = 5 * (1 + 0.02 * (rng.uniform() - 0.5));
    const Vec3 p = cam.camera_to_world({(u - cam.cx) * z / cam.fx, (v - cam.cy) * z / cam.fy, z});
    scene.positions.insert(scene.positions.end(), {float(p.x), float(p.y), float(p.z)});
    total.index.push_back(i);
    total.weight.push_back(int64_t(1 + rng.next() % 1000));
  }
  const SurroundingsIndex index = surroundings_index(scene, cam, total);
  ASSERT_EQ(index.votes, total.index.size());
  EXPECT_GT(index.entries.size(), 200000u);  // of the 300,000 read, those in the image (~73 %)
  Image depth(300, 200, 1, 5.f), alpha(300, 200, 1, 1.f);
  BackgroundOptions o;
  o.spread_scale = 1.0;
  int compared = 0;
  for (int trial = 0; trial < 12; ++trial) {
    Image mask(300, 200, 1);
    const int x0 = int(rng.uniform() * 280), y0 = int(rng.uniform() * 180), mw = 4 + int(rng.uniform() * 40),
              mh = 4 + int(rng.uniform() * 30);
    for (int y = y0; y < std::min(200, y0 + mh); ++y)
      for (int x = x0; x < std::min(300, x0 + mw); ++x) mask.at(x, y) = 1.f;
    for (int threads : {1, 2}) {
      const SurroundingsSurface pass = surroundings_surface(scene, cam, mask, depth, alpha, total, 4.0, o, threads);
      const SurroundingsSurface filed = surroundings_surface(scene, cam, mask, depth, alpha, total, 4.0, o, threads, &index);
      EXPECT_EQ(filed.offset, pass.offset) << "trial " << trial;
      EXPECT_EQ(filed.tolerance, pass.tolerance) << "trial " << trial;
      compared += pass.tolerance >= 0;
    }
  }
  EXPECT_GE(compared, 20);  // nearly every mask had surroundings to measure
  // An index of another list is not used.
  ViewVotes shorter = total;
  shorter.index.pop_back();
  shorter.weight.pop_back();
  Image mask(300, 200, 1);
  for (int y = 90; y < 110; ++y)
    for (int x = 140; x < 160; ++x) mask.at(x, y) = 1.f;
  const SurroundingsSurface a = surroundings_surface(scene, cam, mask, depth, alpha, shorter, 4.0, o, 1);
  const SurroundingsSurface b = surroundings_surface(scene, cam, mask, depth, alpha, shorter, 4.0, o, 1, &index);
  EXPECT_EQ(a.offset, b.offset);
  EXPECT_EQ(a.tolerance, b.tolerance);
}

}  // namespace
}  // namespace isegman::segment
