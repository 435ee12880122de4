// Small fixed-size linear algebra for cameras and Gaussians (no heavy deps).
#pragma once

#include <cmath>

#include "core/quat_rotation.h"

namespace isegman {

// A point in an image, continuous pixel coordinates (core/click.h).
struct Point2 {
  double x = 0, y = 0;
};

struct Vec3 {
  double x = 0, y = 0, z = 0;
  Vec3() = default;
  Vec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
  double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  Vec3 operator+(const Vec3& o) const { return {x + o.x, y + o.y, z + o.z}; }
  Vec3 operator-(const Vec3& o) const { return {x - o.x, y - o.y, z - o.z}; }
  Vec3 operator-() const { return {-x, -y, -z}; }
  Vec3 operator*(double s) const { return {x * s, y * s, z * s}; }
  Vec3 operator/(double s) const { return {x / s, y / s, z / s}; }
  Vec3& operator+=(const Vec3& o) { x += o.x; y += o.y; z += o.z; return *this; }
};

// The logistic function: a Gaussian's stored logit opacity to its opacity in (0, 1). One
// template for the renderer's float, its backward pass's Real and the double that range
// selections and quantisers compare exactly.
template <typename Real>
inline Real sigmoid(Real x) {
  return Real(1) / (Real(1) + std::exp(-x));
}

inline Vec3 operator*(double s, const Vec3& v) { return v * s; }
inline double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(const Vec3& v) { return std::sqrt(dot(v, v)); }
inline Vec3 normalized(const Vec3& v) { double n = norm(v); return n > 0 ? v / n : v; }

// Row-major 3x3 matrix: m[r][c].
struct Mat3 {
  double m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  static Mat3 identity() { return Mat3{}; }
  static Mat3 from_rows(const Vec3& r0, const Vec3& r1, const Vec3& r2) {
    Mat3 a;
    for (int c = 0; c < 3; ++c) { a.m[0][c] = r0[c]; a.m[1][c] = r1[c]; a.m[2][c] = r2[c]; }
    return a;
  }
  static Mat3 from_cols(const Vec3& c0, const Vec3& c1, const Vec3& c2) {
    return from_rows(c0, c1, c2).transposed();
  }
  Vec3 row(int r) const { return {m[r][0], m[r][1], m[r][2]}; }
  Vec3 col(int c) const { return {m[0][c], m[1][c], m[2][c]}; }
  Mat3 transposed() const {
    Mat3 t;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) t.m[r][c] = m[c][r];
    return t;
  }
  Vec3 operator*(const Vec3& v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
  Mat3 operator*(const Mat3& o) const {
    Mat3 p;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        p.m[r][c] = m[r][0] * o.m[0][c] + m[r][1] * o.m[1][c] + m[r][2] * o.m[2][c];
    return p;
  }
  double det() const {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  }
};

// Unit quaternion (w, x, y, z) as stored by 3DGS trainers (w first).
struct Quat {
  double w = 1, x = 0, y = 0, z = 0;
  Quat() = default;
  Quat(double w_, double x_, double y_, double z_) : w(w_), x(x_), y(y_), z(z_) {}
  Quat operator*(const Quat& o) const {
    return {w * o.w - x * o.x - y * o.y - z * o.z, w * o.x + x * o.w + y * o.z - z * o.y,
            w * o.y - x * o.z + y * o.w + z * o.x, w * o.z + x * o.y - y * o.x + z * o.w};
  }
  double norm() const { return std::sqrt(w * w + x * x + y * y + z * z); }
  Quat normalized() const {
    double n = norm();
    return n > 0 ? Quat{w / n, x / n, y / n, z / n} : Quat{};
  }
  // Rotation matrix of the normalised quaternion (core/quat_rotation.h).
  Mat3 to_matrix() const {
    const Quat q = normalized();
    double R[9];
    unit_quat_to_rotmat(q.w, q.x, q.y, q.z, R);
    Mat3 r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) r.m[i][j] = R[3 * i + j];
    return r;
  }
  static Quat from_matrix(const Mat3& r);
  static Quat from_axis_angle(const Vec3& axis, double angle_rad);
};

inline Quat Quat::from_matrix(const Mat3& r) {
  // Shepperd's method: pick the largest diagonal term for numerical stability.
  const double tr = r.m[0][0] + r.m[1][1] + r.m[2][2];
  Quat q;
  if (tr > 0) {
    double s = std::sqrt(tr + 1.0) * 2;
    q = {0.25 * s, (r.m[2][1] - r.m[1][2]) / s, (r.m[0][2] - r.m[2][0]) / s, (r.m[1][0] - r.m[0][1]) / s};
  } else if (r.m[0][0] > r.m[1][1] && r.m[0][0] > r.m[2][2]) {
    double s = std::sqrt(1.0 + r.m[0][0] - r.m[1][1] - r.m[2][2]) * 2;
    q = {(r.m[2][1] - r.m[1][2]) / s, 0.25 * s, (r.m[0][1] + r.m[1][0]) / s, (r.m[0][2] + r.m[2][0]) / s};
  } else if (r.m[1][1] > r.m[2][2]) {
    double s = std::sqrt(1.0 + r.m[1][1] - r.m[0][0] - r.m[2][2]) * 2;
    q = {(r.m[0][2] - r.m[2][0]) / s, (r.m[0][1] + r.m[1][0]) / s, 0.25 * s, (r.m[1][2] + r.m[2][1]) / s};
  } else {
    double s = std::sqrt(1.0 + r.m[2][2] - r.m[0][0] - r.m[1][1]) * 2;
    q = {(r.m[1][0] - r.m[0][1]) / s, (r.m[0][2] + r.m[2][0]) / s, (r.m[1][2] + r.m[2][1]) / s, 0.25 * s};
  }
  return q.normalized();
}

inline Quat Quat::from_axis_angle(const Vec3& axis, double angle_rad) {
  Vec3 a = isegman::normalized(axis);
  double s = std::sin(angle_rad / 2);
  return {std::cos(angle_rad / 2), a.x * s, a.y * s, a.z * s};
}

}  // namespace isegman
