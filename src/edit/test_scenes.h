// Small deterministic scenes for the edit tests (header-only, test use only).
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "core/random.h"
#include "core/scene.h"

namespace isegman::edit::testing {

// SplitMix64 with the seed spread so that small seeds give unrelated streams.
struct TestRng : SplitMix64 {
  explicit TestRng(uint64_t seed) : SplitMix64(seed * 0x9E3779B97F4A7C15ull + 1) {}
};

// n Gaussians in [-1, 1]^3 with random shapes, unnormalised rotations, opacities and SH
// of `degree`; optionally normals and an extra uchar + float property.
inline GaussianScene random_scene(size_t n, int degree, uint64_t seed, bool normals = true, bool extras = true,
                                  double sh_scale = 0.3) {
  TestRng rng(seed);
  GaussianScene s;
  s.resize(n, degree);
  if (normals) s.normals.resize(3 * n);
  for (size_t i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      s.positions[3 * i + a] = float(rng.range(-1, 1));
      s.scales[3 * i + a] = float(std::log(rng.range(0.01, 0.08)));
      if (normals) s.normals[3 * i + a] = float(rng.range(-1, 1));
    }
    for (int a = 0; a < 4; ++a) s.rotations[4 * i + a] = float(rng.range(-1, 1));
    s.rotations[4 * i] += 1.5f;  // never a zero quaternion
    s.opacity[i] = float(rng.range(-2, 4));
    float* c = s.sh_of(i);
    for (int ch = 0; ch < 3; ++ch) c[ch] = float(rng.range(-1.2, 1.2));
    for (int k = 3; k < 3 * s.coeffs(); ++k) c[k] = float(rng.range(-sh_scale, sh_scale));
  }
  if (extras) {
    ExtraProperty label{"label", "uchar", 1, {}};
    ExtraProperty conf{"confidence", "float", 4, {}};
    for (size_t i = 0; i < n; ++i) {
      label.data.push_back(uint8_t(rng.next()));
      for (int b = 0; b < 4; ++b) conf.data.push_back(uint8_t(rng.next() & 0x3f));
    }
    s.extras = {label, conf};
  }
  return s;
}

inline bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), 4 * a.size()) == 0);
}

// Bit-exact equality of every array (including normals and extras).
inline bool same_scene(const GaussianScene& a, const GaussianScene& b) {
  if (a.sh_degree != b.sh_degree || !same_bits(a.positions, b.positions) || !same_bits(a.normals, b.normals) ||
      !same_bits(a.sh, b.sh) || !same_bits(a.opacity, b.opacity) || !same_bits(a.scales, b.scales) ||
      !same_bits(a.rotations, b.rotations) || a.extras.size() != b.extras.size())
    return false;
  for (size_t e = 0; e < a.extras.size(); ++e)
    if (a.extras[e].name != b.extras[e].name || a.extras[e].type != b.extras[e].type ||
        a.extras[e].size != b.extras[e].size || a.extras[e].data != b.extras[e].data)
      return false;
  return true;
}

}  // namespace isegman::edit::testing
