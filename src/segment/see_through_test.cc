#include "segment/see_through.h"

#include <gtest/gtest.h>

#include <cmath>

namespace isegman::segment {
namespace {

// A scene of small round splats, added one at a time.
struct Splats {
  GaussianScene scene;
  void add(double x, double y, double z, double size) {
    scene.sh_degree = 0;
    scene.positions.insert(scene.positions.end(), {float(x), float(y), float(z)});
    const float ls = float(std::log(size));
    scene.scales.insert(scene.scales.end(), {ls, ls, ls});
    scene.sh.insert(scene.sh.end(), {0.5f, 0.5f, 0.5f});
    scene.rotations.insert(scene.rotations.end(), {1.f, 0.f, 0.f, 0.f});
    scene.opacity.push_back(5);  // opaque
  }
  // A square sheet facing the camera at depth z.
  void sheet(double x0, double x1, double y0, double y1, double z, double step = 0.02) {
    for (double y = y0; y <= y1; y += step)
      for (double x = x0; x <= x1; x += step) add(x, y, z, step * 0.6);
  }
};

const Camera kCamera = Camera::look_at({0, 0, 0}, {0, 0, 1}, {0, -1, 0}, 160, 160, 50);

TEST(SeeThrough, BarsInFrontOfTheClickedSurfaceAreFoundAndCutBehind) {
  Splats s;
  s.sheet(-1, 1, -1, 1, 4.0);                                      // the object, clicked
  for (double x = -0.9; x <= 0.9; x += 0.3) s.sheet(x, x + 0.08, -1, 1, 3.8);  // vertical bars
  PreparedFrame frame = prepare_frame(s.scene, kCamera);
  // Clicked between two bars (x = 0.15 on the object).
  const Occluders o = find_occluders(s.scene, frame, 80 + 0.15 / 4.0 * kCamera.fx, 80.5);
  ASSERT_TRUE(o.found) << "share " << o.share << " surface " << o.surface;
  EXPECT_NEAR(o.surface, 4.0, 0.02);
  EXPECT_GT(o.share, 0.05);
  EXPECT_GT(o.cut, 3.8);  // behind the bars ...
  EXPECT_LT(o.cut, 4.0);  // ... in front of the object
}

TEST(SeeThrough, TheClickedSurfacesOwnNearerPartsStayBehindTheCut) {
  // A coarse surface (a far pillar of a few large Gaussians) has parts a few per cent nearer
  // than where it is clicked, flanked by it like an occluder: strips at 3.90 and 3.85 before
  // the surface at 4.0. The occluders proper, bars at 3.0, lie beyond a wider gap; the cut
  // falls behind them and before the strips, so those stay in the peeled render.
  Splats s;
  s.sheet(-1, 1, -1, 1, 4.0);
  for (double x = -0.9; x <= 0.9; x += 0.3) s.sheet(x, x + 0.08, -1, 1, 3.0);
  s.sheet(0.22, 0.27, -1, 1, 3.9, 0.01);
  s.sheet(-0.1, -0.05, -1, 1, 3.85, 0.01);
  const double x = 80 + 0.15 / 4.0 * kCamera.fx;
  const Occluders o = find_occluders(s.scene, prepare_frame(s.scene, kCamera), x, 80.5);
  ASSERT_TRUE(o.found) << "share " << o.share;
  EXPECT_NEAR(o.surface, 4.0, 0.02);
  EXPECT_GT(o.cut, 3.0);
  EXPECT_LT(o.cut, 3.85);
}

TEST(SeeThrough, NothingInFrontOrOnlyGroundBelowIsNoOccluder) {
  Splats open;
  open.sheet(-1, 1, -1, 1, 4.0);
  PreparedFrame a = prepare_frame(open.scene, kCamera);
  EXPECT_FALSE(find_occluders(open.scene, a, 80.5, 80.5).found);
  // Something nearer below the click (ground in front of an object's foot) is not flanked
  // by the clicked surface on both sides: no see-through.
  Splats ground = open;
  ground.sheet(-1, 1, 0.25, 1, 3.6);
  PreparedFrame b = prepare_frame(ground.scene, kCamera);
  const Occluders o = find_occluders(ground.scene, b, 80.5, 86.5);  // the ground starts ~6 px below
  EXPECT_NEAR(o.surface, 4.0, 0.02);
  EXPECT_FALSE(o.found) << "share " << o.share;
}

TEST(SeeThrough, AClickedPixelHalfCoveredByTheNearerThingIsNoGap) {
  // The bars of the first test, and a faint veil (a coarse surface's nearer Gaussians) over
  // the clicked pixel only: the click sees its surface at 4.0 through ~45 % of nearer weight.
  Splats s;
  s.sheet(-1, 1, -1, 1, 4.0);
  for (double x = -0.9; x <= 0.9; x += 0.3) s.sheet(x, x + 0.08, -1, 1, 3.8);
  const double x = 80 + 0.15 / 4.0 * kCamera.fx;
  const Occluders clear = find_occluders(s.scene, prepare_frame(s.scene, kCamera), x, 80.5);
  ASSERT_TRUE(clear.found);
  EXPECT_LT(clear.click_front_weight, 0.05);  // through a gap: the surface seen clearly
  s.add(0.15 * 3.9 / 4.0, 0, 3.9, 0.05);
  s.scene.opacity.back() = -0.2f;  // alpha ~0.45 at its centre
  const Occluders veiled = find_occluders(s.scene, prepare_frame(s.scene, kCamera), x, 80.5);
  EXPECT_NEAR(veiled.surface, 4.0, 0.02);
  EXPECT_GT(veiled.click_front_weight, 0.3);
  EXPECT_FALSE(veiled.found);
  SeeThroughOptions any_weight;  // the bars are still there: only the veil stops the peel
  any_weight.max_click_front_weight = 1;
  EXPECT_TRUE(find_occluders(s.scene, prepare_frame(s.scene, kCamera), x, 80.5, any_weight).found);
}

TEST(SeeThrough, BarsStandApartFromWhatTheClickShowsWhereNearerLeavesTouchIt) {
  // Every Gaussian is in SAM's mask at the click, which holds the nearer things: bars at 3.8
  // before a surface at 4.0 (an enclosure), and foliage of layers every 0.02 from 3.8 to 4.0
  // whose splats touch the next layer's (a plant's nearer leaves running on into the clicked
  // ones). The cut falls at 3.91 in both.
  auto contact = [](const Splats& s, double cut) {
    std::vector<uint32_t> shown(s.scene.size());
    for (uint32_t j = 0; j < shown.size(); ++j) shown[j] = j;
    Occluders occ;
    occ.found = true;
    occ.cut = cut;
    occ.surface = 4.0;
    const CentreIndex index(s.scene, 1);
    return enclosure_contact(s.scene, index, kCamera, shown, occ, 80.5, 80.5, SeeThroughOptions(), 1);
  };
  Splats bars;
  bars.sheet(-1, 1, -1, 1, 4.0);
  for (double x = -0.9; x <= 0.9; x += 0.3) bars.sheet(x, x + 0.08, -1, 1, 3.8);
  Splats leaves;
  for (int k = 0; k <= 10; ++k) leaves.sheet(-1, 1, -1, 1, 3.8 + 0.02 * k);
  const double apart = contact(bars, 3.91), touching = contact(leaves, 3.91);
  EXPECT_EQ(apart, 0.0);
  // The layers at 3.92-4.00 lie at the clicked depth; the one at 3.92 touches the cut-away 3.90.
  EXPECT_NEAR(touching, 0.2, 0.02);
  EXPECT_GT(touching, SeeThroughOptions().max_enclosure_touch);
  // Nothing at the clicked depth around the click: no contact to speak of.
  EXPECT_EQ(contact(bars, 4.5), 0.0);
}

}  // namespace
}  // namespace isegman::segment
