// Selection tools beside the 2D clicks: geometric shapes, attribute thresholds, set
// algebra and growing by nearest neighbours. Every tool returns a Selection tied to
// the scene (fingerprint and Gaussian count), and the set operations refuse to mix
// selections of different scenes.
#pragma once

#include "core/math.h"
#include "core/scene.h"
#include "core/selection.h"

namespace isegman::edit {

enum class Region { kInside, kOutside };

// Centres inside the axis-aligned box [lo, hi] (bounds included) or outside it.
Selection select_box(const GaussianScene& scene, const Vec3& lo, const Vec3& hi, Region region = Region::kInside);
// Centres within distance r of c (boundary included) or beyond it.
Selection select_sphere(const GaussianScene& scene, const Vec3& center, double radius,
                        Region region = Region::kInside);
// Activated opacity sigmoid(logit) in [min, max].
Selection select_opacity(const GaussianScene& scene, double min_opacity, double max_opacity);
// Largest axis scale exp(max log-scale) in [min, max] (world units).
Selection select_size(const GaussianScene& scene, double min_size, double max_size);

Selection invert(const Selection& a);
Selection unite(const Selection& a, const Selection& b);
Selection subtract(const Selection& a, const Selection& b);
Selection intersect(const Selection& a, const Selection& b);

// Adds, `steps` times over, the k nearest neighbours (by centre) of every selected
// Gaussian that lie within `max_distance` of it (max_distance <= 0: no limit).
Selection grow(const GaussianScene& scene, const Selection& selection, int k, double max_distance = 0, int steps = 1);

// k nearest centres of every query point (the tool grow() is built on), exposed for
// tests: result[q] lists up to k indices, nearest first (ties by index).
class CentreIndex {
 public:
  explicit CentreIndex(const GaussianScene& scene);
  std::vector<uint32_t> nearest(const Vec3& p, int k, double max_distance) const;

 private:
  struct Node {
    float lo[3], hi[3];
    uint32_t begin, end;   // range in order_
    int32_t left = -1, right = -1;
  };
  int build(uint32_t begin, uint32_t end);
  std::vector<float> pos_;
  std::vector<uint32_t> order_;
  std::vector<Node> nodes_;
};

}  // namespace isegman::edit
