// The scene and the selection packed for the page's WebGL renderer (web/js/splat_renderer.js).
// Little-endian, fixed records, so the page uploads them without parsing.
//
// Splats (`pack_splats`): a 32-byte header
//   "ISGS" | u32 version (3) | u32 count | u32 record bytes (40) | u64 fingerprint |
//   u32 SH degree d | u32 SH bytes per Gaussian (3 ((d+1)^2 - 1))
// then per Gaussian, 40 bytes:
//   f32 x, y, z | u8 r, g, b, a | f32 covariance xx, xy, xz, yy, yz, zz
// then 8 bytes: f32 lo, hi, the range of the colour bytes.
// Colour is the SH DC term as the rasteriser evaluates it (0.5 + C0 * dc), each byte q
// standing for lo + (hi - lo) q / 255; alpha the activated opacity; the covariance is
// R S S^T R^T of the normalised rotation and the exponentiated scales, in world units.
// The rasteriser clamps a Gaussian's colour at 0 only, after adding every SH degree, and
// blends colours above 1: so hi is the scene's largest base colour (at least 1, at most
// kColourHigh), and lo 0 without SH or the smallest base colour with it (at least
// kColourLow), where view-dependent terms may bring a negative base colour back up.
// When d > 0, the view-dependent rest follows: 16 bytes of f32 band scales s1, s2, s3, 0,
// then per Gaussian its coefficients 1 .. (d+1)^2 - 1, each as r, g, b (core/sh.h's order),
// one byte each: q = round(127 c / s_band) + 128, so c = (q - 128) s_band / 127; s_band is
// the band's largest |c| (8 bits per coefficient: a quarter of float32's payload, errors
// under 1/255 of colour per coefficient).
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
constexpr uint32_t kShScalesBytes = 16;
constexpr uint32_t kColourRangeBytes = 8;
// Bounds of the colour bytes' range (a wider range costs every colour precision).
constexpr float kColourLow = -1.f, kColourHigh = 2.f;

std::vector<uint8_t> pack_splats(const GaussianScene& scene, uint64_t fingerprint);

// `selected` has one flag per Gaussian; `hidden` too, or is empty (nothing hidden).
std::vector<uint8_t> pack_selection(const std::vector<bool>& selected, const std::vector<bool>& hidden,
                                    uint64_t fingerprint, uint64_t revision);

}  // namespace isegman::server
