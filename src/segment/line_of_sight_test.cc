#include "segment/line_of_sight.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/camera.h"
#include "segment/view_selection.h"

namespace isegman::segment {
namespace {

// Round Gaussians (scale s, opacity o) at the given centres.
GaussianScene gaussians_at(const std::vector<Vec3>& centres, double s, double o) {
  GaussianScene g;
  g.resize(centres.size(), 0);
  for (size_t i = 0; i < centres.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      g.positions[3 * i + size_t(k)] = float(centres[i][k]);
      g.scales[3 * i + size_t(k)] = float(std::log(s));
    }
    g.rotations[4 * i] = 1;
    g.opacity[i] = float(std::log(o / (1 - o)));
  }
  return g;
}

// A wall of touching opaque Gaussians in the plane x = 0, |y|, |z| <= 1.
std::vector<Vec3> wall() {
  std::vector<Vec3> c;
  for (int y = -20; y <= 20; ++y)
    for (int z = -20; z <= 20; ++z) c.push_back({0, y * 0.05, z * 0.05});
  return c;
}

TEST(LineOfSight, AWallStopsTheLineAndALineBesideItPasses) {
  const GaussianScene g = gaussians_at(wall(), 0.03, 0.95);
  const CentreIndex index(g);
  const LineOfSight sight(g, index);
  EXPECT_LT(sight.transmittance({-2, 0.3, 0.2}, {2, 0.3, 0.2}), 0.05);  // through the wall
  EXPECT_GT(sight.transmittance({-2, 3, 0}, {2, 3, 0}), 0.999);         // beside it
  EXPECT_GT(sight.transmittance({-2, 0, 0}, {-0.5, 0, 0}), 0.999);      // stops before it
}

TEST(LineOfSight, OneGaussianTakesItsOpacityAtItsCentre) {
  const GaussianScene g = gaussians_at({{0, 0, 0}}, 0.1, 0.6);
  const CentreIndex index(g);
  const LineOfSight sight(g, index);
  EXPECT_NEAR(sight.transmittance({-1, 0, 0}, {1, 0, 0}), 0.4, 1e-6);
  // One sigma off its centre the density is exp(-1/2).
  EXPECT_NEAR(sight.transmittance({-1, 0.1, 0}, {1, 0.1, 0}), 1 - 0.6 * std::exp(-0.5), 1e-6);
}

// An object at the origin (a ball of samples) seen by a ring of cameras; a wall hides it
// from the cameras on the -x side.
TEST(LineOfSight, ViewSelectionLeavesOutCamerasTheObjectIsHiddenFrom) {
  std::vector<Vec3> object;
  for (int i = 0; i < 40; ++i) {
    const double a = 2 * M_PI * i / 40;
    object.push_back({0.2 * std::cos(a), 0.2 * std::sin(a), 0.1 * ((i % 3) - 1)});
  }
  std::vector<Vec3> centres = object;
  for (const Vec3& p : wall()) centres.push_back({p.x - 1.0, p.y * 2, p.z});  // at x = -1, 4 m wide
  const GaussianScene g = gaussians_at(centres, 0.04, 0.95);
  const CentreIndex index(g);
  const LineOfSight sight(g, index);
  std::vector<Camera> cams;
  for (int i = 0; i < 24; ++i) {
    const double a = 2 * M_PI * i / 24;
    Camera c = Camera::look_at({3 * std::cos(a), 3 * std::sin(a), 0.3}, {0, 0, 0}, {0, 0, 1}, 320, 240, 60);
    c.id = i;
    c.name = "cam_" + std::to_string(i);
    cams.push_back(c);
  }
  const LineOpen open = [&](const Vec3& a, const Vec3& b) { return sight.transmittance(a, b); };
  std::vector<ViewCandidate> cand = score_views(cams, 0, {0, 0, 0});
  weigh_by_object(cand, cams, 0, object, open);
  for (const ViewCandidate& c : cand) {
    const Vec3 eye = cams[size_t(c.camera)].center();
    const bool behind_wall = eye.x < -1.2 && std::fabs(eye.y) < 1.2;  // the wall spans |y| <= 2 at x = -1
    if (behind_wall) {
      EXPECT_FALSE(c.sees) << c.camera;
    }
    // The cameras on the far side of the object see it through its own near side.
    if (eye.x > 0) {
      EXPECT_TRUE(c.sees) << c.camera;
    }
  }
  const std::vector<int> chosen = select_views_for_object(cams, 0, {0, 0, 0}, object, open, 10);
  for (int i : chosen) {
    const Vec3 eye = cams[size_t(i)].center();
    EXPECT_FALSE(eye.x < -1.2 && std::fabs(eye.y) < 1.2) << i;
  }
}

}  // namespace
}  // namespace isegman::segment
