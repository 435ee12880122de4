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

// Basis values for a unit direction d, as many as (degree+1)^2.
inline void sh_basis(int degree, float x, float y, float z, float* b) {
  b[0] = kShC0;
  if (degree < 1) return;
  b[1] = -kShC1 * y;
  b[2] = kShC1 * z;
  b[3] = -kShC1 * x;
  if (degree < 2) return;
  const float xx = x * x, yy = y * y, zz = z * z, xy = x * y, yz = y * z, xz = x * z;
  b[4] = kShC2[0] * xy;
  b[5] = kShC2[1] * yz;
  b[6] = kShC2[2] * (2.0f * zz - xx - yy);
  b[7] = kShC2[3] * xz;
  b[8] = kShC2[4] * (xx - yy);
  if (degree < 3) return;
  b[9] = kShC3[0] * y * (3.0f * xx - yy);
  b[10] = kShC3[1] * xy * z;
  b[11] = kShC3[2] * y * (4.0f * zz - xx - yy);
  b[12] = kShC3[3] * z * (2.0f * zz - 3.0f * xx - 3.0f * yy);
  b[13] = kShC3[4] * x * (4.0f * zz - xx - yy);
  b[14] = kShC3[5] * z * (xx - yy);
  b[15] = kShC3[6] * x * (xx - 3.0f * yy);
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
