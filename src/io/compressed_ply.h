// SuperSplat's compressed PLY (PlayCanvas): binary little-endian PLY with
//   element chunk  ceil(N/256): float min_x..max_z, min_scale_x..max_scale_z
//                  [, min_r min_g min_b max_r max_g max_b]
//   element vertex N: uint packed_position, packed_rotation, packed_scale, packed_color
//   [element sh N: uchar f_rest_0 .. f_rest_{9|24|45-1}]
// Positions and log-scales are 11-10-11 bit fractions of their chunk's range; colour
// (0.5 + C0 f_dc, per-chunk range when present) and sigmoid(opacity) are 8-8-8-8; the
// rotation keeps the index of its largest component (2 bits) and the other three as
// 10-bit fractions of [-1/sqrt2, 1/sqrt2]; SH bytes are f_rest / 8 + 0.5 in 1/256 steps.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/scene.h"

namespace isegman {

// True when the bytes are a PLY whose header declares packed_position (the compressed form).
bool is_compressed_ply(const uint8_t* data, size_t size);

GaussianScene parse_compressed_ply(const uint8_t* data, size_t size, const std::string& source);

// Encodes 256-Gaussian chunks in the scene's order: ranges are tight when neighbours in
// the file are neighbours in space, so `spatial_order` (default) first sorts a copy in
// Morton order of the centres; `order` (when given) receives, for each written Gaussian,
// its index in `scene`.
std::vector<uint8_t> serialize_compressed_ply(const GaussianScene& scene, bool spatial_order = true,
                                              std::vector<uint32_t>* order = nullptr,
                                              std::vector<std::string>* notes = nullptr);

}  // namespace isegman
