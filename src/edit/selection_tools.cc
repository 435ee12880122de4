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

constexpr uint32_t kLeafSize = 16;

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

Selection select_opacity(const GaussianScene& scene, double lo, double hi) {
  const std::string op = "opacity selection";
  check_finite(lo, "minimum opacity", op);
  check_finite(hi, "maximum opacity", op);
  if (lo > hi) throw Error(op, "minimum opacity exceeds the maximum");
  std::vector<bool> m(scene.size());
  for (size_t i = 0; i < scene.size(); ++i) {
    const double a = 1.0 / (1.0 + std::exp(-double(scene.opacity[i])));
    m[i] = a >= lo && a <= hi;
  }
  return with_mask(scene, std::move(m));
}

Selection select_size(const GaussianScene& scene, double lo, double hi) {
  const std::string op = "size selection";
  check_finite(lo, "minimum size", op);
  check_finite(hi, "maximum size", op);
  if (lo > hi) throw Error(op, "minimum size exceeds the maximum");
  std::vector<bool> m(scene.size());
  for (size_t i = 0; i < scene.size(); ++i) {
    const float* s = &scene.scales[3 * i];
    const double size = std::exp(double(std::max({s[0], s[1], s[2]})));
    m[i] = size >= lo && size <= hi;
  }
  return with_mask(scene, std::move(m));
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

CentreIndex::CentreIndex(const GaussianScene& scene) : pos_(scene.positions) {
  if (scene.size() >= (size_t(1) << 32)) throw Error("neighbour index", "too many Gaussians");
  order_.resize(scene.size());
  for (uint32_t i = 0; i < order_.size(); ++i) order_[i] = i;
  if (!order_.empty()) build(0, uint32_t(order_.size()));
}

int CentreIndex::build(uint32_t begin, uint32_t end) {
  Node node;
  node.begin = begin;
  node.end = end;
  for (int a = 0; a < 3; ++a) {
    node.lo[a] = INFINITY;
    node.hi[a] = -INFINITY;
  }
  for (uint32_t i = begin; i < end; ++i)
    for (int a = 0; a < 3; ++a) {
      node.lo[a] = std::min(node.lo[a], pos_[3 * order_[i] + a]);
      node.hi[a] = std::max(node.hi[a], pos_[3 * order_[i] + a]);
    }
  const int id = int(nodes_.size());
  nodes_.push_back(node);
  if (end - begin > kLeafSize) {
    int axis = 0;
    for (int a = 1; a < 3; ++a)
      if (node.hi[a] - node.lo[a] > node.hi[axis] - node.lo[axis]) axis = a;
    const uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end, [&](uint32_t x, uint32_t y) {
      float px = pos_[3 * x + axis], py = pos_[3 * y + axis];
      return px < py || (px == py && x < y);
    });
    const int l = build(begin, mid);
    const int r = build(mid, end);
    nodes_[id].left = l;
    nodes_[id].right = r;
  }
  return id;
}

std::vector<uint32_t> CentreIndex::nearest(const Vec3& p, int k, double max_distance) const {
  std::vector<uint32_t> out;
  if (k <= 0 || nodes_.empty()) return out;
  const double limit2 = max_distance > 0 ? max_distance * max_distance : INFINITY;
  // Max-heap of the best k (distance^2, index): the top is the worst kept.
  using Item = std::pair<double, uint32_t>;
  std::priority_queue<Item> best;
  auto box_d2 = [&](const Node& n) {
    double d2 = 0;
    for (int a = 0; a < 3; ++a) {
      double v = p[a] < n.lo[a] ? n.lo[a] - p[a] : (p[a] > n.hi[a] ? p[a] - n.hi[a] : 0);
      d2 += v * v;
    }
    return d2;
  };
  auto bound = [&]() { return best.size() < size_t(k) ? limit2 : best.top().first; };
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const Node& n = nodes_[size_t(stack.back())];
    stack.pop_back();
    if (box_d2(n) > bound()) continue;
    if (n.left < 0) {
      for (uint32_t j = n.begin; j < n.end; ++j) {
        const uint32_t i = order_[j];
        double dx = pos_[3 * i] - p.x, dy = pos_[3 * i + 1] - p.y, dz = pos_[3 * i + 2] - p.z;
        const Item it{dx * dx + dy * dy + dz * dz, i};
        if (it.first > limit2) continue;
        if (best.size() < size_t(k)) best.push(it);
        else if (it < best.top()) {
          best.pop();
          best.push(it);
        }
      }
    } else {
      // Visit the nearer child first (pushed last).
      const Node& l = nodes_[size_t(n.left)];
      const Node& r = nodes_[size_t(n.right)];
      if (box_d2(l) <= box_d2(r)) {
        stack.push_back(n.right);
        stack.push_back(n.left);
      } else {
        stack.push_back(n.left);
        stack.push_back(n.right);
      }
    }
  }
  out.resize(best.size());
  for (size_t j = out.size(); j-- > 0;) {
    out[j] = best.top().second;
    best.pop();
  }
  return out;
}

std::vector<uint32_t> CentreIndex::within(const Vec3& p, double radius) const {
  std::vector<uint32_t> out;
  if (nodes_.empty() || !(radius >= 0)) return out;
  const double r2 = radius * radius;
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const Node& n = nodes_[size_t(stack.back())];
    stack.pop_back();
    double d2 = 0;
    for (int a = 0; a < 3; ++a) {
      const double v = p[a] < n.lo[a] ? n.lo[a] - p[a] : (p[a] > n.hi[a] ? p[a] - n.hi[a] : 0);
      d2 += v * v;
    }
    if (d2 > r2) continue;
    if (n.left < 0) {
      for (uint32_t j = n.begin; j < n.end; ++j) {
        const uint32_t i = order_[j];
        const double dx = pos_[3 * i] - p.x, dy = pos_[3 * i + 1] - p.y, dz = pos_[3 * i + 2] - p.z;
        if (dx * dx + dy * dy + dz * dz <= r2) out.push_back(i);
      }
    } else {
      stack.push_back(n.left);
      stack.push_back(n.right);
    }
  }
  std::sort(out.begin(), out.end());
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
