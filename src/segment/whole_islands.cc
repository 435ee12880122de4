#include "segment/whole_islands.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace isegman::segment {

namespace {

uint32_t root(std::vector<uint32_t>& parent, uint32_t a) {
  while (parent[a] != a) a = parent[a] = parent[parent[a]];
  return a;
}

}  // namespace

size_t drop_whole_islands(std::vector<bool>& selection, const VoteAccumulator& votes, const GaussianScene& scene,
                          const CentreIndex& index, double tau, double min_total, const CentreRule& centre,
                          const IslandOptions& o) {
  if (!o.enabled) return 0;
  const int64_t min_fixed = VoteAccumulator::min_fixed(min_total);
  // The Gaussians that depend on the whole rule (or on their neighbours) and the largest
  // scale a link may need (a high percentile, so one huge Gaussian does not widen every search).
  std::vector<uint32_t> dependent;
  std::vector<float> scales;
  for (size_t j = 0; j < selection.size(); ++j) {
    if (!selection[j]) continue;
    scales.push_back(scene.largest_scale(j));
    if (!votes.selects(j, tau, min_fixed, centre)) dependent.push_back(uint32_t(j));
  }
  // Nothing depends on the rule, or nothing is selected on its own votes (no part to grow
  // from): nothing is dropped.
  if (dependent.empty() || dependent.size() == scales.size()) return 0;
  const size_t q = std::min(scales.size() - 1, size_t(0.95 * double(scales.size())));
  std::nth_element(scales.begin(), scales.begin() + std::ptrdiff_t(q), scales.end());
  const double reach = scales[q];
  // Union-find over the dependent Gaussians (positions in `dependent`); a set is anchored
  // when one of its members touches a Gaussian selected on its own votes.
  std::vector<uint32_t> parent(dependent.size());
  std::iota(parent.begin(), parent.end(), 0u);
  std::vector<uint8_t> anchored(dependent.size(), 0);
  auto slot = [&](uint32_t j) -> long {
    const auto it = std::lower_bound(dependent.begin(), dependent.end(), j);
    return it != dependent.end() && *it == j ? long(it - dependent.begin()) : -1;
  };
  for (size_t a = 0; a < dependent.size(); ++a) {
    const uint32_t g = dependent[a];
    const double sg = scene.largest_scale(g);
    const Vec3 p = scene.position(g);
    for (uint32_t j : index.within(p, o.link_sigmas * (sg + reach))) {
      if (j == g || !selection[j]) continue;
      const double link = o.link_sigmas * (sg + scene.largest_scale(j));
      const Vec3 d = scene.position(j) - p;
      if (d.x * d.x + d.y * d.y + d.z * d.z > link * link) continue;
      const long b = slot(j);
      if (b < 0) {
        anchored[a] = 1;
      } else {
        const uint32_t ra = root(parent, uint32_t(a)), rb = root(parent, uint32_t(b));
        if (ra != rb) parent[ra] = rb;  // anchors reach their set's root after the loop
      }
    }
  }
  size_t dropped = 0;
  for (size_t a = 0; a < dependent.size(); ++a) anchored[root(parent, uint32_t(a))] |= anchored[a];
  for (size_t a = 0; a < dependent.size(); ++a)
    if (!anchored[root(parent, uint32_t(a))]) {
      selection[dependent[a]] = false;
      ++dropped;
    }
  return dropped;
}

}  // namespace isegman::segment
