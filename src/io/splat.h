// The 32-byte-per-Gaussian ".splat" format of web viewers (antimatter15/splat and
// descendants), little-endian, no header:
//   float32 x, y, z          position
//   float32 sx, sy, sz       linear scales (exp of the log-scales)
//   uint8   r, g, b, a       base colour 0.5 + C0 * f_dc and sigmoid(opacity), x255
//   uint8   qw, qx, qy, qz   normalised rotation, q * 128 + 128
// It holds SH degree 0 only: writing drops bands 1-3 (a note says so), colours and
// opacities are quantised to 8 bits, rotations to about 1/128.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "core/scene.h"

namespace isegman {

constexpr size_t kSplatRecordBytes = 32;

// A little-endian float32 field of a record.
inline float splat_f32(const uint8_t* p) {
  const uint32_t u = uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
  float v;
  std::memcpy(&v, &u, 4);
  return v;
}

// Validates the scene (non-empty, finite) and encodes it; `notes` gets what was lost.
std::vector<uint8_t> serialize_splat(const GaussianScene& scene, std::vector<std::string>* notes = nullptr);
// Decodes; throws Error(source, ...) on a size that is not a positive multiple of 32,
// a non-finite or non-positive value, or a zero rotation.
GaussianScene parse_splat(const uint8_t* data, size_t size, const std::string& source);

GaussianScene read_splat(const std::string& path);
// Atomic write.
void write_splat(const std::string& path, const GaussianScene& scene, std::vector<std::string>* notes = nullptr);

}  // namespace isegman
