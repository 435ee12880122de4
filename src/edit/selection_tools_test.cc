#include "edit/selection_tools.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/sh.h"
#include "edit/test_scenes.h"

namespace isegman::edit {
namespace {

GaussianScene line() {  // Gaussians at x = 0..9, opacity logit = x - 5, log-scale = -x
  GaussianScene s;
  s.resize(10, 0);
  for (size_t i = 0; i < 10; ++i) {
    s.positions[3 * i] = float(i);
    s.opacity[i] = float(i) - 5.f;
    s.scales[3 * i + 1] = -float(i);
    s.scales[3 * i] = s.scales[3 * i + 2] = -20.f;
  }
  return s;
}

std::vector<bool> flags(std::initializer_list<int> on, size_t n = 10) {
  std::vector<bool> m(n, false);
  for (int i : on) m[size_t(i)] = true;
  return m;
}

TEST(SelectionTools, ShapesInsideAndOutside) {
  const GaussianScene s = line();
  EXPECT_EQ(select_box(s, {2, -1, -1}, {4, 1, 1}).mask, flags({2, 3, 4}));
  EXPECT_EQ(select_box(s, {2, -1, -1}, {4, 1, 1}, Region::kOutside).mask, flags({0, 1, 5, 6, 7, 8, 9}));
  EXPECT_EQ(select_sphere(s, {7, 0, 0}, 1.0).mask, flags({6, 7, 8}));
  EXPECT_EQ(select_sphere(s, {7, 0, 0}, 1.0, Region::kOutside).count(), 7u);
  EXPECT_EQ(select_box(s, {2, -1, -1}, {4, 1, 1}).scene_fingerprint, s.fingerprint());
  EXPECT_THROW(select_box(s, {5, 0, 0}, {4, 1, 1}), Error);
  EXPECT_THROW(select_sphere(s, {0, 0, 0}, 0), Error);
  EXPECT_THROW(select_sphere(s, {NAN, 0, 0}, 1), Error);
}

TEST(SelectionTools, Thresholds) {
  const GaussianScene s = line();
  // sigmoid(x - 5) >= 0.5 for x >= 5; <= sigmoid(2) for x <= 7.
  EXPECT_EQ(select_opacity(s, 0.5, 1.0 / (1.0 + std::exp(-2.0))).mask, flags({5, 6, 7}));
  // Largest scale exp(-x) in [e^-3, e^-1] -> x in 1..3 (with a little slack for float).
  EXPECT_EQ(select_size(s, std::exp(-3.0) * 0.999, std::exp(-1.0) * 1.001).mask, flags({1, 2, 3}));
  EXPECT_THROW(select_opacity(s, 0.8, 0.2), Error);
  EXPECT_THROW(select_size(s, NAN, 1), Error);
}

TEST(SelectionTools, SetAlgebra) {
  const GaussianScene s = line();
  const Selection a = Selection::from_mask(s, flags({1, 2, 3}));
  const Selection b = Selection::from_mask(s, flags({3, 4}));
  EXPECT_EQ(unite(a, b).mask, flags({1, 2, 3, 4}));
  EXPECT_EQ(subtract(a, b).mask, flags({1, 2}));
  EXPECT_EQ(intersect(a, b).mask, flags({3}));
  EXPECT_EQ(invert(a).mask, flags({0, 4, 5, 6, 7, 8, 9}));
  GaussianScene other = s;
  other.opacity[0] = 3.f;
  EXPECT_THROW(unite(a, Selection::all_of(other)), Error);
}

TEST(SelectionTools, GrowAddsNeighbours) {
  const GaussianScene s = line();
  const Selection seed = Selection::from_mask(s, flags({5}));
  EXPECT_EQ(grow(s, seed, 2).mask, flags({4, 5, 6}));
  EXPECT_EQ(grow(s, seed, 2, 0, 2).mask, flags({3, 4, 5, 6, 7}));
  EXPECT_EQ(grow(s, seed, 4, 1.5).mask, flags({4, 5, 6}));  // limited by distance
  EXPECT_THROW(grow(s, seed, 0), Error);
  EXPECT_TRUE(grow(s, Selection::none_of(s), 3).empty());
  // k = 0: every neighbour within a radius in scene units.
  EXPECT_EQ(grow(s, seed, 0, 2.0).mask, flags({3, 4, 5, 6, 7}));
  EXPECT_EQ(grow(s, seed, 0, 1.0, 2).mask, flags({3, 4, 5, 6, 7}));
  EXPECT_THROW(grow(s, seed, 0, -1), Error);
}

TEST(SelectionTools, ShrinkErodesTheBorder) {
  const GaussianScene s = line();
  const Selection run = Selection::from_mask(s, flags({2, 3, 4, 5, 6}));
  // Each end has an unselected nearest neighbour; the middle ones do not.
  EXPECT_EQ(shrink(s, run, 2).mask, flags({3, 4, 5}));
  EXPECT_EQ(shrink(s, run, 2, 0, 2).mask, flags({4}));
  EXPECT_EQ(shrink(s, run, 0, 1.0).mask, flags({3, 4, 5}));
  EXPECT_EQ(shrink(s, run, 0, 2.0).mask, flags({4}));
  // Everything selected has no unselected neighbour: nothing changes.
  EXPECT_EQ(shrink(s, Selection::all_of(s), 3).count(), 10u);
  // Shrink undoes a grow of a lone seed's neighbours back to the seed here.
  const Selection seed = Selection::from_mask(s, flags({5}));
  EXPECT_EQ(shrink(s, grow(s, seed, 2), 2).mask, flags({5}));
  EXPECT_THROW(shrink(s, run, 2, 0, 0), Error);
}

TEST(SelectionTools, SimilarColour) {
  GaussianScene s = line();
  for (size_t i = 0; i < 10; ++i) {  // base colour (i / 10, 0.5, 0.5)
    float* c = s.sh_of(i);
    c[0] = rgb_to_sh_dc(float(i) / 10.f);
  }
  const Vec3 c3 = base_color(s, 3);
  EXPECT_NEAR(c3.x, 0.3, 1e-6);
  EXPECT_NEAR(c3.y, 0.5, 1e-6);
  EXPECT_EQ(select_similar_color(s, c3, 0.1001).mask, flags({2, 3, 4}));
  EXPECT_EQ(select_similar_color(s, c3, 0).mask, flags({3}));
  EXPECT_EQ(select_similar_color(s, {0.3, 0.9, 0.5}, 0.2).count(), 0u);
  EXPECT_THROW(select_similar_color(s, c3, -1), Error);
}

}  // namespace
}  // namespace isegman::edit
