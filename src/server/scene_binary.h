// The scene and the selection packed for the page's WebGL renderer (web/js/splat_renderer.js).
// Little-endian, fixed records, so the page uploads them without parsing.
//
// Splats (`pack_splats`): a 32-byte header
//   "ISGS" | u32 version (1) | u32 count | u32 record bytes (40) | u64 fingerprint | u64 0
// then per Gaussian, 40 bytes:
//   f32 x, y, z | u8 r, g, b, a | f32 covariance xx, xy, xz, yy, yz, zz
// Colour is the SH DC term as the rasteriser evaluates it (0.5 + C0 * dc, clamped to
// [0, 1]; no view-dependent terms), alpha the activated opacity; the covariance is
// R S S^T R^T of the normalised rotation and the exponentiated scales, in world units.
//
// Selection (`pack_selection`): a 32-byte header
//   "ISGM" | u32 version (1) | u32 count | u32 hidden count | u64 scene fingerprint |
//   u64 selection revision
// then one byte per Gaussian: bit 0 selected, bit 1 hidden (display state).
#pragma once

#include <cstdint>
#include <vector>

#include "core/scene.h"

namespace isegman::server {

constexpr uint32_t kSplatRecordBytes = 40;
constexpr uint32_t kSceneBinaryHeaderBytes = 32;

std::vector<uint8_t> pack_splats(const GaussianScene& scene, uint64_t fingerprint);

// `selected` has one flag per Gaussian; `hidden` too, or is empty (nothing hidden).
std::vector<uint8_t> pack_selection(const std::vector<bool>& selected, const std::vector<bool>& hidden,
                                    uint64_t fingerprint, uint64_t revision);

}  // namespace isegman::server
