#include "render/radix_sort.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

namespace isegman {
namespace {

// Against std::stable_sort on (key, input position): the same order for keys of every
// width (one, two and three digit passes), with many ties, on one and on several threads,
// for lists short enough for one slice and long enough for several.
TEST(RadixSort, SortsStablyLikeStableSortForAnyKeyWidthAndThreadCount) {
  uint64_t state = 12345;
  auto next = [&] { return uint32_t((state = state * 6364136223846793005ull + 1442695040888963407ull) >> 32); };
  int checked = 0;
  for (size_t n : {size_t(0), size_t(1), size_t(2), size_t(1000), size_t(300000)})
    for (uint32_t range : {1u, 7u, 4096u, 6000000u, 0xffffffffu}) {
      std::vector<uint32_t> keys(n);
      for (uint32_t& k : keys) k = range == 0xffffffffu ? next() : next() % range;
      std::vector<uint32_t> want(n);
      std::iota(want.begin(), want.end(), 0u);
      std::stable_sort(want.begin(), want.end(), [&](uint32_t a, uint32_t b) { return keys[a] < keys[b]; });
      for (int threads : {1, 2, 3}) {
        std::vector<uint32_t> k = keys, p(n);
        std::iota(p.begin(), p.end(), 0u);
        radix_sort_pairs(k, p, threads);
        ASSERT_EQ(p, want) << "n " << n << ", keys below " << range << ", " << threads << " threads";
        for (size_t i = 0; i < n; ++i) ASSERT_EQ(k[i], keys[p[i]]);
        ++checked;
      }
    }
  std::printf("radix sort: %d lists sorted as std::stable_sort sorts them\n", checked);
}

TEST(RadixSort, RefusesPayloadOfAnotherLength) {
  std::vector<uint32_t> keys = {3, 1, 2}, payload = {0, 1};
  EXPECT_ANY_THROW(radix_sort_pairs(keys, payload));
}

}  // namespace
}  // namespace isegman
