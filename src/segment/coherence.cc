#include "segment/coherence.h"

#include <algorithm>
#include <cmath>

#include "core/virtual_views.h"
#include "segment/votes.h"

namespace isegman::segment {

NeighbourIndex::NeighbourIndex(const GaussianScene& scene) : scene_(scene) {
  const size_t n = scene.size();
  if (n == 0) return;
  // About four Gaussians a cell where the scene is (its robust box, outliers ignored).
  const RobustBounds b = robust_bounds(scene);
  const Vec3 d = b.hi - b.lo;
  // A flat or linear scene has no volume: its thin sides count as 1 % of the longest.
  const double longest = std::max({d.x, d.y, d.z, 1e-9}), thin = 0.01 * longest;
  const double volume = std::max(d.x, thin) * std::max(d.y, thin) * std::max(d.z, thin);
  cell_ = std::cbrt(volume * 4.0 / double(n));
  if (!(cell_ > 0) || !std::isfinite(cell_)) cell_ = 1;
  for (uint32_t i = 0; i < uint32_t(n); ++i) {
    int x, y, z;
    cell_of(i, x, y, z);
    cells_[key(x, y, z)].push_back(i);
  }
}

int64_t NeighbourIndex::key(int x, int y, int z) const {
  return (int64_t(x & 0x1FFFFF) << 42) | (int64_t(y & 0x1FFFFF) << 21) | int64_t(z & 0x1FFFFF);
}

void NeighbourIndex::cell_of(uint32_t i, int& x, int& y, int& z) const {
  auto c = [&](float v) { return int(std::clamp(std::floor(double(v) / cell_), -1e6, 1e6)); };
  x = c(scene_.positions[3 * i]);
  y = c(scene_.positions[3 * i + 1]);
  z = c(scene_.positions[3 * i + 2]);
}

std::vector<uint32_t> NeighbourIndex::nearest(uint32_t i, int k) const {
  int cx, cy, cz;
  cell_of(i, cx, cy, cz);
  const float* p = &scene_.positions[3 * size_t(i)];
  std::vector<std::pair<float, uint32_t>> found;
  // Grow the searched cube of cells until the k-th distance is inside it (Gaussians more
  // than 16 cells away are no one's neighbours).
  for (int r = 1; r <= 16; ++r) {
    found.clear();
    for (int dz = -r; dz <= r; ++dz)
      for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx) {
          auto it = cells_.find(key(cx + dx, cy + dy, cz + dz));
          if (it == cells_.end()) continue;
          for (uint32_t j : it->second) {
            if (j == i) continue;
            const float* q = &scene_.positions[3 * size_t(j)];
            const float ex = q[0] - p[0], ey = q[1] - p[1], ez = q[2] - p[2];
            found.push_back({ex * ex + ey * ey + ez * ez, j});
          }
        }
    if (int(found.size()) < k) continue;
    std::nth_element(found.begin(), found.begin() + (k - 1), found.end());
    const double reach = double(r) * cell_;  // every point within this distance is in the cube
    if (double(found[size_t(k - 1)].first) <= reach * reach || r == 16) break;
  }
  const size_t m = std::min(found.size(), size_t(k));
  std::partial_sort(found.begin(), found.begin() + long(m), found.end());
  std::vector<uint32_t> out(m);
  for (size_t j = 0; j < m; ++j) out[j] = found[j].second;
  return out;
}

std::vector<bool> coherent_selection(const VoteAccumulator& votes, const NeighbourIndex& index, double tau,
                                     double min_total, const CoherenceOptions& o) {
  std::vector<bool> strong = votes.select(tau, min_total);
  std::vector<bool> out = strong;
  const std::vector<bool> observed = votes.select(-1.0, min_total);
  const std::vector<float> share = votes.ratios();
  for (uint32_t i = 0; i < uint32_t(share.size()); ++i) {
    if (strong[i] || !observed[i] || !(share[i] > o.tau_low)) continue;
    int seen = 0, selected = 0;
    for (uint32_t j : index.nearest(i, o.neighbours)) {
      if (!observed[j]) continue;
      ++seen;
      selected += strong[j];
    }
    if (seen > 0 && selected >= o.min_selected * seen) out[i] = true;
  }
  return out;
}

}  // namespace isegman::segment
