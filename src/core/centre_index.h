#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "core/math.h"
#include "core/scene.h"

namespace isegman {

// Nearest Gaussian centres (a kd-tree): the k nearest of a point within a distance,
// nearest first (ties by index), or every centre within a radius. Grow/shrink of a
// selection and the neighbour coherence of segmentation are built on it.
class CentreIndex {
 public:
  // Reads the scene's positions in place (no copy: 72 MB at 6M Gaussians): the scene must
  // outlive the index, its positions unchanged.
  // Built on `threads` threads (0: every core); the tree does not depend on the count.
  explicit CentreIndex(const GaussianScene& scene, int threads = 0);
  std::vector<uint32_t> nearest(const Vec3& p, int k, double max_distance) const;
  // Every centre within `radius` of p (boundary included), in index order.
  std::vector<uint32_t> within(const Vec3& p, double radius) const;
  // Every centre within `radius` of the segment a-b (boundary included), in index order:
  // what may stand in a line of sight.
  std::vector<uint32_t> near_segment(const Vec3& a, const Vec3& b, double radius) const;

 private:
  struct Node {
    float lo[3], hi[3];
    uint32_t begin, end;   // range in order_
    int32_t left = -1, right = -1;
  };
  // Builds the subtree of order_[begin, end) into nodes_[id...] in pre-order (nodes_ is
  // sized up front; `counts`: the node count of a subtree per range size). With spare
  // threads a large range builds its two halves at once: the same tree and ids with any
  // thread count.
  void build(uint32_t begin, uint32_t end, uint32_t id, const std::map<uint32_t, uint32_t>& counts, int spare_threads);
  // The centres (sorted) of the leaves whose boxes pass `node_may_hold(lo, hi)` that pass
  // `holds(p)`: the walk within() and near_segment() share.
  template <typename NodeTest, typename PointTest>
  std::vector<uint32_t> collect(NodeTest node_may_hold, PointTest holds) const;
  const float* pos_ = nullptr;  // the scene's positions
  std::vector<uint32_t> order_;
  std::vector<Node> nodes_;
};

}  // namespace isegman
