#include "segment/attached_parts.h"

#include <algorithm>

#include "core/parallel.h"
#include "segment/whole_islands.h"

namespace isegman::segment {

size_t add_attached_parts(std::vector<bool>& selection, const VoteAccumulator& votes, double min_total,
                          const std::vector<uint32_t>& candidates, const std::vector<uint8_t>& set_aside,
                          const std::vector<uint32_t>& apart, const std::vector<bool>& excluded,
                          const GaussianScene& scene, const CentreIndex& index, const AttachedPartsOptions& o,
                          int threads, const std::vector<ViewVotes>* wide) {
  if (!o.enabled) return 0;
  // What the wide views voted for each candidate (both lists ascending).
  std::vector<int64_t> wide_weight(wide && !wide->empty() ? candidates.size() : 0, 0);
  if (!wide_weight.empty())
    for (const ViewVotes& v : *wide)
      for (size_t i = 0, c = 0; i < v.index.size(); ++i) {
        while (c < candidates.size() && candidates[c] < v.index[i]) ++c;
        if (c < candidates.size() && candidates[c] == v.index[i]) wide_weight[c] += v.weight[i];
      }
  const int64_t min_fixed = VoteAccumulator::min_fixed(min_total);
  const auto& P = votes.positive();
  const auto& A = votes.total();
  const auto& W = votes.whole();
  std::vector<bool> apart_flag(selection.size(), false);
  for (uint32_t j : apart) apart_flag[j] = true;
  // Open: the Gaussians that may still join (cleared as they join or are claimed).
  std::vector<bool> open(selection.size(), false);
  std::vector<uint32_t> listed;
  for (size_t c = 0; c < candidates.size(); ++c) {
    const uint32_t j = candidates[c];
    if (selection[j] || apart_flag[j] || (!set_aside.empty() && set_aside[j] >= o.min_set_aside_views) || (!excluded.empty() && excluded[j]))
      continue;
    const double a = double(A[j]), p = double(P[j] - (wide_weight.empty() ? 0 : wide_weight[c]));
    if (A[j] <= 0 || A[j] < min_fixed || p <= o.min_plain_share * a || p <= o.min_share * (a - double(W[j]))) continue;
    open[j] = true;
    listed.push_back(j);
  }
  if (listed.empty()) return 0;
  const TouchingGaussians touching_open(scene, index, open, o.link_sigmas, threads);
  // Flood `open` from `queue`, calling take(j) on every Gaussian it reaches.
  auto flood = [&](std::vector<uint32_t> queue, auto&& take) {
    while (!queue.empty()) {
      const uint32_t g = queue.back();
      queue.pop_back();
      touching_open.for_each(g, [&](uint32_t j) {
        if (!open[j]) return;
        open[j] = false;
        take(j);
        queue.push_back(j);
      });
    }
  };
  // A neighbour whole islands set apart claims what attaches to it first (the selection is
  // counted only when something was set apart: a pass over every Gaussian).
  if (!apart.empty()) {
    size_t selected = 0;
    for (bool s : selection) selected += s;
    if (double(apart.size()) >= o.min_neighbour_share * double(selected)) flood(apart, [](uint32_t) {});
  }
  // Then the selection takes what attaches to it: first what touches it, then what touches that.
  std::vector<uint32_t> seeds;
  {
    const TouchingGaussians touching_selection(scene, index, selection, o.link_sigmas, threads);
    // Each open Gaussian's search on its own, in parallel; the seeds in the listed order.
    std::vector<uint8_t> touches(listed.size(), 0);
    parallel_chunks(listed.size(), 256, threads, [&](size_t, size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i)
        if (open[listed[i]]) touching_selection.for_each(listed[i], [&](uint32_t) { touches[i] = 1; });
    });
    for (size_t i = 0; i < listed.size(); ++i)
      if (touches[i]) seeds.push_back(listed[i]);
  }
  size_t added = 0;
  for (uint32_t c : seeds) {
    open[c] = false;
    selection[c] = true;
    ++added;
  }
  flood(seeds, [&](uint32_t j) {
    selection[j] = true;
    ++added;
  });
  return added;
}

}  // namespace isegman::segment
