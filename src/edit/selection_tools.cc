#include "edit/selection_tools.h"

#include <algorithm>
#include <cmath>
#include <queue>

#include "core/error.h"
#include "core/sh.h"
#include "edit/checks.h"

namespace isegman::edit {
namespace {

Selection same_scene(const Selection& a, const Selection& b, const char* op) {
  if (a.gaussian_count != b.gaussian_count || a.scene_fingerprint != b.scene_fingerprint)
    throw Error(op, "the two selections were made for different scenes");
  a.validate(op);
  b.validate(op);
  Selection out;
  out.gaussian_count = a.gaussian_count;
  out.scene_fingerprint = a.scene_fingerprint;
  out.mask.resize(a.gaussian_count);
  return out;
}

Selection with_mask(const GaussianScene& scene, std::vector<bool> mask) {
  return Selection::from_mask(scene, std::move(mask));
}


}  // namespace

Selection select_box(const GaussianScene& scene, const Vec3& lo, const Vec3& hi, Region region) {
  const std::string op = "box selection";
  check_finite(lo, "box corner", op);
  check_finite(hi, "box corner", op);
  for (int a = 0; a < 3; ++a)
    if (lo[a] > hi[a]) throw Error(op, "box minimum exceeds its maximum on axis " + std::string(1, "xyz"[a]));
  std::vector<bool> m(scene.size());
  for (size_t i = 0; i < scene.size(); ++i) {
    const float* p = &scene.positions[3 * i];
    bool in = p[0] >= lo.x && p[0] <= hi.x && p[1] >= lo.y && p[1] <= hi.y && p[2] >= lo.z && p[2] <= hi.z;
    m[i] = region == Region::kInside ? in : !in;
  }
  return with_mask(scene, std::move(m));
}

Selection select_sphere(const GaussianScene& scene, const Vec3& c, double r, Region region) {
  const std::string op = "sphere selection";
  check_finite(c, "sphere centre", op);
  check_finite(r, "sphere radius", op);
  if (!(r > 0)) throw Error(op, "sphere radius must be > 0");
  std::vector<bool> m(scene.size());
  const double r2 = r * r;
  for (size_t i = 0; i < scene.size(); ++i) {
    Vec3 d = scene.position(i) - c;
    bool in = dot(d, d) <= r2;
    m[i] = region == Region::kInside ? in : !in;
  }
  return with_mask(scene, std::move(m));
}

namespace {

// The Gaussians whose `value(i)` lies in [lo, hi]; `what` names the value in errors.
template <class Value>
Selection select_in_range(const GaussianScene& scene, double lo, double hi, const std::string& what, Value value) {
  const std::string op = what + " selection";
  check_finite(lo, "minimum " + what, op);
  check_finite(hi, "maximum " + what, op);
  if (lo > hi) throw Error(op, "minimum " + what + " exceeds the maximum");
  std::vector<bool> m(scene.size());
  for (size_t i = 0; i < scene.size(); ++i) {
    const double v = value(i);
    m[i] = v >= lo && v <= hi;
  }
  return with_mask(scene, std::move(m));
}

}  // namespace

Selection select_opacity(const GaussianScene& scene, double lo, double hi) {
  return select_in_range(scene, lo, hi, "opacity",
                         [&](size_t i) { return sigmoid(double(scene.opacity[i])); });
}

Selection select_size(const GaussianScene& scene, double lo, double hi) {
  return select_in_range(scene, lo, hi, "size", [&](size_t i) {
    const float* s = &scene.scales[3 * i];
    return std::exp(double(std::max({s[0], s[1], s[2]})));
  });
}

Selection invert(const Selection& a) {
  a.validate("invert");
  Selection out = a;
  out.score.clear();
  for (size_t i = 0; i < out.mask.size(); ++i) out.mask[i] = !a.mask[i];
  return out;
}

Selection unite(const Selection& a, const Selection& b) {
  Selection out = same_scene(a, b, "union of selections");
  for (size_t i = 0; i < out.mask.size(); ++i) out.mask[i] = a.mask[i] || b.mask[i];
  return out;
}

Selection subtract(const Selection& a, const Selection& b) {
  Selection out = same_scene(a, b, "difference of selections");
  for (size_t i = 0; i < out.mask.size(); ++i) out.mask[i] = a.mask[i] && !b.mask[i];
  return out;
}

Selection intersect(const Selection& a, const Selection& b) {
  Selection out = same_scene(a, b, "intersection of selections");
  for (size_t i = 0; i < out.mask.size(); ++i) out.mask[i] = a.mask[i] && b.mask[i];
  return out;
}

namespace {

// Checks the neighbour rule shared by grow and shrink (see the header).
void check_neighbour_rule(int k, double max_distance, int steps, const std::string& op) {
  check_finite(max_distance, "maximum distance", op);
  if (k < 0 || k > 1000) throw Error(op, "neighbour count must be in 0..1000, got " + std::to_string(k));
  if (k == 0 && !(max_distance > 0)) throw Error(op, "with no neighbour count, a radius > 0 is required");
  if (steps < 1 || steps > 1000) throw Error(op, "steps must be in 1..1000, got " + std::to_string(steps));
}

std::vector<uint32_t> neighbours(const CentreIndex& index, const Vec3& p, int k, double max_distance) {
  // +1: the query point is its own nearest centre.
  return k > 0 ? index.nearest(p, k + 1, max_distance) : index.within(p, max_distance);
}

}  // namespace

Selection grow(const GaussianScene& scene, const Selection& sel, int k, double max_distance, int steps) {
  const std::string op = "grow selection";
  sel.check_matches(scene, op);
  check_neighbour_rule(k, max_distance, steps, op);
  Selection out = sel;
  out.score.clear();
  if (sel.empty()) return out;
  const CentreIndex index(scene);
  std::vector<uint32_t> frontier;
  for (size_t i = 0; i < out.mask.size(); ++i)
    if (out.mask[i]) frontier.push_back(uint32_t(i));
  for (int s = 0; s < steps && !frontier.empty(); ++s) {
    std::vector<uint32_t> next;
    for (uint32_t i : frontier)
      for (uint32_t j : neighbours(index, scene.position(i), k, max_distance))
        if (!out.mask[j]) {
          out.mask[j] = true;
          next.push_back(j);
        }
    frontier = std::move(next);
  }
  return out;
}

Selection shrink(const GaussianScene& scene, const Selection& sel, int k, double max_distance, int steps) {
  const std::string op = "shrink selection";
  sel.check_matches(scene, op);
  check_neighbour_rule(k, max_distance, steps, op);
  Selection out = sel;
  out.score.clear();
  if (sel.empty()) return out;
  const CentreIndex index(scene);
  for (int s = 0; s < steps; ++s) {
    // Decide every drop on the mask before this step, so the result does not depend on
    // the visiting order.
    const std::vector<bool> before = out.mask;
    bool changed = false;
    for (size_t i = 0; i < before.size(); ++i) {
      if (!before[i]) continue;
      for (uint32_t j : neighbours(index, scene.position(i), k, max_distance))
        if (!before[j]) {
          out.mask[i] = false;
          changed = true;
          break;
        }
    }
    if (!changed) break;
  }
  return out;
}

Vec3 base_color(const GaussianScene& scene, size_t i) {
  const float* c = scene.sh_of(i);
  Vec3 rgb;
  for (int k = 0; k < 3; ++k) rgb[k] = std::clamp(double(sh_dc_to_rgb(c[k])), 0.0, 1.0);
  return rgb;
}

Selection select_similar_color(const GaussianScene& scene, const Vec3& color, double tolerance) {
  const std::string op = "colour selection";
  check_finite(color, "colour", op);
  check_finite(tolerance, "tolerance", op);
  if (!(tolerance >= 0)) throw Error(op, "tolerance must be >= 0");
  std::vector<bool> m(scene.size());
  const double t2 = tolerance * tolerance;
  for (size_t i = 0; i < scene.size(); ++i) {
    const Vec3 d = base_color(scene, i) - color;
    m[i] = dot(d, d) <= t2;
  }
  return with_mask(scene, std::move(m));
}

}  // namespace isegman::edit
