// Rotation of real spherical-harmonic colour coefficients (degrees 1-3, in the
// trainers' basis of core/sh.h). Rotating an object by R changes its colour function to
// f'(d) = f(R^T d); each band l transforms on its own by a (2l+1)x(2l+1) orthogonal
// matrix. The matrices are found by exact least squares on a fixed set of directions:
// b_l(R^T d) = M_l b_l(d) holds for every d because each band spans a rotation-invariant
// space, so M_l = B'_l B_l^T (B_l B_l^T)^-1 with B_l the basis at the sample directions.
#pragma once

#include "core/math.h"

namespace isegman::edit {

class ShRotation {
 public:
  // Matrices for rotating by R (a proper rotation: orthonormal, det +1).
  explicit ShRotation(const Mat3& R);

  // Rotates coefficients laid out [coefficient][channel] (3 channels) of `degree` in
  // place. The DC term is unchanged.
  void apply(int degree, float* coeffs) const;

  // Entry (r, c) of band l's matrix M_l, with b_l(R^T d) = M_l b_l(d).
  double band(int l, int r, int c) const { return m_[l][r * 7 + c]; }

 private:
  double m_[4][49] = {};
};

}  // namespace isegman::edit
