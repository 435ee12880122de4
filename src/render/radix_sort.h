// Stable LSD radix sort of (32-bit key, 32-bit payload) pairs: the CPU stand-in for the
// CUDA rasteriser's device radix sort (same order, ties keep their input order).
#pragma once

#include <cstdint>
#include <vector>

namespace isegman {

void radix_sort_pairs(std::vector<uint32_t>& keys, std::vector<uint32_t>& payload);

}  // namespace isegman
