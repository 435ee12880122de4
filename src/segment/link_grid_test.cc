#include "segment/link_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "segment/whole_islands.h"

namespace isegman::segment {
namespace {

void add_gaussian(GaussianScene& s, float x, float y, float z, float scale) {
  s.positions.insert(s.positions.end(), {x, y, z});
  s.scales.insert(s.scales.end(), {std::log(scale), std::log(scale * 0.5f), std::log(scale * 0.1f)});
  s.rotations.insert(s.rotations.end(), {1, 0, 0, 0});
  s.opacity.push_back(0);
}

// Every Gaussian j != g of `members` that touches g, by the rule itself (whole_islands.h: within
// link x the sum of the two largest scales, and within link x g's scale + the members' reach),
// in ascending order.
std::vector<uint32_t> touching_by_rule(const GaussianScene& s, const std::vector<uint32_t>& members, uint32_t g,
                                       double link) {
  std::vector<float> scales;
  for (uint32_t j : members) scales.push_back(s.largest_scale(j));
  const double reach = touch_reach(scales);
  std::vector<uint32_t> out;
  const Vec3 p = s.position(g);
  for (uint32_t j : members) {
    if (j == g) continue;
    const Vec3 d = s.position(j) - p;
    const double d2 = d.x * d.x + d.y * d.y + d.z * d.z;
    const double l = link * (double(s.largest_scale(g)) + double(s.largest_scale(j)));
    const double r = link * (double(s.largest_scale(g)) + reach);
    if (d2 <= l * l && d2 <= r * r) out.push_back(j);
  }
  return out;
}

// Clusters of Gaussians of mixed sizes (`count` of them: far apart, the grid's box coarsens its
// cells), and pairs about one link apart along x, where the grid bounds its search.
GaussianScene clusters(std::mt19937& rng, int count) {
  GaussianScene s;
  std::uniform_real_distribution<float> unit(-1, 1), size(0.002f, 0.02f);
  const float centres[3][3] = {{0, 0, 0}, {40, -3, 7}, {-25, 60, -90}};
  for (int c = 0; c < count; ++c)
    for (int i = 0; i < 700; ++i)
      add_gaussian(s, centres[c][0] + 0.1f * unit(rng), centres[c][1] + 0.1f * unit(rng),
                   centres[c][2] + 0.1f * unit(rng), size(rng));
  for (int i = 0; i < 20; ++i) {  // pairs 2 x 1 cm apart along x: about touching at link 1
    add_gaussian(s, 0.5f + 0.25f * float(i), 0, 0, 0.01f);
    add_gaussian(s, 0.5f + 0.25f * float(i) + 0.02f, 0, 0, 0.01f);
  }
  return s;
}

TEST(LinkGrid, FindsWhatTheTouchRuleFindsAmongItsMembers) {
  for (int count : {1, 3}) {
    std::mt19937 rng(7);
    const GaussianScene s = clusters(rng, count);
    // Every other Gaussian is a member, and both of each pair; the others are searched from
    // outside the set.
    std::vector<uint32_t> members;
    for (uint32_t g = 0; g < s.size(); ++g)
      if (g % 2 == 0 || g + 40 >= s.size()) members.push_back(g);
    size_t pairs = 0;
    for (double link : {1.0, 2.5}) {
      const LinkGrid grid(s, members, link);
      for (uint32_t g = 0; g < s.size(); ++g) {
        std::vector<uint32_t> found;
        ASSERT_TRUE(grid.for_each(g, [&](uint32_t j) { found.push_back(j); }));
        std::sort(found.begin(), found.end());
        ASSERT_EQ(found, touching_by_rule(s, members, g, link)) << "Gaussian " << g << ", link " << link;
        pairs += found.size();
      }
    }
    std::printf("[ link grid ] %d cluster(s): %zu touching pairs found, all as the rule finds them\n", count, pairs);
    EXPECT_GT(pairs, size_t(count) * 5000);
  }
}

TEST(LinkGrid, RefusesASearchOverTooManyCells) {
  GaussianScene s;
  for (int i = 0; i < 100; ++i) add_gaussian(s, 0.01f * float(i), 0, 0, 0.01f);
  add_gaussian(s, 0.5f, 0, 0, 5.0f);  // a broad Gaussian, not a member
  std::vector<uint32_t> members(100);
  for (uint32_t g = 0; g < 100; ++g) members[g] = g;
  const LinkGrid grid(s, members, 1.0);
  size_t calls = 0;
  EXPECT_FALSE(grid.for_each(100, [&](uint32_t) { ++calls; }, 512));
  EXPECT_EQ(calls, 0u);
  // Unbounded, it finds every member.
  EXPECT_TRUE(grid.for_each(100, [&](uint32_t) { ++calls; }));
  EXPECT_EQ(calls, 100u);
  // An empty grid finds nothing and refuses nothing.
  const LinkGrid none(s, {}, 1.0);
  EXPECT_TRUE(none.for_each(0, [&](uint32_t) { ++calls; }));
  EXPECT_EQ(calls, 100u);
}

}  // namespace
}  // namespace isegman::segment
