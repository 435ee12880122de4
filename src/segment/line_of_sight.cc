#include "segment/line_of_sight.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/quat_rotation.h"

namespace isegman::segment {

LineOfSight::LineOfSight(const GaussianScene& scene, const CentreIndex& index) : scene_(scene), index_(index) {
  const size_t n = scene.size();
  if (n == 0) return;
  const size_t step = std::max<size_t>(1, n / 100000);  // a sample is enough for a percentile
  std::vector<float> largest;
  for (size_t i = 0; i < n; i += step) {
    const float* s = &scene.scales[3 * i];
    largest.push_back(std::max({s[0], s[1], s[2]}));
  }
  const size_t at = size_t(0.99 * double(largest.size() - 1));
  std::nth_element(largest.begin(), largest.begin() + long(at), largest.end());
  reach_ = 3.0 * std::exp(double(largest[at]));
}

double LineOfSight::transmittance(const Vec3& from, const Vec3& to) const {
  const Vec3 d = to - from;
  if (!(dot(d, d) > 0) || reach_ <= 0) return 1.0;
  double T = 1.0;
  for (uint32_t i : index_.near_segment(from, to, reach_)) {
    const double opacity = sigmoid(double(scene_.opacity[i]));
    if (opacity < 1.0 / 255) continue;
    // Inverse covariance R S^-2 R^T, with R's columns the Gaussian's axes.
    double q[4], R[9], qn[4];
    for (int k = 0; k < 4; ++k) q[k] = scene_.rotations[4 * size_t(i) + k];
    if (!(quat_to_rotmat(q, R, qn) > 0)) continue;  // no orientation: no shape to block with
    double inv_s2[3];
    for (int k = 0; k < 3; ++k) inv_s2[k] = std::exp(-2.0 * double(scene_.scales[3 * size_t(i) + k]));
    const Vec3 v = from - scene_.position(i);
    // In the Gaussian's axes: the quadratic form of v + t d is sum_k (a_k + t b_k)^2 / s_k^2.
    double vv = 0, vd = 0, dd = 0;
    for (int k = 0; k < 3; ++k) {
      const double a = R[k] * v.x + R[3 + k] * v.y + R[6 + k] * v.z;
      const double b = R[k] * d.x + R[3 + k] * d.y + R[6 + k] * d.z;
      vv += a * a * inv_s2[k];
      vd += a * b * inv_s2[k];
      dd += b * b * inv_s2[k];
    }
    const double t = dd > 0 ? std::clamp(-vd / dd, 0.0, 1.0) : 0.0;
    const double power = vv + 2 * t * vd + t * t * dd;
    const double alpha = std::min(0.99, opacity * std::exp(-0.5 * power));
    if (!(alpha >= 1.0 / 255)) continue;  // NaN from a degenerate scale too
    T *= 1.0 - alpha;
    if (T < 1e-4) return 0.0;
  }
  return T;
}

}  // namespace isegman::segment
