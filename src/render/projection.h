// EWA projection of one 3D Gaussian to its 2D screen-space footprint, exactly as the
// INRIA CUDA rasteriser does it (Zwicker et al. 2001; Kerbl et al. 2023):
//   Sigma = R S S^T R^T, cov2D = J W Sigma W^T J^T + 0.3 I, 3-sigma radius.
// Pixel coordinates here are "index" coordinates: pixel (i, j) has its centre at (i, j),
// i.e. the continuous coordinate minus 0.5.
#pragma once

#include <cmath>

#include "core/camera.h"

namespace isegman {

// Camera constants prepared once per render, in the precision of the pass (float for
// rendering, double for the gradient checks of the differentiable rasteriser).
template <typename Real>
struct BasicProjectionCamera {
  Real R[9];  // world -> camera, row-major
  Real t[3];
  Real fx, fy, cx, cy;  // cx, cy in index coordinates (continuous - 0.5)
  Real lim_x_lo, lim_x_hi, lim_y_lo, lim_y_hi;  // clamp of x/z, y/z for the Jacobian
  Real center[3];  // camera centre in world space (for SH view directions)
  int width, height;

  explicit BasicProjectionCamera(const Camera& cam) {
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) R[3 * r + c] = Real(cam.R.m[r][c]);
      t[r] = Real(cam.t[r]);
    }
    fx = Real(cam.fx);
    fy = Real(cam.fy);
    cx = Real(cam.cx - 0.5);
    cy = Real(cam.cy - 0.5);
    // INRIA clamps x/z to +-1.3 tan(fov/2); with an off-centre principal point the
    // same 30 % margin is taken on each side of the image.
    lim_x_lo = -Real((cam.cx + 0.15 * cam.width) / cam.fx);
    lim_x_hi = Real((cam.width - cam.cx + 0.15 * cam.width) / cam.fx);
    lim_y_lo = -Real((cam.cy + 0.15 * cam.height) / cam.fy);
    lim_y_hi = Real((cam.height - cam.cy + 0.15 * cam.height) / cam.fy);
    const Vec3 c = cam.center();
    center[0] = Real(c.x);
    center[1] = Real(c.y);
    center[2] = Real(c.z);
    width = cam.width;
    height = cam.height;
  }
};
using ProjectionCamera = BasicProjectionCamera<float>;

// 3D covariance (upper triangle: xx xy xz yy yz zz) from log-scales and a quaternion.
inline void covariance_3d(const float* log_scale, const float* quat_wxyz, float cov[6]) {
  float w = quat_wxyz[0], x = quat_wxyz[1], y = quat_wxyz[2], z = quat_wxyz[3];
  const float n = std::sqrt(w * w + x * x + y * y + z * z);
  w /= n; x /= n; y /= n; z /= n;
  const float Rm[9] = {1.f - 2.f * (y * y + z * z), 2.f * (x * y - w * z), 2.f * (x * z + w * y),
                       2.f * (x * y + w * z), 1.f - 2.f * (x * x + z * z), 2.f * (y * z - w * x),
                       2.f * (x * z - w * y), 2.f * (y * z + w * x), 1.f - 2.f * (x * x + y * y)};
  const float s[3] = {std::exp(log_scale[0]), std::exp(log_scale[1]), std::exp(log_scale[2])};
  float M[9];  // M = R S
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) M[3 * r + c] = Rm[3 * r + c] * s[c];
  // Sigma = M M^T
  cov[0] = M[0] * M[0] + M[1] * M[1] + M[2] * M[2];
  cov[1] = M[0] * M[3] + M[1] * M[4] + M[2] * M[5];
  cov[2] = M[0] * M[6] + M[1] * M[7] + M[2] * M[8];
  cov[3] = M[3] * M[3] + M[4] * M[4] + M[5] * M[5];
  cov[4] = M[3] * M[6] + M[4] * M[7] + M[5] * M[8];
  cov[5] = M[6] * M[6] + M[7] * M[7] + M[8] * M[8];
}

