#include "core/spatial_order.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <random>

namespace isegman {
namespace {

// n Gaussians at random centres in a cube, every attribute tagged with its index.
GaussianScene tagged_scene(size_t n, int degree, uint32_t seed) {
  GaussianScene s;
  s.resize(n, degree);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-10.f, 10.f);
  for (float& p : s.positions) p = u(rng);
  s.normals.assign(3 * n, 0.f);
  ExtraProperty extra{"f_tag", "uint", 4, std::vector<uint8_t>(4 * n)};
  for (size_t i = 0; i < n; ++i) {
    for (int c = 0; c < s.coeffs() * 3; ++c) s.sh_of(i)[c] = float(i) + 0.001f * float(c);
    s.opacity[i] = float(i);
    for (int a = 0; a < 3; ++a) s.scales[3 * i + a] = float(i) + 0.1f * float(a);
    for (int a = 0; a < 4; ++a) s.rotations[4 * i + a] = float(i) + 0.1f * float(a);
    for (int a = 0; a < 3; ++a) s.normals[3 * i + a] = -float(i) - 0.1f * float(a);
    const uint32_t tag = uint32_t(i) * 7u + 1u;
    std::memcpy(extra.data.data() + 4 * i, &tag, 4);
  }
  s.extras.push_back(extra);
  return s;
}

double mean_step(const GaussianScene& s) {
  double sum = 0;
  for (size_t i = 1; i < s.size(); ++i) sum += norm(s.position(i) - s.position(i - 1));
  return sum / double(s.size() - 1);
}

TEST(SpatialOrder, IsAPermutationThatPutsNeighboursTogether) {
  const GaussianScene s = tagged_scene(20000, 0, 3);
  const std::vector<uint32_t> order = spatial_order(s);
  std::vector<uint32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (size_t i = 0; i < sorted.size(); ++i) ASSERT_EQ(sorted[i], i);
  GaussianScene ordered = s;
  reorder(ordered, order);
  const double before = mean_step(s), after = mean_step(ordered);
  std::printf("mean distance between consecutive Gaussians: %.3f in index order, %.3f in space order\n", before,
              after);
  // Two random points of a cube of side 20 lie ~13 apart; neighbours of 20,000 under 1.
  EXPECT_GT(before, 8.0);
  EXPECT_LT(after, 1.5);
}

TEST(SpatialOrder, TiesKeepTheirIndexOrderAndRepeatsGiveTheSameOrder) {
  GaussianScene s = tagged_scene(1000, 0, 5);
  for (size_t i = 500; i < 1000; ++i)  // each in the same place as one before it
    for (int a = 0; a < 3; ++a) s.positions[3 * i + a] = s.positions[3 * (i - 500) + a];
  const std::vector<uint32_t> order = spatial_order(s);
  EXPECT_EQ(order, spatial_order(s));
  std::vector<uint32_t> position(order.size());
  for (size_t k = 0; k < order.size(); ++k) position[order[k]] = uint32_t(k);
  for (size_t i = 0; i < 500; ++i) EXPECT_LT(position[i], position[i + 500]) << i;
}

TEST(SpatialOrder, ReorderMovesEveryArrayTogether) {
  // Rows of 48, 108 and 192 bytes of SH: one slice, a slice and a part, three slices.
  for (int degree : {1, 2, 3}) {
    SCOPED_TRACE("SH degree " + std::to_string(degree));
    const GaussianScene original = tagged_scene(3000, degree, 9);
    GaussianScene s = original;
    const SpaceOrder space = put_in_space_order(s);
    ASSERT_EQ(s.size(), original.size());
    for (size_t k = 0; k < s.size(); ++k) {
      const size_t i = space.order[k];
      ASSERT_EQ(s.position(k).x, original.position(i).x) << k;
      ASSERT_EQ(s.opacity[k], float(i)) << k;
      for (int c = 0; c < s.coeffs() * 3; ++c) ASSERT_EQ(s.sh_of(k)[c], original.sh_of(i)[c]) << k;
      for (int a = 0; a < 3; ++a) ASSERT_EQ(s.scales[3 * k + a], original.scales[3 * i + a]) << k;
      for (int a = 0; a < 4; ++a) ASSERT_EQ(s.rotations[4 * k + a], original.rotations[4 * i + a]) << k;
      for (int a = 0; a < 3; ++a) ASSERT_EQ(s.normals[3 * k + a], original.normals[3 * i + a]) << k;
      uint32_t tag = 0;
      std::memcpy(&tag, s.extras[0].data.data() + 4 * k, 4);
      ASSERT_EQ(tag, uint32_t(i) * 7u + 1u) << k;
    }
    // Values per Gaussian of the reordered scene go back to the file's order.
    std::vector<float> opacity_back = space.to_file_order(s.opacity);
    EXPECT_EQ(opacity_back, original.opacity);
    EXPECT_EQ(space.to_space_order(original.opacity), s.opacity);
    EXPECT_THROW(space.to_file_order(std::vector<int>(5)), Error);
    std::vector<bool> flags(s.size());
    for (size_t k = 0; k < s.size(); ++k) flags[k] = s.opacity[k] < 100.f;  // the file's first 100
    const std::vector<bool> back = space.to_file_order(flags);
    for (size_t i = 0; i < back.size(); ++i) ASSERT_EQ(back[i], i < 100) << i;
  }
}

TEST(SpatialOrder, RejectsAnOrderThatIsNotAPermutation) {
  GaussianScene s = tagged_scene(10, 0, 1);
  std::vector<uint32_t> order(10);
  std::iota(order.begin(), order.end(), 0u);
  order[3] = 4;  // 4 twice, 3 never
  EXPECT_THROW(reorder(s, order), Error);
  order[3] = 10;
  EXPECT_THROW(reorder(s, order), Error);
  order.pop_back();
  EXPECT_THROW(reorder(s, order), Error);
  EXPECT_EQ(s.opacity[3], 3.f);  // nothing moved
  GaussianScene empty;
  EXPECT_NO_THROW(reorder(empty, {}));
  EXPECT_TRUE(spatial_order(empty).empty());
}

}  // namespace
}  // namespace isegman
