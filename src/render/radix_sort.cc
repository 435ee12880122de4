#include "render/radix_sort.h"

#include <algorithm>
#include <cstddef>
#include <utility>

#include "core/error.h"
#include "core/parallel.h"

namespace isegman {

void radix_sort_pairs(std::vector<uint32_t>& keys, std::vector<uint32_t>& payload, int threads) {
  const size_t n = keys.size();
  if (payload.size() != n) throw Error("radix_sort_pairs: keys and payload differ in length");
  if (n < 2) return;
  // Digit width from the largest key: 12 bits keep a slice's counters (16 KB) in L1.
  uint32_t largest = 0;
  for (uint32_t k : keys) largest = std::max(largest, k);
  constexpr int kMaxDigitBits = 12;
  const int key_bits = largest == 0 ? 1 : 32 - __builtin_clz(largest);
  const int passes = (key_bits + kMaxDigitBits - 1) / kMaxDigitBits;
  const int bits = (key_bits + passes - 1) / passes;
  const size_t buckets = size_t(1) << bits;
  const uint32_t digit_mask = uint32_t(buckets - 1);
  // Slices of the list, each counted and scattered by one task: slice s writes after
  // slices < s in every bucket, which keeps the sort stable.
  constexpr size_t kSliceMin = size_t(1) << 16;
  const size_t slices = std::clamp<size_t>(n / kSliceMin, 1, size_t(resolve_threads(threads)) * 2);
  const size_t per_slice = (n + slices - 1) / slices;
  std::vector<uint32_t> k2(n), p2(n);
  std::vector<size_t> count(slices * buckets);
  for (int pass = 0; pass < passes; ++pass) {
    const int shift = pass * bits;
    std::fill(count.begin(), count.end(), 0);
    parallel_for(slices, threads, [&](int, size_t s) {
      size_t* c = count.data() + s * buckets;
      for (size_t i = s * per_slice, e = std::min(n, (s + 1) * per_slice); i < e; ++i) ++c[(keys[i] >> shift) & digit_mask];
    });
    // Each slice's write cursor per bucket; a digit every key shares cannot change the order.
    bool one_digit = false;
    size_t cursor = 0;
    for (size_t b = 0; b < buckets; ++b) {
      const size_t bucket_start = cursor;
      for (size_t s = 0; s < slices; ++s) {
        const size_t c = count[s * buckets + b];
        count[s * buckets + b] = cursor;
        cursor += c;
      }
      one_digit |= cursor - bucket_start == n;
    }
    if (one_digit) continue;
    parallel_for(slices, threads, [&](int, size_t s) {
      size_t* c = count.data() + s * buckets;
      for (size_t i = s * per_slice, e = std::min(n, (s + 1) * per_slice); i < e; ++i) {
        const size_t dst = c[(keys[i] >> shift) & digit_mask]++;
        k2[dst] = keys[i];
        p2[dst] = payload[i];
      }
    });
    keys.swap(k2);
    payload.swap(p2);
  }
}

}  // namespace isegman
