// Real spherical harmonics up to degree 3 in the 3DGS trainers' basis and sign convention.
#pragma once

namespace isegman {

constexpr float kShC0 = 0.28209479177387814f;
constexpr float kShC1 = 0.4886025119029199f;
constexpr float kShC2[5] = {1.0925484305920792f, -1.0925484305920792f, 0.31539156525252005f,
                            -1.0925484305920792f, 0.5462742152960396f};
constexpr float kShC3[7] = {-0.5900435899266435f, 2.890611442640554f, -0.4570457994644658f,
                            0.3731763325901154f, -0.4570457994644658f, 1.445305721320277f,
                            -0.5900435899266435f};

// Basis values for a unit direction (x, y, z), as many as (degree+1)^2. One template for
// every precision: float for rendering, double for the SH rotation and the gradient checks.
template <typename Real>
inline void sh_basis(int degree, Real x, Real y, Real z, Real* b) {
  b[0] = Real(kShC0);
  if (degree < 1) return;
  b[1] = -Real(kShC1) * y;
  b[2] = Real(kShC1) * z;
  b[3] = -Real(kShC1) * x;
  if (degree < 2) return;
  const Real xx = x * x, yy = y * y, zz = z * z, xy = x * y, yz = y * z, xz = x * z;
  b[4] = Real(kShC2[0]) * xy;
  b[5] = Real(kShC2[1]) * yz;
  b[6] = Real(kShC2[2]) * (Real(2) * zz - xx - yy);
  b[7] = Real(kShC2[3]) * xz;
  b[8] = Real(kShC2[4]) * (xx - yy);
  if (degree < 3) return;
  b[9] = Real(kShC3[0]) * y * (Real(3) * xx - yy);
  b[10] = Real(kShC3[1]) * xy * z;
  b[11] = Real(kShC3[2]) * y * (Real(4) * zz - xx - yy);
  b[12] = Real(kShC3[3]) * z * (Real(2) * zz - Real(3) * xx - Real(3) * yy);
  b[13] = Real(kShC3[4]) * x * (Real(4) * zz - xx - yy);
  b[14] = Real(kShC3[5]) * z * (xx - yy);
  b[15] = Real(kShC3[6]) * x * (xx - Real(3) * yy);
}

// Its derivatives d b_k / d(x, y, z) for k < (degree+1)^2, for the backward pass.
template <typename Real>
inline void sh_basis_grad(int degree, Real x, Real y, Real z, Real dx[16], Real dy[16], Real dz[16]) {
  for (int k = 0; k < 16; ++k) dx[k] = dy[k] = dz[k] = 0;
  if (degree < 1) return;
  const Real c1 = Real(kShC1);
  dy[1] = -c1;
  dz[2] = c1;
  dx[3] = -c1;
  if (degree < 2) return;
  const Real xx = x * x, yy = y * y, zz = z * z;
  const Real a0 = Real(kShC2[0]), a1 = Real(kShC2[1]), a2 = Real(kShC2[2]), a3 = Real(kShC2[3]), a4 = Real(kShC2[4]);
  dx[4] = a0 * y; dy[4] = a0 * x;
  dy[5] = a1 * z; dz[5] = a1 * y;
  dx[6] = -2 * a2 * x; dy[6] = -2 * a2 * y; dz[6] = 4 * a2 * z;
  dx[7] = a3 * z; dz[7] = a3 * x;
  dx[8] = 2 * a4 * x; dy[8] = -2 * a4 * y;
  if (degree < 3) return;
  const Real b0 = Real(kShC3[0]), b1 = Real(kShC3[1]), b2 = Real(kShC3[2]), b3 = Real(kShC3[3]),
             b4 = Real(kShC3[4]), b5 = Real(kShC3[5]), b6 = Real(kShC3[6]);
  dx[9] = b0 * 6 * x * y; dy[9] = b0 * (3 * xx - 3 * yy);
  dx[10] = b1 * y * z; dy[10] = b1 * x * z; dz[10] = b1 * x * y;
  dx[11] = b2 * (-2 * x * y); dy[11] = b2 * (4 * zz - xx - 3 * yy); dz[11] = b2 * 8 * y * z;
  dx[12] = b3 * (-6 * x * z); dy[12] = b3 * (-6 * y * z); dz[12] = b3 * (6 * zz - 3 * xx - 3 * yy);
  dx[13] = b4 * (4 * zz - 3 * xx - yy); dy[13] = b4 * (-2 * x * y); dz[13] = b4 * 8 * x * z;
  dx[14] = b5 * 2 * x * z; dy[14] = b5 * (-2 * y * z); dz[14] = b5 * (xx - yy);
  dx[15] = b6 * (3 * xx - 3 * yy); dy[15] = b6 * (-6 * x * y);
}

// RGB colour seen along unit direction (x, y, z) from coefficients laid out
// [coefficient][channel]: max(sum_k b_k c_k + 0.5, 0), as the trainers do.
inline void sh_to_rgb(int degree, const float* coeffs, float x, float y, float z, float rgb[3]) {
  float b[16];
  sh_basis(degree, x, y, z, b);
  const int k = (degree + 1) * (degree + 1);
  for (int c = 0; c < 3; ++c) {
    float s = 0.f;
    for (int i = 0; i < k; ++i) s += b[i] * coeffs[3 * i + c];
    s += 0.5f;
    rgb[c] = s > 0.f ? s : 0.f;
  }
}

// DC coefficient that shows colour `rgb` (0..1) when the higher bands are zero.
inline float rgb_to_sh_dc(float rgb) { return (rgb - 0.5f) / kShC0; }
inline float sh_dc_to_rgb(float dc) { return 0.5f + kShC0 * dc; }

}  // namespace isegman
