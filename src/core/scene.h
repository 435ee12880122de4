// A 3DGS scene as structure-of-arrays, in the trainers' storage conventions:
// positions, log-scales, rotation quaternions (w, x, y, z; not necessarily unit),
// logit opacities and spherical-harmonic colour coefficients.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/math.h"

namespace isegman {

// Number of SH coefficients per colour channel for degree d: (d+1)^2.
inline int sh_coeff_count(int degree) { return (degree + 1) * (degree + 1); }

// A per-vertex PLY property that isegman does not interpret but keeps, so a scene
// round-trips through the tool without losing data (e.g. trainer-specific attributes).
struct ExtraProperty {
  std::string name;
  std::string type;            // PLY scalar type name as read ("float", "uchar", ...)
  int size = 4;                // bytes per value
  std::vector<uint8_t> data;   // size * count bytes, little-endian
};

struct GaussianScene {
  int sh_degree = 0;
  std::vector<float> positions;  // 3N: x y z
  std::vector<float> normals;    // 3N or empty (kept only to round-trip files)
  std::vector<float> sh;         // N * K * 3: [gaussian][coefficient][channel], K = (d+1)^2
  std::vector<float> opacity;    // N: logits
  std::vector<float> scales;     // 3N: log scales
  std::vector<float> rotations;  // 4N: w x y z
  std::vector<ExtraProperty> extras;

  size_t size() const { return opacity.size(); }
  int coeffs() const { return sh_coeff_count(sh_degree); }

  Vec3 position(size_t i) const { return {positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]}; }
  Vec3 scale(size_t i) const {  // linear scale (exp of the stored log)
    return {std::exp(scales[3 * i]), std::exp(scales[3 * i + 1]), std::exp(scales[3 * i + 2])};
  }
  float largest_scale(size_t i) const {  // linear, of the largest axis
    return std::exp(std::max({scales[3 * i], scales[3 * i + 1], scales[3 * i + 2]}));
  }
  Quat rotation(size_t i) const {
    return {rotations[4 * i], rotations[4 * i + 1], rotations[4 * i + 2], rotations[4 * i + 3]};
  }
  float activated_opacity(size_t i) const { return sigmoid(opacity[i]); }
  float* sh_of(size_t i) { return sh.data() + i * coeffs() * 3; }
  const float* sh_of(size_t i) const { return sh.data() + i * coeffs() * 3; }

  // Resizes every array for n Gaussians at the given SH degree (new entries zero,
  // rotations identity). Extra properties and normals are dropped.
  void resize(size_t n, int degree);
  // Appends Gaussian `i` of `other` (same SH degree required).
  void append_from(const GaussianScene& other, size_t i);
  // Keeps the Gaussians whose flag is true, extras and normals included.
  GaussianScene subset(const std::vector<bool>& keep) const;

  // Throws Error(source, ...) on inconsistent array sizes or non-finite values.
  void validate(const std::string& source) const;
  // Axis-aligned bounds of the Gaussian centres.
  void bounds(Vec3& lo, Vec3& hi) const;
  // A content hash over every parameter array that identifies the scene (four lanes of 8-byte
  // words: memory-bound, ~0.1 s for 6M Gaussians, where a byte-serial hash took ~2 s).
  uint64_t fingerprint() const;
  // The fingerprint before 2026-11-26 (FNV-1a over the bytes), which selection files saved
  // then carry: Selection::check_matches accepts it too.
  uint64_t legacy_fingerprint() const;
};

// A scene plus its views, as loaded from a trainer's output directory.
struct SceneBundle {
  GaussianScene gaussians;
  std::vector<Camera> cameras;
  std::string ply_path;      // where the Gaussians came from
  std::string cameras_path;  // where the cameras came from (may be empty)
  std::string images_dir;    // where source photos were found (may be empty)
};

}  // namespace isegman
