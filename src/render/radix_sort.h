// Stable LSD radix sort of (32-bit key, 32-bit payload) pairs: the CPU stand-in for the
// CUDA rasteriser's device radix sort (same order, ties keep their input order).
#pragma once

#include <cstdint>
#include <vector>

namespace isegman {

// Digits of up to 12 bits, as few passes as the largest key needs (Gaussian indices below
// 2^24: two; float depth bits: three). Long lists are counted and scattered in slices on
// `threads` workers (0 = all cores); the order is the same on any thread count.
void radix_sort_pairs(std::vector<uint32_t>& keys, std::vector<uint32_t>& payload, int threads = 1);

}  // namespace isegman
