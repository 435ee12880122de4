// EWA projection of one 3D Gaussian to its 2D screen-space footprint, exactly as the
// INRIA CUDA rasteriser does it (Zwicker et al. 2001; Kerbl et al. 2023):
//   Sigma = R S S^T R^T, cov2D = J W Sigma W^T J^T + 0.3 I, 3-sigma radius.
// Pixel coordinates here are "index" coordinates: pixel (i, j) has its centre at (i, j),
// i.e. the continuous coordinate minus 0.5.
#pragma once

#include <cmath>

#include "core/camera.h"
#include "core/quat_rotation.h"

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

// The 3D covariance Sigma = R S S^T R^T of a Gaussian from its log-scales and quaternion,
// with the factors the backward pass differentiates through.
template <typename Real>
struct BasicCovariance3d {
  Real rot[9];          // R (row-major) of the normalised quaternion
  Real qn[4], qnorm;    // that quaternion and the stored one's norm
  Real s[3];            // scales
  Real M[9];            // R S
  Real cov[6];          // upper triangle: xx xy xz yy yz zz
};

template <typename Real>
inline void covariance_3d(const Real* log_scale, const Real* quat_wxyz, BasicCovariance3d<Real>& c) {
  c.qnorm = quat_to_rotmat(quat_wxyz, c.rot, c.qn);
  for (int k = 0; k < 3; ++k) c.s[k] = std::exp(log_scale[k]);
  Real* M = c.M;
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) M[3 * r + k] = c.rot[3 * r + k] * c.s[k];
  // Sigma = M M^T
  c.cov[0] = M[0] * M[0] + M[1] * M[1] + M[2] * M[2];
  c.cov[1] = M[0] * M[3] + M[1] * M[4] + M[2] * M[5];
  c.cov[2] = M[0] * M[6] + M[1] * M[7] + M[2] * M[8];
  c.cov[3] = M[3] * M[3] + M[4] * M[4] + M[5] * M[5];
  c.cov[4] = M[3] * M[6] + M[4] * M[7] + M[5] * M[8];
  c.cov[5] = M[6] * M[6] + M[7] * M[7] + M[8] * M[8];
}

// The covariance alone, for the forward passes.
inline void covariance_3d(const float* log_scale, const float* quat_wxyz, float cov[6]) {
  BasicCovariance3d<float> c;
  covariance_3d(log_scale, quat_wxyz, c);
  for (int k = 0; k < 6; ++k) cov[k] = c.cov[k];
}

template <typename Real>
struct BasicFootprint {
  Real mean_x, mean_y;  // index coordinates
  Real depth;           // camera-space z
  Real cov_a, cov_b, cov_c;        // 2D covariance incl. the blur
  Real conic_a, conic_b, conic_c;  // its inverse
  int radius;                      // 3-sigma radius in pixels (ceil)
  // For the backward pass: the camera-space centre, its x/z and y/z after the clamp (and
  // whether the clamp acted), and T = J W.
  Real tx0, ty0, txtz, tytz;
  bool clamp_x, clamp_y;
  Real T0[3], T1[3];
};
using Footprint = BasicFootprint<float>;

// Projects Gaussian centre `p` with 3D covariance `cov3`; false when culled (near plane,
// degenerate covariance).
template <typename Real>
inline bool project_footprint(const BasicProjectionCamera<Real>& cam, const Real* p, const Real* cov3, Real near_plane,
                              Real blur, BasicFootprint<Real>& f) {
  const Real* R = cam.R;
  f.tx0 = R[0] * p[0] + R[1] * p[1] + R[2] * p[2] + cam.t[0];
  f.ty0 = R[3] * p[0] + R[4] * p[1] + R[5] * p[2] + cam.t[1];
  const Real tz = R[6] * p[0] + R[7] * p[1] + R[8] * p[2] + cam.t[2];
  if (tz <= near_plane) return false;
  f.depth = tz;
  const Real inv_z = Real(1) / tz;
  // Jacobian of the perspective map at the (clamped) point.
  const Real ux = f.tx0 * inv_z, uy = f.ty0 * inv_z;
  f.txtz = std::fmin(std::fmax(ux, cam.lim_x_lo), cam.lim_x_hi);
  f.tytz = std::fmin(std::fmax(uy, cam.lim_y_lo), cam.lim_y_hi);
  f.clamp_x = f.txtz != ux;
  f.clamp_y = f.tytz != uy;
  const Real tx = f.txtz * tz, ty = f.tytz * tz;
  const Real j00 = cam.fx * inv_z, j02 = -cam.fx * tx * inv_z * inv_z;
  const Real j11 = cam.fy * inv_z, j12 = -cam.fy * ty * inv_z * inv_z;
  // T = J W (2x3)
  for (int k = 0; k < 3; ++k) {
    f.T0[k] = j00 * R[k] + j02 * R[6 + k];
    f.T1[k] = j11 * R[3 + k] + j12 * R[6 + k];
  }
  const Real* T0 = f.T0;
  const Real* T1 = f.T1;
  const Real S[9] = {cov3[0], cov3[1], cov3[2], cov3[1], cov3[3], cov3[4], cov3[2], cov3[4], cov3[5]};
  Real ST0[3], ST1[3];  // Sigma T^T columns
  for (int r = 0; r < 3; ++r) {
    ST0[r] = S[3 * r] * T0[0] + S[3 * r + 1] * T0[1] + S[3 * r + 2] * T0[2];
    ST1[r] = S[3 * r] * T1[0] + S[3 * r + 1] * T1[1] + S[3 * r + 2] * T1[2];
  }
  const Real a = T0[0] * ST0[0] + T0[1] * ST0[1] + T0[2] * ST0[2] + blur;
  const Real b = T0[0] * ST1[0] + T0[1] * ST1[1] + T0[2] * ST1[2];
  const Real c = T1[0] * ST1[0] + T1[1] * ST1[1] + T1[2] * ST1[2] + blur;
  const Real det = a * c - b * b;
  if (!(det > Real(0))) return false;
  const Real inv_det = Real(1) / det;
  f.conic_a = c * inv_det;
  f.conic_b = -b * inv_det;
  f.conic_c = a * inv_det;
  f.cov_a = a;
  f.cov_b = b;
  f.cov_c = c;
  const Real mid = Real(0.5) * (a + c);
  const Real disc = std::sqrt(std::fmax(Real(0.1), mid * mid - det));
  const Real lambda1 = mid + disc, lambda2 = mid - disc;
  f.radius = int(std::ceil(Real(3) * std::sqrt(std::fmax(lambda1, lambda2))));
  f.mean_x = cam.fx * f.tx0 * inv_z + cam.cx;
  f.mean_y = cam.fy * f.ty0 * inv_z + cam.cy;
  return true;
}

}  // namespace isegman
