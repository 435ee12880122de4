#include "core/virtual_views.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "core/error.h"

namespace isegman {
namespace {

// Weighted percentile of values[i] (weights w[i] >= 0) by sorting an index.
double weighted_percentile(const std::vector<float>& v, size_t stride, size_t axis, const std::vector<double>& w,
                           double total, std::vector<uint32_t>& idx, double pct) {
  const size_t n = w.size();
  idx.resize(n);
  std::iota(idx.begin(), idx.end(), 0u);
  std::sort(idx.begin(), idx.end(), [&](uint32_t a, uint32_t b) { return v[stride * a + axis] < v[stride * b + axis]; });
  const double target = total * pct / 100.0;
  double acc = 0;
  for (uint32_t i : idx) {
    acc += w[i];
    if (acc >= target) return v[stride * i + axis];
  }
  return v[stride * idx.back() + axis];
}

Vec3 any_perpendicular(const Vec3& a) {
  const Vec3 t = std::fabs(a.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  return normalized(cross(a, t));
}

}  // namespace

RobustBounds robust_bounds(const GaussianScene& scene, double lower, double upper) {
  const size_t n = scene.size();
  if (n == 0) throw Error("robust bounds", "the scene has no Gaussians");
  if (!(lower >= 0 && lower < upper && upper <= 100)) throw Error("robust bounds", "percentiles must satisfy 0 <= lo < hi <= 100");
  std::vector<double> w(n);
  double total = 0;
  for (size_t i = 0; i < n; ++i) {
    const double o = double(scene.activated_opacity(i));
    w[i] = std::isfinite(o) ? o : 0.0;
    total += w[i];
  }
  if (!(total > 0)) {  // all transparent: fall back to plain counts
    std::fill(w.begin(), w.end(), 1.0);
    total = double(n);
  }
  std::vector<uint32_t> idx;
  double lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = weighted_percentile(scene.positions, 3, a, w, total, idx, lower);
    hi[a] = weighted_percentile(scene.positions, 3, a, w, total, idx, upper);
  }
  RobustBounds b;
  b.lo = {lo[0], lo[1], lo[2]};
  b.hi = {hi[0], hi[1], hi[2]};
  b.center = (b.lo + b.hi) * 0.5;
  b.radius = std::max(0.5 * norm(b.hi - b.lo), 1e-6);
  return b;
}

VirtualLayout parse_virtual_layout(const std::string& t) {
  if (t == "auto") return VirtualLayout::kAuto;
  if (t == "orbit") return VirtualLayout::kOrbit;
  if (t == "sphere") return VirtualLayout::kSphere;
  if (t == "forward") return VirtualLayout::kForward;
  throw Error("--virtual-layout", "expected auto, orbit, sphere or forward, got '" + t + "'");
}

std::vector<Camera> make_virtual_views(const GaussianScene& scene, const std::vector<Camera>& existing,
                                       const VirtualViewOptions& o) {
  if (o.count <= 0 || o.count > 10000) throw Error("virtual views", "count must be 1..10000");
  if (o.width <= 0 || o.height <= 0 || o.width > 16384 || o.height > 16384)
    throw Error("virtual views", "image size must be 1..16384 pixels per side");
  const RobustBounds rb = robust_bounds(scene);
  Vec3 up = normalized(o.up), fwd = normalized(o.forward);
  double fwd_agreement = 0;
  if (!existing.empty()) {
    Vec3 su{0, 0, 0}, sf{0, 0, 0};
    for (const Camera& c : existing) {
      // Rows of R are the camera axes in world coordinates: y down, z forward.
      su = su - Vec3{c.R.m[1][0], c.R.m[1][1], c.R.m[1][2]};
      sf = sf + Vec3{c.R.m[2][0], c.R.m[2][1], c.R.m[2][2]};
    }
    if (norm(su) > 1e-9) up = normalized(su);
    fwd_agreement = norm(sf) / double(existing.size());
    if (norm(sf) > 1e-9) fwd = normalized(sf);
  }
  VirtualLayout layout = o.layout;
  if (layout == VirtualLayout::kAuto)
    layout = (!existing.empty() && fwd_agreement > 0.8) ? VirtualLayout::kForward : VirtualLayout::kOrbit;
  // Distance at which a sphere of the robust radius fills ~80% of the narrower field of view.
  const double half_fov_x = 0.5 * o.fov_x_deg * M_PI / 180.0;
  const double half_fov_y = std::atan(std::tan(half_fov_x) * double(o.height) / double(o.width));
  const double half_fov = std::min(half_fov_x, half_fov_y);
  const double dist = rb.radius / std::sin(half_fov) / 0.8;
  int next_id = 0;
  for (const Camera& c : existing) next_id = std::max(next_id, c.id + 1);

  std::vector<Camera> out;
  auto add = [&](const Vec3& eye, const Vec3& target, Vec3 cam_up) {
    const Vec3 dir = normalized(target - eye);
    if (std::fabs(dot(dir, normalized(cam_up))) > 0.99) cam_up = any_perpendicular(dir);
    Camera c = Camera::look_at(eye, target, cam_up, o.width, o.height, o.fov_x_deg);
    c.id = next_id++;
    char name[32];
    std::snprintf(name, sizeof(name), "virtual_%03zu", out.size());
    c.name = name;
    out.push_back(c);
  };
  const Vec3 e1 = any_perpendicular(up), e2 = cross(up, e1);
  if (layout == VirtualLayout::kOrbit) {
    const double elev = 20.0 * M_PI / 180.0;
    for (int k = 0; k < o.count; ++k) {
      const double az = 2.0 * M_PI * k / o.count;
      const Vec3 d = (e1 * std::cos(az) + e2 * std::sin(az)) * std::cos(elev) + up * std::sin(elev);
      add(rb.center + d * dist, rb.center, up);
    }
  } else if (layout == VirtualLayout::kSphere) {
    const double golden = M_PI * (3.0 - std::sqrt(5.0));
    for (int k = 0; k < o.count; ++k) {
      const double h = o.count == 1 ? 0.0 : 1.0 - 2.0 * (k + 0.5) / o.count;  // height along up
      const double r = std::sqrt(std::max(0.0, 1.0 - h * h));
      const Vec3 d = (e1 * std::cos(golden * k) + e2 * std::sin(golden * k)) * r + up * h;
      add(rb.center + d * dist, rb.center, up);
    }
  } else {
    // Forward-facing: a near-square grid on the plane facing `fwd`, all looking along fwd.
    Vec3 right = cross(fwd, up);
    if (norm(right) < 1e-6) right = any_perpendicular(fwd);
    right = normalized(right);
    const Vec3 gup = normalized(cross(right, fwd));
    const int cols = int(std::ceil(std::sqrt(double(o.count))));
    const int rows = (o.count + cols - 1) / cols;
    const double spacing = 0.1 * 2.0 * rb.radius / std::sqrt(3.0);
    const Vec3 base = rb.center - fwd * dist;
    for (int k = 0; k < o.count; ++k) {
      const int i = k % cols, j = k / cols;
      const Vec3 off = right * ((i - 0.5 * (cols - 1)) * spacing) + gup * ((0.5 * (rows - 1) - j) * spacing);
      add(base + off, base + off + fwd, gup);
    }
  }
  return out;
}

}  // namespace isegman
