#include "edit/sh_rotation.h"

#include <cmath>

#include "core/error.h"
#include "core/sh.h"

namespace isegman::edit {

namespace {

constexpr int kSamples = 26;  // > 2l+1 for every band; spread over the sphere

// Fibonacci-sphere directions (well spread, none degenerate for any band).
void sample_direction(int j, double d[3]) {
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  const double z = 1.0 - 2.0 * (j + 0.5) / kSamples;
  const double r = std::sqrt(1.0 - z * z);
  d[0] = r * std::cos(golden * j);
  d[1] = r * std::sin(golden * j);
  d[2] = z;
}

// Inverts an n x n matrix (n <= 7) by Gauss-Jordan with partial pivoting.
void invert(int n, double a[7][7], double inv[7][7]) {
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) inv[r][c] = r == c;
  for (int c = 0; c < n; ++c) {
    int p = c;
    for (int r = c + 1; r < n; ++r)
      if (std::fabs(a[r][c]) > std::fabs(a[p][c])) p = r;
    if (std::fabs(a[p][c]) < 1e-12) throw Error("SH rotation", "singular sample matrix");
    for (int k = 0; k < n; ++k) {
      std::swap(a[c][k], a[p][k]);
      std::swap(inv[c][k], inv[p][k]);
    }
    const double s = 1.0 / a[c][c];
    for (int k = 0; k < n; ++k) {
      a[c][k] *= s;
      inv[c][k] *= s;
    }
    for (int r = 0; r < n; ++r) {
      if (r == c) continue;
      const double f = a[r][c];
      if (f == 0) continue;
      for (int k = 0; k < n; ++k) {
        a[r][k] -= f * a[c][k];
        inv[r][k] -= f * inv[c][k];
      }
    }
  }
}

// Per band: the sample basis B_l (values at the sample directions) and the
// pseudo-inverse P_l = B_l^T (B_l B_l^T)^-1, independent of the rotation.
struct Fit {
  double P[4][kSamples][7] = {};
  Fit() {
    double basis[kSamples][16];
    for (int j = 0; j < kSamples; ++j) {
      double d[3];
      sample_direction(j, d);
      sh_basis(3, d[0], d[1], d[2], basis[j]);
    }
    for (int l = 1; l <= 3; ++l) {
      const int n = 2 * l + 1, off = l * l;
      double g[7][7] = {}, gi[7][7];
      for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c)
          for (int j = 0; j < kSamples; ++j) g[r][c] += basis[j][off + r] * basis[j][off + c];
      invert(n, g, gi);
      for (int j = 0; j < kSamples; ++j)
        for (int c = 0; c < n; ++c) {
          double s = 0;
          for (int k = 0; k < n; ++k) s += basis[j][off + k] * gi[k][c];
          P[l][j][c] = s;
        }
    }
  }
};

const Fit& fit() {
  static const Fit f;
  return f;
}

}  // namespace

ShRotation::ShRotation(const Mat3& R) {
  const Fit& f = fit();
  // B'_l: basis at R^T d_j.
  const Mat3 Rt = R.transposed();
  double rotated[kSamples][16];
  for (int j = 0; j < kSamples; ++j) {
    double d[3];
    sample_direction(j, d);
    Vec3 v = Rt * Vec3{d[0], d[1], d[2]};
    sh_basis(3, v.x, v.y, v.z, rotated[j]);
  }
  m_[0][0] = 1;
  for (int l = 1; l <= 3; ++l) {
    const int n = 2 * l + 1, off = l * l;
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c) {
        double s = 0;
        for (int j = 0; j < kSamples; ++j) s += rotated[j][off + r] * f.P[l][j][c];
        m_[l][r * 7 + c] = s;
      }
  }
}

void ShRotation::apply(int degree, float* coeffs) const {
  for (int l = 1; l <= degree && l <= 3; ++l) {
    const int n = 2 * l + 1, off = l * l;
    for (int ch = 0; ch < 3; ++ch) {
      double in[7], out[7];
      for (int k = 0; k < n; ++k) in[k] = coeffs[3 * (off + k) + ch];
      // c' = M^T c
      for (int c = 0; c < n; ++c) {
        double s = 0;
        for (int r = 0; r < n; ++r) s += m_[l][r * 7 + c] * in[r];
        out[c] = s;
      }
      for (int k = 0; k < n; ++k) coeffs[3 * (off + k) + ch] = float(out[k]);
    }
  }
}

}  // namespace isegman::edit
