#include "app/scene_builder.h"

#include <algorithm>
#include <cmath>

#include "core/sh.h"

namespace isegman {

Quat align_z_to(const Vec3& n) {
  Vec3 z{0, 0, 1};
  double c = dot(z, n);
  if (c < -0.999999) return {0, 1, 0, 0};
  Vec3 axis = cross(z, n);
  Quat q{1 + c, axis.x, axis.y, axis.z};
  return q.normalized();
}

namespace {
void push(GaussianScene& g, std::vector<int>& labels, SplitMix64& rng, int degree, const Vec3& p, const Vec3& n,
          const Quat& q, double sx, double sy, double sz, const Vec3& rgb, int label, double shine) {
  g.positions.insert(g.positions.end(), {float(p.x), float(p.y), float(p.z)});
  g.normals.insert(g.normals.end(), {float(n.x), float(n.y), float(n.z)});
  g.scales.insert(g.scales.end(), {float(std::log(sx)), float(std::log(sy)), float(std::log(sz))});
  // Stored unnormalised on purpose (as trainers do) to exercise normalisation.
  double scale = rng.range(0.5, 2.0);
  g.rotations.insert(g.rotations.end(), {float(q.w * scale), float(q.x * scale), float(q.y * scale), float(q.z * scale)});
  g.opacity.push_back(float(std::log(0.97 / 0.03) + rng.range(-0.5, 0.5)));
  const int K = sh_coeff_count(degree);
  for (int k = 0; k < K; ++k)
    for (int c = 0; c < 3; ++c) {
      float v;
      if (k == 0) v = rgb_to_sh_dc(float(std::clamp(rgb[c] + rng.normal() * 0.03, 0.0, 1.0)));
      else v = float(rng.normal() * shine / k);  // a little view dependence
      g.sh.push_back(v);
    }
  labels.push_back(label);
}
// The imperfections of SceneBuilder::depth_jitter and shape_jitter: moves p along n,
// scales the tangent axes and the thickness, tilts q. Draws nothing when both are 0.
void jitter(SplitMix64& rng, double depth_jitter, double shape_jitter, const Vec3& n, Vec3& p, Quat& q, double& sx,
            double& sy, double& sz) {
  if (depth_jitter > 0) p = p + normalized(n) * (std::clamp(rng.normal(), -2.5, 2.5) * depth_jitter);
  if (shape_jitter > 0) {
    const double size = std::exp(rng.normal() * shape_jitter), ratio = std::exp(rng.normal() * shape_jitter);
    sx *= size * ratio;
    sy *= size / ratio;
    sz *= size * std::exp(std::abs(rng.normal()) * 2 * shape_jitter);  // some thicker than a flat splat
    const double tilt = rng.normal() * 0.6 * shape_jitter, axis = rng.range(0, 2 * M_PI);
    q = q * Quat::from_axis_angle({std::cos(axis), std::sin(axis), 0}, tilt);  // about a local tangent axis
  }
}
}  // namespace

void SceneBuilder::splat(const Vec3& p, const Vec3& n, double size, const Vec3& rgb, int label, double shine) {
  size *= size_scale;
  double sx = size * rng.range(0.8, 1.25), sy = size * rng.range(0.8, 1.25);
  Quat q = align_z_to(n) * Quat::from_axis_angle({0, 0, 1}, rng.range(0, M_PI));
  Vec3 at = p;
  double sz = size * 0.15;
  jitter(rng, depth_jitter, shape_jitter, n, at, q, sx, sy, sz);
  push(g, labels, rng, degree, at, n, q, sx, sy, sz, rgb, label, shine);
}

void SceneBuilder::strip(const Vec3& p, const Vec3& n, const Vec3& along, double length, double width,
                         const Vec3& rgb, int label, double shine) {
  // Local x along `along` projected into the tangent plane, local z along n.
  const Vec3 z = normalized(n);
  Vec3 x = along - z * dot(along, z);
  if (norm(x) < 1e-9) x = std::fabs(z.x) < 0.9 ? cross(z, Vec3{1, 0, 0}) : cross(z, Vec3{0, 1, 0});
  x = normalized(x);
  const Vec3 y = cross(z, x);
  Quat q = Quat::from_matrix(Mat3::from_cols(x, y, z));
  Vec3 at = p;
  double sx = length * size_scale, sy = width * size_scale, sz = 0.15 * width * size_scale;
  jitter(rng, depth_jitter, shape_jitter, n, at, q, sx, sy, sz);
  push(g, labels, rng, degree, at, n, q, sx, sy, sz, rgb, label, shine);
}

void SceneBuilder::floater(const Vec3& p, double size, const Vec3& rgb, double opacity) {
  const Vec3 n = normalized(Vec3{rng.normal(), rng.normal(), rng.normal() + 1e-9});
  const Quat q = align_z_to(n);
  size *= size_scale;
  push(g, labels, rng, degree, p, n, q, size * rng.range(0.6, 1.6), size * rng.range(0.6, 1.6), size * rng.range(0.3, 1.0),
       rgb, -1, 0.0);
  const double a = std::clamp(opacity, 0.01, 0.99);
  g.opacity.back() = float(std::log(a / (1 - a)));
}

}  // namespace isegman
