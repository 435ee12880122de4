#include "app/hard_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

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

TEST(ClicksDrawnOn, DrawsInsideTheMaskKeepingTheInsetAndTheSameDrawsPerName) {
  Image mask(30, 20, 1);  // a 10 x 8 block at (10..19, 6..13)
  for (int y = 6; y < 14; ++y)
    for (int x = 10; x < 20; ++x) mask.at(x, y) = 1;
  const Click own = pixel_centre_click(0, 0, 1);
  const std::vector<Click> drawn = clicks_drawn_on(mask, "task", own, 40, 3);
  ASSERT_EQ(drawn.size(), 40u);
  EXPECT_EQ(drawn[0].x, own.x);  // the task's own click first, whatever the mask
  std::set<std::pair<int, int>> seen;
  for (size_t k = 1; k < drawn.size(); ++k) {  // 3 px in: only the block's inner 4 x 2 pixels
    const int x = int(drawn[k].x), y = int(drawn[k].y);
    EXPECT_TRUE(x >= 13 && x <= 16 && y >= 9 && y <= 10) << x << "," << y;
    seen.insert({x, y});
  }
  EXPECT_GT(seen.size(), 4u);  // spread over them, not one pixel
  const std::vector<Click> again = clicks_drawn_on(mask, "task", own, 40, 3);
  for (size_t k = 0; k < drawn.size(); ++k) EXPECT_EQ(drawn[k].x, again[k].x);
  const std::vector<Click> other = clicks_drawn_on(mask, "another task", own, 40, 3);
  bool differs = false;
  for (size_t k = 1; k < drawn.size(); ++k) differs |= drawn[k].x != other[k].x || drawn[k].y != other[k].y;
  EXPECT_TRUE(differs);
  EXPECT_EQ(clicks_drawn_on(mask, "task", own, 5, 5).size(), 1u);  // no pixel 5 px in: the own click alone
}

}  // namespace
}  // namespace isegman
