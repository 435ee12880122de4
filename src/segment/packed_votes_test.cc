#include "segment/packed_votes.h"

#include <gtest/gtest.h>

#include <random>

#include "core/error.h"

namespace isegman::segment {
namespace {

// Votes over `n` entries with every kind of gap and weight the packing treats apart.
ViewVotes varied_votes(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  ViewVotes v;
  uint32_t index = rng() % 300;  // the first index itself may be a wide gap
  for (size_t k = 0; k < n; ++k) {
    v.index.push_back(index);
    const uint32_t kind = rng() % 100;
    int64_t w = int64_t(rng() % 50000000);                          // a few pixels' weight
    if (kind < 3) w = int64_t(0xFFFFFFFFu) + int64_t(rng() % 1000);  // a large Gaussian: 256+ pixels
    if (kind == 3) w = int64_t(0xFFFFFFFFu);                        // the marker value itself
    if (kind == 4) w = int64_t(0xFFFFFFFEu);                        // the largest narrow one
    if (kind == 5) w = 0;
    if (kind == 6) w = -int64_t(rng() % 1000) - 1;  // never a total vote, but exact all the same
    v.weight.push_back(w);
    const uint32_t g = rng() % 100;
    index += 1 + (g < 5 ? 254 + rng() % 3 : g < 8 ? rng() % 100000 : rng() % 4);  // around the 1-byte limit
  }
  return v;
}

TEST(PackedVotes, UnpacksToTheSameIndicesAndWeights) {
  for (size_t n : {size_t(0), size_t(1), size_t(1000), PackedVotes::kBlock, 3 * PackedVotes::kBlock + 17}) {
    const ViewVotes v = varied_votes(n, uint32_t(n) + 3);
    const PackedVotes packed(v);
    EXPECT_EQ(packed.size(), n);
    for (int threads : {1, 2, 3}) {
      const ViewVotes u = packed.unpack(threads);
      ASSERT_EQ(u.index, v.index) << n << " entries, " << threads << " threads";
      ASSERT_EQ(u.weight, v.weight) << n << " entries, " << threads << " threads";
    }
  }
}

// A view of a large scene shows most Gaussians of its region (index gaps of a few) with a
// few pixels' weight each: 5 bytes an entry, where a ViewVotes takes 12.
TEST(PackedVotes, TakesFiveBytesAnEntryForAViewsTypicalVotes) {
  std::mt19937 rng(9);
  ViewVotes v;
  for (uint32_t index = 0; v.index.size() < 200000; index += 1 + rng() % 4) {
    v.index.push_back(index);
    v.weight.push_back(int64_t(rng() % (uint32_t(1) << 28)));
  }
  const PackedVotes packed(v);
  EXPECT_LE(packed.bytes(), v.index.size() * 5 + 64);
  EXPECT_EQ(packed.unpack().weight, v.weight);
}

TEST(PackedVotes, ReusesTheListsItUnpacksInto) {
  const PackedVotes big(varied_votes(5000, 1)), small(varied_votes(40, 2));
  ViewVotes out;
  big.unpack(out);
  const uint32_t* buffer = out.index.data();
  small.unpack(out);
  EXPECT_EQ(out.index.data(), buffer);  // no new allocation for the smaller view
  EXPECT_EQ(out.index, varied_votes(40, 2).index);
  EXPECT_EQ(out.weight, varied_votes(40, 2).weight);
}

TEST(PackedVotes, RefusesIndicesThatAreNotStrictlyAscending) {
  ViewVotes v;
  v.index = {3, 7, 7};
  v.weight = {1, 2, 3};
  EXPECT_THROW(PackedVotes{v}, Error);
  v.index = {3, 7, 5};
  EXPECT_THROW(PackedVotes{v}, Error);
  v.index = {3, 7};
  EXPECT_THROW(PackedVotes{v}, Error);  // lists of different lengths
  v.index = {0, 1, 0xFFFFFFFFu};
  EXPECT_EQ(PackedVotes(v).unpack().index, v.index);
}

}  // namespace
}  // namespace isegman::segment
