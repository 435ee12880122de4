#include "core/centre_index.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <map>
#include <queue>
#include <thread>

#include "core/error.h"
#include "core/parallel.h"

namespace isegman {

namespace {
constexpr uint32_t kLeafSize = 16;
constexpr uint32_t kParallelBuild = 1u << 16;  // smaller ranges build on one thread
}  // namespace

CentreIndex::CentreIndex(const GaussianScene& scene, int threads) : pos_(scene.positions.data()) {
  if (scene.size() >= (size_t(1) << 32)) throw Error("neighbour index", "too many Gaussians");
  order_.resize(scene.size());
  for (uint32_t i = 0; i < order_.size(); ++i) order_[i] = i;
  if (order_.empty()) return;
  // Ranges halve at every level, so a level holds at most two sizes: the node count of a
  // subtree per size is a short table, filled here and only read while building.
  std::map<uint32_t, uint32_t> counts;
  auto count = [&](auto& self, uint32_t n) -> uint32_t {
    if (n <= kLeafSize) return 1;
    auto it = counts.find(n);
    if (it != counts.end()) return it->second;
    const uint32_t c = 1 + self(self, n / 2) + self(self, n - n / 2);
    counts[n] = c;
    return c;
  };
  nodes_.resize(count(count, uint32_t(order_.size())));
  build(0, uint32_t(order_.size()), 0, counts, resolve_threads(threads) - 1);
}

void CentreIndex::build(uint32_t begin, uint32_t end, uint32_t id, const std::map<uint32_t, uint32_t>& counts,
                        int spare_threads) {
  Node& node = nodes_[id];
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
  if (end - begin <= kLeafSize) return;
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (node.hi[a] - node.lo[a] > node.hi[axis] - node.lo[axis]) axis = a;
  const uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end, [&](uint32_t x, uint32_t y) {
    float px = pos_[3 * x + axis], py = pos_[3 * y + axis];
    return px < py || (px == py && x < y);
  });
  // Pre-order: the left subtree right after this node, the right one after the left.
  const uint32_t left_nodes = mid - begin <= kLeafSize ? 1 : counts.at(mid - begin);
  node.left = int32_t(id + 1);
  node.right = int32_t(id + 1 + left_nodes);
  if (spare_threads <= 0 || end - begin < kParallelBuild) {
    build(begin, mid, id + 1, counts, 0);
    build(mid, end, id + 1 + left_nodes, counts, 0);
    return;
  }
  // The halves touch disjoint ranges of order_ and of nodes_: one is built on a thread of its own.
  const int for_left = (spare_threads - 1) / 2, for_right = spare_threads - 1 - for_left;
  std::exception_ptr failed;
  std::thread helper([&] {
    try {
      build(begin, mid, id + 1, counts, for_left);
    } catch (...) {
      failed = std::current_exception();
    }
  });
  try {
    build(mid, end, id + 1 + left_nodes, counts, for_right);
  } catch (...) {
    helper.join();
    throw;
  }
  helper.join();
  if (failed) std::rethrow_exception(failed);
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

template <typename NodeTest, typename PointTest>
std::vector<uint32_t> CentreIndex::collect(NodeTest node_may_hold, PointTest holds) const {
  std::vector<uint32_t> out;
  if (nodes_.empty()) return out;
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const Node& n = nodes_[size_t(stack.back())];
    stack.pop_back();
    if (!node_may_hold(n.lo, n.hi)) continue;
    if (n.left < 0) {
      for (uint32_t j = n.begin; j < n.end; ++j) {
        const uint32_t i = order_[j];
        if (holds(Vec3{pos_[3 * i], pos_[3 * i + 1], pos_[3 * i + 2]})) out.push_back(i);
      }
    } else {
      stack.push_back(n.left);
      stack.push_back(n.right);
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<uint32_t> CentreIndex::within(const Vec3& p, double radius) const {
  if (!(radius >= 0)) return {};
  const double r2 = radius * radius;
  return collect(
      [&](const float* lo, const float* hi) {
        double d2 = 0;
        for (int a = 0; a < 3; ++a) {
          const double v = p[a] < lo[a] ? lo[a] - p[a] : (p[a] > hi[a] ? p[a] - hi[a] : 0);
          d2 += v * v;
        }
        return d2 <= r2;
      },
      [&](const Vec3& c) {
        const double dx = c.x - p.x, dy = c.y - p.y, dz = c.z - p.z;
        return dx * dx + dy * dy + dz * dz <= r2;
      });
}

namespace {

// Whether segment a + t (b - a), t in [0, 1], meets the box [lo - r, hi + r] (slab test).
bool segment_meets_box(const Vec3& a, const Vec3& b, const float* lo, const float* hi, double r) {
  double t0 = 0, t1 = 1;
  for (int k = 0; k < 3; ++k) {
    const double d = b[k] - a[k], l = lo[k] - r, h = hi[k] + r;
    if (std::fabs(d) < 1e-300) {
      if (a[k] < l || a[k] > h) return false;
      continue;
    }
    double ta = (l - a[k]) / d, tb = (h - a[k]) / d;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace

std::vector<uint32_t> CentreIndex::near_segment(const Vec3& a, const Vec3& b, double radius) const {
  if (!(radius >= 0)) return {};
  const Vec3 d = b - a;
  const double len2 = dot(d, d), r2 = radius * radius;
  return collect([&](const float* lo, const float* hi) { return segment_meets_box(a, b, lo, hi, radius); },
                 [&](const Vec3& p) {
                   const double t = len2 > 0 ? std::clamp(dot(p - a, d) / len2, 0.0, 1.0) : 0.0;
                   const Vec3 q = p - (a + d * t);
                   return dot(q, q) <= r2;
                 });
}

}  // namespace isegman
