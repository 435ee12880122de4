#include "segment/apart_islands.h"

#include <algorithm>

#include "core/zeroed_array.h"

namespace isegman::segment {

namespace {

// Views past this many (8 bits a Gaussian) are not read: a user gives a few positive clicks.
constexpr size_t kMaxClickedViews = 8;

enum Flood : uint8_t { kUnvisited = 0, kJoined = 1, kSettled = 2 };

}  // namespace

ApartReport drop_apart_islands(std::vector<bool>& selection, const GaussianScene& scene, const CentreIndex& index,
                               const std::vector<ClickedViewVotes>& clicked,
                               const std::vector<uint32_t>& click_gaussians, double min_weight,
                               const ApartOptions& options, const IslandOptions& link, int threads) {
  ApartReport out;
  if (!options.enabled || clicked.empty() || click_gaussians.empty()) return out;
  const size_t n = selection.size();
  const size_t views = std::min(clicked.size(), kMaxClickedViews);
  // Per Gaussian: inside some clicked view's mask; a bit per clicked view that sees it outside.
  ZeroedArray<uint8_t> inside(n), outside(n), at_click(n);
  for (uint32_t g : click_gaussians) at_click[g] = 1;
  std::vector<uint32_t> seeds;
  size_t in_masks = 0;  // the object as the clicked views' masks show it: its selected Gaussians there
  const double min_fixed = min_weight * kVoteScale;
  for (size_t v = 0; v < views; ++v) {
    const ViewVotes& total = *clicked[v].total;
    const ViewVotes& mask = *clicked[v].inside;
    size_t m = 0;
    for (size_t i = 0; i < total.index.size(); ++i) {
      const uint32_t g = total.index[i];
      while (m < mask.index.size() && mask.index[m] < g) ++m;
      if (!selection[g]) continue;
      const double a = double(total.weight[i]);
      const double p = m < mask.index.size() && mask.index[m] == g ? double(mask.weight[m]) : 0.0;
      if (p > 0 && p >= options.inside_share * a) {
        in_masks += !inside[g];
        inside[g] = 1;
      } else if (a >= min_fixed && p <= options.outside_share * a) {
        if (!outside[g]) seeds.push_back(g);
        outside[g] = uint8_t(outside[g] | (1u << v));
      }
    }
  }
  if (seeds.empty()) return out;
  // Large Gaussians do not link: a few broad flat ones of the floor the selection took join
  // everything standing on it.
  std::vector<bool> linkable = selection;
  {
    std::vector<uint32_t> selected;
    std::vector<float> scales;
    for (size_t j = 0; j < n; ++j)
      if (selection[j]) {
        selected.push_back(uint32_t(j));
        scales.push_back(scene.largest_scale(j));
      }
    std::vector<float> sorted = scales;
    std::nth_element(sorted.begin(), sorted.begin() + std::ptrdiff_t(sorted.size() / 2), sorted.end());
    const double limit = options.max_link_scale * sorted[sorted.size() / 2];
    for (size_t i = 0; i < selected.size(); ++i)
      if (scales[i] > limit) linkable[selected[i]] = false;
  }
  const TouchingGaussians touching(scene, index, linkable, link.link_sigmas, threads);
  ZeroedArray<uint8_t> state(n);
  std::vector<uint32_t> frontier, leave;
  for (uint32_t seed : seeds) {
    if (state[seed] != kUnvisited || inside[seed] || !linkable[seed]) continue;
    // Flood the set breadth first over selected Gaussians; it ends early when it joins what
    // a positive click's pixel shows (or a set that did), which for the rest of an object is
    // near. Not the mask: a clicked view's mask may spill onto the neighbour's near edge.
    frontier.assign(1, seed);
    state[seed] = kSettled;
    bool joined = at_click[seed] != 0;
    for (size_t head = 0; head < frontier.size() && !joined; ++head) {
      touching.for_each(frontier[head], [&](uint32_t j) {
        if (joined) return;
        if (at_click[j] || state[j] == kJoined) {
          joined = true;
          return;
        }
        if (state[j] != kUnvisited) return;
        state[j] = kSettled;
        frontier.push_back(j);
      });
    }
    if (joined) {
      for (uint32_t g : frontier) state[g] = kJoined;
      continue;
    }
    size_t seen_outside[kMaxClickedViews] = {};
    size_t selected_in_set = 0;
    for (uint32_t g : frontier) {
      if (!selection[g]) continue;
      ++selected_in_set;
      for (size_t v = 0; v < views; ++v) seen_outside[v] += (outside[g] >> v) & 1u;
    }
    const size_t most = *std::max_element(seen_outside, seen_outside + views);
    if (double(most) < options.min_seen_share * double(selected_in_set)) continue;
    if (double(selected_in_set) < options.min_size_share * double(in_masks)) continue;
    for (uint32_t g : frontier)
      if (selection[g]) leave.push_back(g);
    ++out.islands;
  }
  // Only after every flood: the touch rule sees one selection throughout.
  for (uint32_t g : leave) selection[g] = false;
  out.removed = leave.size();
  return out;
}

}  // namespace isegman::segment
