// The rotation matrix of a 3DGS quaternion (w, x, y, z), and its vector-Jacobian product,
// written once for every precision: float for rendering, double for the edit maths and the
// gradient checks of the differentiable rasteriser.
#pragma once

#include <cmath>

namespace isegman {

// Row-major rotation matrix of a unit quaternion (the 3DGS trainers' build_rotation).
template <typename Real>
inline void unit_quat_to_rotmat(Real w, Real x, Real y, Real z, Real R[9]) {
  const Real one = 1, two = 2;
  R[0] = one - two * (y * y + z * z); R[1] = two * (x * y - w * z); R[2] = two * (x * z + w * y);
  R[3] = two * (x * y + w * z); R[4] = one - two * (x * x + z * z); R[5] = two * (y * z - w * x);
  R[6] = two * (x * z - w * y); R[7] = two * (y * z + w * x); R[8] = one - two * (x * x + y * y);
}

// The matrix of q / |q| as trainers store q (not normalised on disk). Keeps the unit
// quaternion and the norm for the backward pass; returns the norm.
template <typename Real>
inline Real quat_to_rotmat(const Real* q, Real R[9], Real qn[4]) {
  Real w = q[0], x = q[1], y = q[2], z = q[3];
  const Real norm = std::sqrt(w * w + x * x + y * y + z * z);
  w /= norm; x /= norm; y /= norm; z /= norm;
  qn[0] = w; qn[1] = x; qn[2] = y; qn[3] = z;
  unit_quat_to_rotmat(w, x, y, z, R);
  return norm;
}

// dL/dq of the unnormalised quaternion from dL/dR (G, row-major), given what
// quat_to_rotmat kept.
template <typename Real>
inline void quat_to_rotmat_vjp(const Real qn[4], Real norm, const Real G[9], Real dq[4]) {
  const Real w = qn[0], x = qn[1], y = qn[2], z = qn[3];
  Real gw = 2 * (-z * G[1] + y * G[2] + z * G[3] - x * G[5] - y * G[6] + x * G[7]);
  Real gx = 2 * (y * G[1] + z * G[2] + y * G[3] - 2 * x * G[4] - w * G[5] + z * G[6] + w * G[7] - 2 * x * G[8]);
  Real gy = 2 * (-2 * y * G[0] + x * G[1] + w * G[2] + x * G[3] + z * G[5] - w * G[6] + z * G[7] - 2 * y * G[8]);
  Real gz = 2 * (-2 * z * G[0] - w * G[1] + x * G[2] + w * G[3] - 2 * z * G[4] + y * G[5] + x * G[6] + y * G[7]);
  // Through the normalisation qn = q / |q|.
  const Real d = w * gw + x * gx + y * gy + z * gz;
  dq[0] = (gw - w * d) / norm;
  dq[1] = (gx - x * d) / norm;
  dq[2] = (gy - y * d) / norm;
  dq[3] = (gz - z * d) / norm;
}

}  // namespace isegman
