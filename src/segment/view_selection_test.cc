#include "segment/view_selection.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "segment/views.h"

namespace isegman::segment {
namespace {

// n cameras on a ring of radius r around the origin (alternating heights), looking at it.
std::vector<Camera> ring(int n, double r = 5.0) {
  std::vector<Camera> cams;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    Vec3 eye{r * std::cos(a), r * std::sin(a), i % 2 ? 1.5 : 0.5};
    Camera c = Camera::look_at(eye, {0, 0, 0}, {0, 0, 1}, 1000, 660, 55.0);
    c.id = i;
    c.name = "cam_" + std::to_string(i);
    cams.push_back(c);
  }
  return cams;
}

double azimuth_deg(const Camera& c) {
  const Vec3 o = c.center();
  double a = std::atan2(o.y, o.x) * 180 / M_PI;
  return a < 0 ? a + 360 : a;
}

TEST(ViewSelection, RingOf200CoversTheAnglesAndSeesThePoint) {
  const auto cams = ring(200);
  const Vec3 X{0.1, -0.05, 0.2};
  const int clicked = 37;
  const auto chosen = select_views_for_point(cams, clicked, X, 20);
  ASSERT_EQ(chosen.size(), 20u);
  EXPECT_TRUE(std::is_sorted(chosen.begin(), chosen.end()));
  EXPECT_TRUE(std::binary_search(chosen.begin(), chosen.end(), clicked));
  std::vector<double> az;
  for (int i : chosen) {
    double u, v, z;
    ASSERT_TRUE(cams[size_t(i)].project(X, u, v, &z)) << i;
    EXPECT_GT(z, 0);
    EXPECT_TRUE(u >= 0 && v >= 0 && u < 1000 && v < 660) << i;
    az.push_back(azimuth_deg(cams[size_t(i)]));
  }
  std::sort(az.begin(), az.end());
  double max_gap = az.front() + 360 - az.back();
  for (size_t i = 1; i < az.size(); ++i) max_gap = std::max(max_gap, az[i] - az[i - 1]);
  // 20 evenly spread views leave 18 degree gaps; farthest-point sampling stays within 2x.
  EXPECT_LE(max_gap, 36.0 + 1e-6);
}

TEST(ViewSelection, CamerasThatDoNotSeeThePointAreLeftOut) {
  auto cams = ring(60);
  // Turn every third camera away from the point (it is then behind them).
  for (size_t i = 0; i < cams.size(); i += 3) {
    const Vec3 eye = cams[i].center();
    Camera c = Camera::look_at(eye, eye * 2.0, {0, 0, 1}, 1000, 660, 55.0);
    c.id = cams[i].id;
    c.name = cams[i].name;
    cams[i] = c;
  }
  const auto chosen = select_views_for_point(cams, 1, {0, 0, 0}, 30);
  EXPECT_EQ(chosen.size(), 30u);
  for (int i : chosen) EXPECT_NE(i % 3, 0) << i;
  EXPECT_TRUE(std::binary_search(chosen.begin(), chosen.end(), 1));
  // Asking for more than can see it returns only those (40 of 60).
  EXPECT_EQ(select_views_for_point(cams, 1, {0, 0, 0}, 100).size(), 40u);
}

TEST(ViewSelection, PrefersCamerasAtASimilarDistance) {
  // Two cameras in the same direction: one as near as the clicked one, one 4x farther.
  std::vector<Camera> cams;
  cams.push_back(Camera::look_at({5, 0, 0.5}, {0, 0, 0}, {0, 0, 1}, 800, 600, 55.0));
  cams.push_back(Camera::look_at({-20, 0.1, 2}, {0, 0, 0}, {0, 0, 1}, 800, 600, 55.0));
  cams.push_back(Camera::look_at({-5, 0, 0.5}, {0, 0, 0}, {0, 0, 1}, 800, 600, 55.0));
  const auto s = score_views(cams, 0, {0, 0, 0});
  EXPECT_GT(s[2].quality, s[1].quality);
  const auto chosen = select_views_for_point(cams, 0, {0, 0, 0}, 2);
  EXPECT_EQ(chosen, (std::vector<int>{0, 2}));
}

TEST(ViewSelection, SpreadWithoutAPoint) {
  const auto cams = ring(200);
  const auto chosen = spread_views(cams, 5, 20);
  ASSERT_EQ(chosen.size(), 20u);
  EXPECT_TRUE(std::binary_search(chosen.begin(), chosen.end(), 5));
  std::vector<double> az;
  for (int i : chosen) az.push_back(azimuth_deg(cams[size_t(i)]));
  std::sort(az.begin(), az.end());
  double max_gap = az.front() + 360 - az.back();
  for (size_t i = 1; i < az.size(); ++i) max_gap = std::max(max_gap, az[i] - az[i - 1]);
  EXPECT_LE(max_gap, 36.0 + 1e-6);
}

TEST(ViewSelection, AutoSpec) {
  int k = 0;
  EXPECT_TRUE(parse_auto_views("auto", k));
  EXPECT_EQ(k, kDefaultVotingViews);
  EXPECT_TRUE(parse_auto_views("auto:24", k));
  EXPECT_EQ(k, 24);
  EXPECT_FALSE(parse_auto_views("all", k));
  EXPECT_FALSE(parse_auto_views("25%", k));
  EXPECT_THROW(parse_auto_views("auto:", k), Error);
  EXPECT_THROW(parse_auto_views("auto:0", k), Error);
  EXPECT_THROW(parse_auto_views("auto:x", k), Error);

  const auto cams = ring(200);
  EXPECT_EQ(sample_views(cams, "auto", 3).size(), 20u);
  auto v = sample_views(cams, "auto:24", 3);
  EXPECT_EQ(v.size(), 24u);
  EXPECT_TRUE(std::binary_search(v.begin(), v.end(), 3));
  // At most K cameras: all of them, as before.
  const auto few = ring(12);
  EXPECT_EQ(sample_views(few, "auto").size(), 12u);
  EXPECT_EQ(sample_views(cams, "all").size(), 200u);
}

}  // namespace
}  // namespace isegman::segment
