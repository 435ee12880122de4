#include "segment/epipolar.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace isegman::segment {
namespace {

std::vector<Camera> ring(int n) {
  std::vector<Camera> cams;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    cams.push_back(Camera::look_at({4 * std::cos(a), 4 * std::sin(a), 1.5 + 0.3 * i}, {0, 0, 0.3}, {0, 0, 1}, 320,
                                   240, 55));
  }
  return cams;
}

TEST(Epipolar, ProjectionOfTheRaysPointsLiesOnTheLineInEveryView) {
  const auto cams = ring(6);
  const Vec3 points[] = {{0.1, -0.2, 0.4}, {-0.5, 0.3, 0.0}, {0.7, 0.6, 1.1}};
  for (const Vec3& X : points)
    for (size_t s = 0; s < cams.size(); ++s) {
      double u, v;
      ASSERT_TRUE(cams[s].project(X, u, v));
      for (size_t d = 0; d < cams.size(); ++d) {
        if (d == s) continue;
        double line[3];
        ASSERT_TRUE(epipolar_line(cams[s], u, v, cams[d], line));
        double pu, pv;
        if (!cams[d].project(X, pu, pv)) continue;
        EXPECT_NEAR(line[0] * pu + line[1] * pv + line[2], 0.0, 1e-6) << "views " << s << " -> " << d;
        // The clipped segment passes through the projection when it is inside the image.
        Point2 a, b;
        if (pu < 0 || pv < 0 || pu > 320 || pv > 240) continue;
        ASSERT_TRUE(epipolar_segment(cams[s], u, v, cams[d], 1e-6, 1e6, a, b));
        const double cross = (b.x - a.x) * (pv - a.y) - (b.y - a.y) * (pu - a.x);
        EXPECT_NEAR(cross / std::hypot(b.x - a.x, b.y - a.y), 0.0, 1e-6);
        const double t = ((pu - a.x) * (b.x - a.x) + (pv - a.y) * (b.y - a.y)) /
                         ((b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y));
        EXPECT_GE(t, -1e-9);
        EXPECT_LE(t, 1 + 1e-9);
      }
    }
}

TEST(Epipolar, SegmentStaysInsideTheImage) {
  const auto cams = ring(4);
  Point2 a, b;
  ASSERT_TRUE(epipolar_segment(cams[0], 160, 120, cams[1], 1e-6, 1e6, a, b));
  for (const Point2& p : {a, b}) {
    EXPECT_GE(p.x, -1e-9);
    EXPECT_LE(p.x, 320 + 1e-9);
    EXPECT_GE(p.y, -1e-9);
    EXPECT_LE(p.y, 240 + 1e-9);
  }
}

TEST(GridWalk, VisitsEveryCellTheSegmentCrossesAndNoOther) {
  const Point2 segs[][2] = {{{0.3, 0.2}, {9.7, 3.1}},  {{7.5, 7.5}, {0.5, 0.5}},   {{2.2, 9.9}, {2.7, 0.1}},
                            {{-3, 2.5}, {20, 6.25}},   {{1.0, 1.0}, {4.0, 4.0}},   {{5.5, 2.5}, {5.5, 8.5}},
                            {{0.1, 6.9}, {12.9, 6.9}}, {{3.99, 0.01}, {0.01, 3.99}}};
  for (const auto& s : segs) {
    const auto cells = grid_cells_on_segment(s[0], s[1], 10, 10);
    std::set<std::pair<int, int>> visited(cells.begin(), cells.end());
    EXPECT_EQ(visited.size(), cells.size()) << "a cell was visited twice";
    // Dense sampling: every cell a sample falls in must have been visited.
    for (int k = 0; k <= 20000; ++k) {
      const double t = k / 20000.0;
      const double x = s[0].x + t * (s[1].x - s[0].x), y = s[0].y + t * (s[1].y - s[0].y);
      const int cx = int(std::floor(x)), cy = int(std::floor(y));
      if (cx < 0 || cy < 0 || cx >= 10 || cy >= 10) continue;
      ASSERT_TRUE(visited.count({cx, cy})) << "missed cell " << cx << "," << cy;
    }
    // And every visited cell touches the segment (distance from its centre <= half diagonal).
    for (const auto& [cx, cy] : cells) {
      const double px = cx + 0.5, py = cy + 0.5, dx = s[1].x - s[0].x, dy = s[1].y - s[0].y;
      const double t = std::clamp(((px - s[0].x) * dx + (py - s[0].y) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
      EXPECT_LE(std::hypot(s[0].x + t * dx - px, s[0].y + t * dy - py), std::sqrt(0.5) + 1e-9);
    }
    // Cells come in order along the segment: consecutive cells are neighbours.
    for (size_t i = 1; i < cells.size(); ++i)
      EXPECT_LE(std::abs(cells[i].first - cells[i - 1].first) + std::abs(cells[i].second - cells[i - 1].second), 2);
  }
}

}  // namespace
}  // namespace isegman::segment
