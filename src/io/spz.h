// Niantic's .spz (github.com/nianticlabs/spz): quantised Gaussians, one attribute after
// another (positions, alphas, colours, scales, rotations, SH), compressed.
//   v1-3: one gzip stream holding a 16-byte header + the attributes (v1: float16
//         positions; v1-2: rotations as 3 bytes xyz; v3: "smallest three" in 32 bits).
//   v4:   a plain 32-byte header, a table of contents and one zstd stream per attribute.
// Quantisation (all versions): positions 24-bit fixed point with `fractionalBits`, alpha
// = sigmoid(opacity) x 255, colour = f_dc x 0.15 x 255 + 127.5, scales (log + 10) x 16,
// SH (x x 128 + 128) rounded to buckets of 8 (degree 1) / 16 (degrees 2-3).
// Axes: SPZ stores RUB (x right, y up, z back); isegman and INRIA PLY use RDF. Reading and
// writing flip y and z of positions, conjugate rotations by that flip (w, x, -y, -z) and
// negate the SH coefficients whose basis function is odd in y and z together.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/scene.h"

namespace isegman {

struct SpzWriteOptions {
  // 4 (zstd streams): the newest the reference tools read (splat-transform 2.7.1, the
  // Niantic library); 3 or 2 (gzip) for older readers.
  int version = 4;
};

// True when the bytes start like an .spz (gzip magic or the v4 "NGSP" header).
bool looks_like_spz(const uint8_t* data, size_t size);

// Decodes any version 1-4; throws Error(source, ...) on truncated or corrupt data.
// `notes` gets what was dropped (SH degree 4, extensions).
GaussianScene parse_spz(const uint8_t* data, size_t size, const std::string& source,
                        std::vector<std::string>* notes = nullptr);
// Validates the scene and encodes it; `notes` gets what the format could not keep.
std::vector<uint8_t> serialize_spz(const GaussianScene& scene, const SpzWriteOptions& options = {},
                                   std::vector<std::string>* notes = nullptr);

// The scene with y and z flipped (positions, rotations, SH): RDF <-> RUB, its own
// inverse. For files from writers that stored PLY axes unconverted (spz-js 1.x, the
// reference library with coordinate system UNSPECIFIED).
GaussianScene flip_y_z(const GaussianScene& scene);

}  // namespace isegman
