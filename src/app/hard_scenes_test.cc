#include "app/hard_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace isegman {
namespace {

double rotation_angle(const Mat3& a, const Mat3& b) {  // geodesic angle between two rotations
  const Mat3 d = a * b.transposed();
  const double c = std::clamp((d.m[0][0] + d.m[1][1] + d.m[2][2] - 1) / 2, -1.0, 1.0);
  return std::acos(c);
}

TEST(DensifyCameras, AddsCamerasAlongThePathAndKeepsTheOriginals) {
  std::vector<Camera> cams;
  for (int i = 0; i < 4; ++i) {  // a quarter orbit around the origin, 30 degrees apart
    const double a = i * M_PI / 6;
    Camera c = Camera::look_at({3 * std::cos(a), 3 * std::sin(a), 1}, {0, 0, 0}, {0, 0, 1}, 64, 48, 60);
    c.id = i;
    c.name = "orbit_00" + std::to_string(i);
    cams.push_back(c);
  }
  std::vector<Camera> dense = cams;
  densify_cameras(dense, 3);
  ASSERT_EQ(dense.size(), 10u);  // 3 per gap and the last one
  for (size_t i = 0; i < cams.size(); ++i) {  // camera i is now 3 i, pose unchanged
    const Camera& c = dense[3 * i];
    EXPECT_NEAR(norm(c.center() - cams[i].center()), 0, 1e-12);
    EXPECT_NEAR(rotation_angle(c.R, cams[i].R), 0, 1e-6);
  }
  for (size_t i = 0; i + 1 < cams.size(); ++i)
    for (int k = 1; k < 3; ++k) {  // in between: a third of the way, in position and in rotation
      const Camera& c = dense[3 * i + size_t(k)];
      const Vec3 want = cams[i].center() + (cams[i + 1].center() - cams[i].center()) * (k / 3.0);
      EXPECT_NEAR(norm(c.center() - want), 0, 1e-9);
      const double whole = rotation_angle(cams[i].R, cams[i + 1].R);
      EXPECT_NEAR(rotation_angle(cams[i].R, c.R), whole * k / 3.0, 1e-6);
      EXPECT_NEAR(rotation_angle(c.R, cams[i + 1].R), whole * (3 - k) / 3.0, 1e-6);
      EXPECT_EQ(c.width, 64);
      EXPECT_DOUBLE_EQ(c.fx, cams[i].fx);
    }
  for (size_t i = 0; i < dense.size(); ++i) {  // renamed in path order
    EXPECT_EQ(dense[i].id, int(i));
    char want[32];
    std::snprintf(want, sizeof want, "orbit_%03zu", i);
    EXPECT_EQ(dense[i].name, want);
  }
  std::vector<Camera> same = cams;
  densify_cameras(same, 1);
  EXPECT_EQ(same.size(), cams.size());
}

}  // namespace
}  // namespace isegman
