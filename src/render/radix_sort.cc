#include "render/radix_sort.h"

#include <cstddef>
#include <utility>

namespace isegman {

void radix_sort_pairs(std::vector<uint32_t>& keys, std::vector<uint32_t>& payload) {
  const size_t n = keys.size();
  if (n < 2) return;
  std::vector<uint32_t> k2(n), p2(n);
  constexpr int kBits = 11, kBuckets = 1 << kBits;
  for (int shift = 0; shift < 32; shift += kBits) {
    size_t count[kBuckets + 1] = {};
    bool all_same_digit = true;
    const uint32_t first = (keys[0] >> shift) & (kBuckets - 1);
    for (size_t i = 0; i < n; ++i) {
      const uint32_t d = (keys[i] >> shift) & (kBuckets - 1);
      all_same_digit &= d == first;
      ++count[d + 1];
    }
    if (all_same_digit) continue;  // this digit cannot change the order
    for (int b = 0; b < kBuckets; ++b) count[b + 1] += count[b];
    for (size_t i = 0; i < n; ++i) {
      const size_t dst = count[(keys[i] >> shift) & (kBuckets - 1)]++;
      k2[dst] = keys[i];
      p2[dst] = payload[i];
    }
    keys.swap(k2);
    payload.swap(p2);
  }
}

}  // namespace isegman
