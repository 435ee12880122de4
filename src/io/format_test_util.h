// Test helpers for the splat formats: plausible synthetic scenes and the per-attribute
// differences between two scenes, in the units the tolerances are stated in.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/random.h"
#include "core/scene.h"
#include "core/sh.h"

namespace isegman::testing_formats {

// Values inside every format's range: positions in +-range, log-scales in [-6, 0],
// opacities in [-4, 4], f_dc in [-1.5, 1.5], SH rest in [-0.4, 0.4].
inline GaussianScene plausible_scene(size_t n, int degree, uint64_t seed, double range = 3.0) {
  SplitMix64 r(seed);
  GaussianScene s;
  s.resize(n, degree);
  for (size_t i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) {
      s.positions[3 * i + a] = float(r.range(-range, range));
      s.scales[3 * i + a] = float(r.range(-6, 0));
    }
    s.opacity[i] = float(r.range(-4, 4));
    for (int k = 0; k < 4; ++k) s.rotations[4 * i + k] = float(r.normal());
    float* c = s.sh_of(i);
    for (int ch = 0; ch < 3; ++ch) c[ch] = float(r.range(-1.5, 1.5));
    for (int k = 3; k < 3 * s.coeffs(); ++k) c[k] = float(r.range(-0.4, 0.4));
  }
  return s;
}

struct Differences {
  double position = 0;  // max |dx| over coordinates
  double mean_position = 0;  // mean |dx| over coordinates
  double log_scale = 0;  // max |d log s|
  double alpha = 0;      // max |d sigmoid(opacity)|
  double rotation = 0;   // max angle between the rotations, radians
  double dc = 0;         // max |d f_dc|
  double sh = 0;         // max |d f_rest|
};

// `order` maps b's Gaussians to a's (b[j] is a[order[j]]); identity when empty.
inline Differences differences(const GaussianScene& a, const GaussianScene& b,
                               const std::vector<uint32_t>& order = {}) {
  Differences d;
  const int K = std::min(a.coeffs(), b.coeffs());
  for (size_t j = 0; j < b.size(); ++j) {
    const size_t i = order.empty() ? j : order[j];
    for (int k = 0; k < 3; ++k) {
      const double dp = std::fabs(a.positions[3 * i + k] - b.positions[3 * j + k]);
      d.position = std::max(d.position, dp);
      d.mean_position += dp / double(3 * b.size());
      d.log_scale = std::max(d.log_scale, double(std::fabs(a.scales[3 * i + k] - b.scales[3 * j + k])));
      d.dc = std::max(d.dc, double(std::fabs(a.sh_of(i)[k] - b.sh_of(j)[k])));
    }
    d.alpha = std::max(d.alpha, double(std::fabs(a.activated_opacity(i) - b.activated_opacity(j))));
    const Quat p = a.rotation(i).normalized(), q = b.rotation(j).normalized();
    const double dot = std::min(1.0, std::fabs(p.w * q.w + p.x * q.x + p.y * q.y + p.z * q.z));
    d.rotation = std::max(d.rotation, 2.0 * std::acos(dot));
    for (int k = 1; k < K; ++k)
      for (int ch = 0; ch < 3; ++ch)
        d.sh = std::max(d.sh, double(std::fabs(a.sh_of(i)[3 * k + ch] - b.sh_of(j)[3 * k + ch])));
  }
  return d;
}

}  // namespace isegman::testing_formats
