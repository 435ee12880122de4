#include "edit/screen_selection.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"

namespace isegman::edit {
namespace {

// Two layers of a 20 x 20 grid of Gaussians facing a camera on the -z side: an opaque
// front layer at z = 0 and a back layer at z = 1 it hides (indices 400..799).
struct Layers {
  GaussianScene scene;
  Camera camera = Camera::look_at({0, 0, -4}, {0, 0, 0}, {0, -1, 0}, 200, 160, 50);
};

Layers layers() {
  Layers l;
  GaussianScene& s = l.scene;
  s.resize(800, 0);
  for (size_t i = 0; i < 800; ++i) {
    const size_t k = i % 400;
    s.positions[3 * i] = float(-1.0 + 2.0 * double(k % 20) / 19);
    s.positions[3 * i + 1] = float(-1.0 + 2.0 * double(k / 20) / 19);
    s.positions[3 * i + 2] = i < 400 ? 0.f : 1.f;
    for (int a = 0; a < 3; ++a) s.scales[3 * i + a] = std::log(0.09f);
    s.opacity[i] = 6.f;  // ~0.998: the front layer blocks the back one
  }
  return l;
}

std::vector<bool> by_projection(const Layers& l, bool (*in)(double u, double v)) {
  std::vector<bool> m(l.scene.size());
  for (size_t i = 0; i < m.size(); ++i) {
    double u, v;
    m[i] = l.camera.project(l.scene.position(i), u, v) && in(u, v);
  }
  return m;
}

TEST(ScreenSelection, RectangleTakesTheCentresInside) {
  const Layers l = layers();
  ScreenShape rect{ShapeKind::kRect, {{120, 100}, {60, 40}}, 0};  // corners in any order
  const Selection s = select_in_shape(l.scene, l.camera, rect);
  const auto want = by_projection(l, [](double u, double v) {
    // Pixel centres in [60, 120] x [40, 100]: the pixels 60..119 x 40..99 (centres 60.5 ..).
    const int x = int(u), y = int(v);
    return x >= 60 && x <= 119 && y >= 40 && y <= 99;
  });
  EXPECT_EQ(s.mask, want);
  EXPECT_GT(s.count(), 20u);
  EXPECT_LT(s.count(), 400u);
  EXPECT_EQ(s.scene_fingerprint, l.scene.fingerprint());
}

TEST(ScreenSelection, LassoAndBrushRegions) {
  // A right triangle: even-odd fill of pixel centres (its edge passes no centre).
  ScreenShape tri{ShapeKind::kLasso, {{0, 0}, {10.3, 0}, {0, 10.3}}, 0};
  const PixelRegion t = rasterize_shape(tri, 20, 20, 20, 20);
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 20; ++x) EXPECT_EQ(t.contains(x, y), x + 0.5 + y + 0.5 < 10.3) << x << "," << y;
  // The same triangle at half resolution scales.
  EXPECT_EQ(rasterize_shape(tri, 20, 20, 10, 10).count(), 15u);  // centres with x + y + 1 < 5.15
  // A brush dot of radius 2 around (5, 5): the 12 pixels whose centres lie within 2.
  ScreenShape dot{ShapeKind::kBrush, {{5, 5}}, 2};
  EXPECT_EQ(rasterize_shape(dot, 20, 20, 20, 20).count(), 12u);
  // A stroke sweeps the segment between its points.
  ScreenShape stroke{ShapeKind::kBrush, {{2, 10}, {18, 10}}, 1};
  const PixelRegion s = rasterize_shape(stroke, 20, 20, 20, 20);
  for (int x = 2; x < 18; ++x) EXPECT_TRUE(s.contains(x, 9) && s.contains(x, 10)) << x;
  EXPECT_FALSE(s.contains(10, 12));
}

TEST(ScreenSelection, LassoSelectsByProjectedCentre) {
  const Layers l = layers();
  ScreenShape tri{ShapeKind::kLasso, {{20, 20}, {180, 20}, {20, 140}}, 0};
  const Selection s = select_in_shape(l.scene, l.camera, tri);
  const PixelRegion r = rasterize_shape(tri, 200, 160, 200, 160);
  for (size_t i = 0; i < l.scene.size(); ++i) {
    double u, v;
    ASSERT_TRUE(l.camera.project(l.scene.position(i), u, v));
    EXPECT_EQ(s.mask[i], r.contains(int(u), int(v))) << i;
  }
}

TEST(ScreenSelection, VisibleSurfaceOnlySkipsHiddenGaussians) {
  const Layers l = layers();
  ScreenShape rect{ShapeKind::kRect, {{0, 0}, {200, 160}}, 0};
  const Selection all = select_in_shape(l.scene, l.camera, rect);
  ScreenSelectOptions o;
  o.visible_only = true;
  const Selection visible = select_in_shape(l.scene, l.camera, rect, o);
  size_t front = 0, back = 0;
  for (size_t i = 0; i < 800; ++i) {
    if (!visible.mask[i]) continue;
    EXPECT_TRUE(all.mask[i]);
    (i < 400 ? front : back)++;
  }
  size_t front_all = 0;
  for (size_t i = 0; i < 400; ++i) front_all += all.mask[i];
  EXPECT_EQ(front, front_all);  // every front Gaussian in the frame shows
  EXPECT_LT(back, all.count() - front_all);  // the covered back ones do not
  // Rendered at a lower resolution the verdict is the same for this scene.
  o.max_side = 100;
  EXPECT_EQ(select_in_shape(l.scene, l.camera, rect, o).mask, visible.mask);
}

TEST(ScreenSelection, GaussianUnderThePixel) {
  const Layers l = layers();
  // The front Gaussian whose centre projects nearest the image centre is on top there.
  double u, v;
  ASSERT_TRUE(l.camera.project(l.scene.position(0), u, v));
  const int64_t g = gaussian_at(l.scene, l.camera, u, v);
  EXPECT_EQ(g, 0);
  EXPECT_THROW(gaussian_at(l.scene, l.camera, -1, 5), Error);
  GaussianScene far = l.scene;
  for (size_t i = 0; i < far.size(); ++i) far.positions[3 * i] += 100.f;
  EXPECT_EQ(gaussian_at(far, l.camera, 100, 80), -1);
}

TEST(ScreenSelection, RefusesBadShapes) {
  const Layers l = layers();
  EXPECT_THROW(select_in_shape(l.scene, l.camera, {ShapeKind::kRect, {{0, 0}}, 0}), Error);
  EXPECT_THROW(select_in_shape(l.scene, l.camera, {ShapeKind::kLasso, {{0, 0}, {1, 1}}, 0}), Error);
  EXPECT_THROW(select_in_shape(l.scene, l.camera, {ShapeKind::kBrush, {{0, 0}}, 0}), Error);
  EXPECT_THROW(select_in_shape(l.scene, l.camera, {ShapeKind::kRect, {{0, NAN}, {1, 1}}, 0}), Error);
  EXPECT_THROW(parse_shape_kind("circle"), Error);
  ScreenSelectOptions o;
  o.min_weight = 2;
  EXPECT_THROW(select_in_shape(l.scene, l.camera, {ShapeKind::kRect, {{0, 0}, {5, 5}}, 0}, o), Error);
}

}  // namespace
}  // namespace isegman::edit
