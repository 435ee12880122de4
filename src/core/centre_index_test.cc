#include "core/centre_index.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "core/random.h"

namespace isegman {
namespace {

GaussianScene random_centres(size_t n, uint64_t seed) {
  SplitMix64 rng(seed);
  GaussianScene s;
  s.resize(n, 0);
  for (float& p : s.positions) p = float(rng.range(-1, 1));
  return s;
}

TEST(CentreIndex, NearestMatchBruteForce) {
  const GaussianScene s = random_centres(3000, 8);
  const CentreIndex index(s);
  SplitMix64 rng(5);
  for (int q = 0; q < 100; ++q) {
    const Vec3 p{rng.range(-1.2, 1.2), rng.range(-1.2, 1.2), rng.range(-1.2, 1.2)};
    std::vector<std::pair<double, uint32_t>> all;
    for (uint32_t i = 0; i < s.size(); ++i) {
      const Vec3 d = s.position(i) - p;
      all.push_back({dot(d, d), i});
    }
    std::sort(all.begin(), all.end());
    const std::vector<uint32_t> got = index.nearest(p, 7, 0);
    ASSERT_EQ(got.size(), 7u);
    for (int k = 0; k < 7; ++k) EXPECT_EQ(got[k], all[k].second);
    // With a distance limit only the close ones come back.
    const std::vector<uint32_t> near = index.nearest(p, 50, 0.15);
    size_t within = 0;
    while (within < all.size() && all[within].first <= 0.15 * 0.15) ++within;
    EXPECT_EQ(near.size(), std::min<size_t>(within, 50));
  }
}

TEST(CentreIndex, RadiusQueryMatchesBruteForce) {
  const GaussianScene s = random_centres(2000, 9);
  const CentreIndex index(s);
  SplitMix64 rng(6);
  for (int q = 0; q < 50; ++q) {
    const Vec3 p{rng.range(-1.2, 1.2), rng.range(-1.2, 1.2), rng.range(-1.2, 1.2)};
    const double r = rng.range(0.01, 0.4);
    std::vector<uint32_t> want;
    for (uint32_t i = 0; i < s.size(); ++i) {
      const Vec3 d = s.position(i) - p;
      if (dot(d, d) <= r * r) want.push_back(i);
    }
    EXPECT_EQ(index.within(p, r), want);
  }
}

TEST(CentreIndex, SegmentQueryMatchesBruteForce) {
  const GaussianScene s = random_centres(2000, 10);
  const CentreIndex index(s);
  SplitMix64 rng(7);
  size_t found = 0;
  for (int q = 0; q < 50; ++q) {
    const Vec3 a{rng.range(-1.5, 1.5), rng.range(-1.5, 1.5), rng.range(-1.5, 1.5)};
    const Vec3 b = q % 10 == 0 ? a : Vec3{rng.range(-1.5, 1.5), rng.range(-1.5, 1.5), rng.range(-1.5, 1.5)};
    const double r = rng.range(0.01, 0.2);
    const Vec3 d = b - a;
    std::vector<uint32_t> want;
    for (uint32_t i = 0; i < s.size(); ++i) {
      const double t = dot(d, d) > 0 ? std::clamp(dot(s.position(i) - a, d) / dot(d, d), 0.0, 1.0) : 0.0;
      const Vec3 off = s.position(i) - (a + d * t);
      if (dot(off, off) <= r * r) want.push_back(i);
    }
    found += want.size();
    EXPECT_EQ(index.near_segment(a, b, r), want);
  }
  EXPECT_GT(found, 500u);  // the queries did meet centres
}

TEST(CentreIndex, ThreadsBuildTheSameTree) {
  // Large enough that the build splits its upper levels over threads.
  const GaussianScene s = random_centres(300000, 11);
  const CentreIndex one(s, 1), four(s, 4);
  SplitMix64 rng(12);
  for (int q = 0; q < 40; ++q) {
    const Vec3 p{rng.range(-1.1, 1.1), rng.range(-1.1, 1.1), rng.range(-1.1, 1.1)};
    const Vec3 e{rng.range(-1.1, 1.1), rng.range(-1.1, 1.1), rng.range(-1.1, 1.1)};
    const std::vector<uint32_t> near = four.nearest(p, 9, 0);
    EXPECT_EQ(near, one.nearest(p, 9, 0));
    const std::vector<uint32_t> ball = four.within(p, 0.05);
    EXPECT_EQ(ball, one.within(p, 0.05));
    EXPECT_EQ(four.near_segment(p, e, 0.01), one.near_segment(p, e, 0.01));
    // And against every centre: the nearest one, and the ball's size.
    double best = INFINITY;
    uint32_t best_i = 0;
    size_t inside = 0;
    for (uint32_t i = 0; i < s.size(); ++i) {
      const Vec3 d = s.position(i) - p;
      const double d2 = dot(d, d);
      if (d2 < best) {
        best = d2;
        best_i = i;
      }
      inside += d2 <= 0.05 * 0.05;
    }
    ASSERT_FALSE(near.empty());
    EXPECT_EQ(near.front(), best_i);
    EXPECT_EQ(ball.size(), inside);
  }
}

TEST(CentreIndex, EmptySceneAnswersNothing) {
  const GaussianScene s;
  const CentreIndex index(s);
  EXPECT_TRUE(index.nearest({0, 0, 0}, 5, 0).empty());
  EXPECT_TRUE(index.within({0, 0, 0}, 1.0).empty());
}

}  // namespace
}  // namespace isegman
