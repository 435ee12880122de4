#include "segment/scribbles.h"

#include <gtest/gtest.h>

namespace isegman::segment {
namespace {

TEST(Scribbles, FarthestPointClicksSpreadAlongTheStroke) {
  Image s(100, 50, 1);
  for (int x = 10; x < 90; ++x) s.at(x, 25) = 1.f;  // a horizontal stroke
  auto clicks = clicks_from_scribble(s, 3, 1);
  ASSERT_EQ(clicks.size(), 3u);
  EXPECT_NEAR(clicks[0].x, 50.0, 0.6);  // starts at the centroid
  // Then the two ends, the farthest points.
  EXPECT_TRUE((clicks[1].x == 10.5 && clicks[2].x == 89.5) || (clicks[1].x == 89.5 && clicks[2].x == 10.5));  // pixel centres
  for (const auto& c : clicks) {
    EXPECT_EQ(c.y, 25.5);
    EXPECT_EQ(c.label, 1);
  }
}

TEST(Scribbles, NeverMoreClicksThanPixelsAndNoneFromAnEmptyImage) {
  Image s(10, 10, 3);
  s.at(2, 3, 1) = 0.5f;
  s.at(7, 7, 0) = 1.f;
  EXPECT_EQ(clicks_from_scribble(s, 5, 0).size(), 2u);
  EXPECT_TRUE(clicks_from_scribble(Image(4, 4, 1), 3, 1).empty());
}

}  // namespace
}  // namespace isegman::segment
