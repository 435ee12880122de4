#include "core/zeroed_array.h"

#include <gtest/gtest.h>

#include <cstdint>

namespace isegman {
namespace {

TEST(ZeroedArray, StartsAtZeroSmallAndLarge) {
  for (size_t n : {size_t(0), size_t(1), size_t(1000), size_t(3) << 20}) {
    ZeroedArray<int64_t> a(n);
    ASSERT_EQ(a.size(), n);
    for (size_t i = 0; i < n; i += 4093) EXPECT_EQ(a[i], 0);
    if (n) {
      EXPECT_EQ(a[n - 1], 0);
    }
  }
}

TEST(ZeroedArray, CopiesMovesAndCompares) {
  ZeroedArray<int64_t> a(size_t(1) << 18);  // 2 MiB: a mapped block
  a[7] = -5;
  a[a.size() - 1] = 9;
  ZeroedArray<int64_t> b = a;
  EXPECT_EQ(b, a);
  b[7] = 0;
  EXPECT_NE(b, a);
  ZeroedArray<int64_t> c = std::move(a);
  EXPECT_TRUE(a.empty());
  EXPECT_EQ(c[7], -5);
  EXPECT_EQ(c[c.size() - 1], 9);
  c = ZeroedArray<int64_t>(3);
  EXPECT_EQ(c, ZeroedArray<int64_t>(3));
  EXPECT_NE(c, ZeroedArray<int64_t>(4));
}

}  // namespace
}  // namespace isegman
