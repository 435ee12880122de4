#include "core/virtual_views.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/random.h"

namespace isegman {
namespace {

// A unit-cube cloud around (10, 0, 5) plus 2% far, faint and bright outliers.
GaussianScene cloud_with_outliers() {
  SplitMix64 r(4);
  GaussianScene s;
  s.resize(5000, 0);
  for (size_t i = 0; i < s.size(); ++i) {
    const bool outlier = i % 50 == 0;
    const double spread = outlier ? 1000.0 : 1.0;
    s.positions[3 * i] = float(10 + r.range(-spread, spread));
    s.positions[3 * i + 1] = float(r.range(-spread, spread));
    s.positions[3 * i + 2] = float(5 + r.range(-spread, spread));
    s.opacity[i] = outlier && i % 100 == 0 ? -6.0f : 2.0f;
  }
  return s;
}

TEST(VirtualViews, RobustBoundsIgnoreFarOutliers) {
  const GaussianScene s = cloud_with_outliers();
  const RobustBounds b = robust_bounds(s);
  EXPECT_NEAR(b.center.x, 10, 0.2);
  EXPECT_NEAR(b.center.y, 0, 0.2);
  EXPECT_NEAR(b.center.z, 5, 0.2);
  EXPECT_LT(b.radius, 2.0);
  Vec3 lo, hi;
  s.bounds(lo, hi);
  EXPECT_GT(hi.x - lo.x, 1000);  // the raw box would be useless
  EXPECT_THROW(robust_bounds(GaussianScene{}), Error);
}

TEST(VirtualViews, EveryLayoutLooksAtTheCentreAndSeesTheScene) {
  const GaussianScene s = cloud_with_outliers();
  const RobustBounds b = robust_bounds(s);
  for (VirtualLayout layout : {VirtualLayout::kOrbit, VirtualLayout::kSphere, VirtualLayout::kForward}) {
    VirtualViewOptions o;
    o.count = 12;
    o.width = 320;
    o.height = 240;
    o.layout = layout;
    const std::vector<Camera> cams = make_virtual_views(s, {}, o);
    ASSERT_EQ(cams.size(), 12u);
    for (size_t k = 0; k < cams.size(); ++k) {
      const Camera& c = cams[k];
      c.validate("virtual");
      EXPECT_EQ(c.width, 320);
      char want[32];  // room for any size_t
      std::snprintf(want, sizeof(want), "virtual_%03zu", k);
      EXPECT_EQ(c.name, want);
      EXPECT_EQ(c.id, int(k));
      // The robust box's corners project inside the image (the box fills ~80%).
      for (int corner = 0; corner < 8; ++corner) {
        const Vec3 p{corner & 1 ? b.hi.x : b.lo.x, corner & 2 ? b.hi.y : b.lo.y, corner & 4 ? b.hi.z : b.lo.z};
        double u, v;
        ASSERT_TRUE(c.project(p, u, v));
        EXPECT_GE(u, -0.05 * c.width);
        EXPECT_LE(u, 1.05 * c.width);
        EXPECT_GE(v, -0.05 * c.height);
        EXPECT_LE(v, 1.05 * c.height);
      }
    }
  }
  EXPECT_EQ(parse_virtual_layout("sphere"), VirtualLayout::kSphere);
  EXPECT_THROW(parse_virtual_layout("spiral"), Error);
}

TEST(VirtualViews, AddedViewsContinueIdsAndFollowForwardFacingCameras) {
  const GaussianScene s = cloud_with_outliers();
  std::vector<Camera> existing;
  for (int k = 0; k < 4; ++k) {
    Camera c = Camera::look_at({10.0 + 0.1 * k, 0, -3}, {10.0 + 0.1 * k, 0, 5}, {0, -1, 0}, 320, 240, 60);
    c.id = 10 + k;
    existing.push_back(c);
  }
  VirtualViewOptions o;
  o.count = 4;
  const std::vector<Camera> v = make_virtual_views(s, existing, o);  // auto -> forward grid
  ASSERT_EQ(v.size(), 4u);
  EXPECT_EQ(v[0].id, 14);
  for (const Camera& c : v) EXPECT_NEAR(c.R.m[2][2], 1.0, 1e-9);  // all look along +z like the real ones
}

}  // namespace
}  // namespace isegman