struct Footprint {
  float mean_x, mean_y;  // index coordinates
  float depth;           // camera-space z
  float cov_a, cov_b, cov_c;        // 2D covariance incl. the 0.3 blur
  float conic_a, conic_b, conic_c;  // its inverse
  int radius;                        // 3-sigma radius in pixels (ceil)
};

// Projects Gaussian centre `p` with 3D covariance `cov3`; false when culled (near plane,
// degenerate covariance).
inline bool project_footprint(const ProjectionCamera& cam, const float* p, const float* cov3, float near_plane,
                              float blur, Footprint& f) {
  const float* R = cam.R;
  const float tx0 = R[0] * p[0] + R[1] * p[1] + R[2] * p[2] + cam.t[0];
  const float ty0 = R[3] * p[0] + R[4] * p[1] + R[5] * p[2] + cam.t[1];
  const float tz = R[6] * p[0] + R[7] * p[1] + R[8] * p[2] + cam.t[2];
  if (tz <= near_plane) return false;
  const float inv_z = 1.f / tz;
  // Jacobian of the perspective map at the (clamped) point.
  const float txtz = std::fmin(std::fmax(tx0 * inv_z, cam.lim_x_lo), cam.lim_x_hi);
  const float tytz = std::fmin(std::fmax(ty0 * inv_z, cam.lim_y_lo), cam.lim_y_hi);
  const float tx = txtz * tz, ty = tytz * tz;
  const float j00 = cam.fx * inv_z, j02 = -cam.fx * tx * inv_z * inv_z;
  const float j11 = cam.fy * inv_z, j12 = -cam.fy * ty * inv_z * inv_z;
  // T = J W (2x3)
  const float T0[3] = {j00 * R[0] + j02 * R[6], j00 * R[1] + j02 * R[7], j00 * R[2] + j02 * R[8]};
  const float T1[3] = {j11 * R[3] + j12 * R[6], j11 * R[4] + j12 * R[7], j11 * R[5] + j12 * R[8]};
  const float S[9] = {cov3[0], cov3[1], cov3[2], cov3[1], cov3[3], cov3[4], cov3[2], cov3[4], cov3[5]};
  float ST0[3], ST1[3];  // Sigma T^T columns
  for (int r = 0; r < 3; ++r) {
    ST0[r] = S[3 * r] * T0[0] + S[3 * r + 1] * T0[1] + S[3 * r + 2] * T0[2];
    ST1[r] = S[3 * r] * T1[0] + S[3 * r + 1] * T1[1] + S[3 * r + 2] * T1[2];
  }
  const float a = T0[0] * ST0[0] + T0[1] * ST0[1] + T0[2] * ST0[2] + blur;
  const float b = T0[0] * ST1[0] + T0[1] * ST1[1] + T0[2] * ST1[2];
  const float c = T1[0] * ST1[0] + T1[1] * ST1[1] + T1[2] * ST1[2] + blur;
  const float det = a * c - b * b;
  if (!(det > 0.f)) return false;
  const float inv_det = 1.f / det;
  f.conic_a = c * inv_det;
  f.conic_b = -b * inv_det;
  f.conic_c = a * inv_det;
  f.cov_a = a;
  f.cov_b = b;
  f.cov_c = c;
  const float mid = 0.5f * (a + c);
  const float disc = std::sqrt(std::fmax(0.1f, mid * mid - det));
  const float lambda1 = mid + disc, lambda2 = mid - disc;
  f.radius = int(std::ceil(3.f * std::sqrt(std::fmax(lambda1, lambda2))));
  f.mean_x = cam.fx * tx0 * inv_z + cam.cx;
  f.mean_y = cam.fy * ty0 * inv_z + cam.cy;
  f.depth = tz;
  return true;
}

}  // namespace isegman
