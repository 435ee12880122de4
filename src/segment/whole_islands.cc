#include "segment/whole_islands.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/parallel.h"

namespace isegman::segment {

namespace {

uint32_t root(std::vector<uint32_t>& parent, uint32_t a) {
  while (parent[a] != a) a = parent[a] = parent[parent[a]];
  return a;
}

}  // namespace

float touch_reach(std::vector<float>& scales) {
  if (scales.empty()) return 0;
  const size_t q = std::min(scales.size() - 1, size_t(0.95 * double(scales.size())));
  std::nth_element(scales.begin(), scales.begin() + std::ptrdiff_t(q), scales.end());
  return scales[q];
}

TouchingGaussians::TouchingGaussians(const GaussianScene& scene, const CentreIndex& index,
                                     const std::vector<bool>& selection, double link_sigmas, int threads)
    : scene_(scene), index_(index), selection_(selection), link_(link_sigmas) {
  // The selected Gaussians' scales, gathered in chunks (a scene of millions, a selection of
  // about a million); the percentile is one value whatever their order.
  const size_t n = selection.size(), grain = list_grain(n);
  std::vector<std::vector<float>> parts(chunk_count(n, grain));
  parallel_chunks(n, grain, threads, [&](size_t chunk, size_t begin, size_t end) {
    std::vector<float> part;
    for (size_t j = begin; j < end; ++j)
      if (selection[j]) part.push_back(scene.largest_scale(j));
    parts[chunk] = std::move(part);
  });
  std::vector<float> scales;
  for (const std::vector<float>& part : parts) scales.insert(scales.end(), part.begin(), part.end());
  reach_ = touch_reach(scales);
}

size_t drop_whole_islands(std::vector<bool>& selection, const VoteAccumulator& votes, const GaussianScene& scene,
                          const CentreIndex& index, double tau, double min_total, const CentreRule& centre,
                          const IslandOptions& o, int threads) {
  if (!o.enabled) return 0;
  const int64_t min_fixed = VoteAccumulator::min_fixed(min_total);
  // The Gaussians that depend on the whole rule (or on their neighbours).
  std::vector<uint32_t> dependent;
  size_t selected = 0;
  for (size_t j = 0; j < selection.size(); ++j) {
    if (!selection[j]) continue;
    ++selected;
    if (!votes.selects(j, tau, min_fixed, centre)) dependent.push_back(uint32_t(j));
  }
  // Nothing depends on the rule, or nothing is selected on its own votes (no part to grow
  // from): nothing is dropped.
  if (dependent.empty() || dependent.size() == selected) return 0;
  const TouchingGaussians touching(scene, index, selection, o.link_sigmas, threads);
  // Union-find over the dependent Gaussians (positions in `dependent`), and the Gaussians
  // selected on their own votes that each touches (its set's anchors).
  std::vector<uint32_t> parent(dependent.size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto slot = [&](uint32_t j) -> long {
    const auto it = std::lower_bound(dependent.begin(), dependent.end(), j);
    return it != dependent.end() && *it == j ? long(it - dependent.begin()) : -1;
  };
  std::vector<std::pair<uint32_t, uint32_t>> anchors;  // (dependent position, anchor)
  // The neighbour searches, a block of dependent Gaussians at a time, run in parallel (each
  // Gaussian's touching ones in a list of its own); the joins that follow do not depend on
  // the order (the sets are the connected ones, the anchors are sorted below).
  constexpr size_t kBlock = size_t(1) << 14;
  std::vector<std::vector<uint32_t>> touches;
  for (size_t first = 0; first < dependent.size(); first += kBlock) {
    const size_t count = std::min(kBlock, dependent.size() - first);
    touches.assign(count, {});
    parallel_chunks(count, 256, threads, [&](size_t, size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i) touching.for_each(dependent[first + i], [&](uint32_t j) { touches[i].push_back(j); });
    });
    for (size_t i = 0; i < count; ++i) {
      const uint32_t a = uint32_t(first + i);
      for (uint32_t j : touches[i]) {
        const long b = slot(j);
        if (b < 0) {
          anchors.push_back({a, j});
        } else {
          const uint32_t ra = root(parent, a), rb = root(parent, uint32_t(b));
          if (ra != rb) parent[ra] = rb;
        }
      }
    }
  }
  std::vector<uint32_t> set_size(dependent.size(), 0);
  for (size_t a = 0; a < dependent.size(); ++a) ++set_size[root(parent, uint32_t(a))];
  for (auto& [a, j] : anchors) a = root(parent, a);
  std::sort(anchors.begin(), anchors.end());
  // A set is anchored when the part it touches (the Gaussians selected on their own votes
  // joined to its anchors by chains of such Gaussians) holds at least min_own_share of its
  // size, and at least one Gaussian. A search from the anchors stops as soon as it has
  // found that many.
  std::vector<uint8_t> anchored(dependent.size(), 0);
  std::vector<uint32_t> found, frontier;
  for (size_t i = 0; i < anchors.size();) {
    const uint32_t set = anchors[i].first;
    found.clear();
    for (; i < anchors.size() && anchors[i].first == set; ++i)
      if (found.empty() || found.back() != anchors[i].second) found.push_back(anchors[i].second);
    const size_t need = std::max<size_t>(1, size_t(std::ceil(o.min_own_share * double(set_size[set]))));
    frontier = found;
    std::sort(found.begin(), found.end());
    while (found.size() < need && !frontier.empty()) {
      const uint32_t g = frontier.back();
      frontier.pop_back();
      touching.for_each(g, [&](uint32_t j) {
        if (found.size() >= need || slot(j) >= 0) return;
        const auto at = std::lower_bound(found.begin(), found.end(), j);
        if (at != found.end() && *at == j) return;
        found.insert(at, j);
        frontier.push_back(j);
      });
    }
    anchored[set] = found.size() >= need;
  }
  size_t dropped = 0;
  for (size_t a = 0; a < dependent.size(); ++a)
    if (!anchored[root(parent, uint32_t(a))]) {
      selection[dependent[a]] = false;
      ++dropped;
    }
  return dropped;
}

}  // namespace isegman::segment
