#include "segment/votes.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"

namespace isegman::segment {
namespace {

// Per-worker dense accumulators, merged into a sparse list (integer sums: exact and
// order independent).
struct VoteVisitor : ContributionVisitor {
  size_t n;
  const Image* mask;
  std::vector<std::vector<int64_t>> sums;
  VoteVisitor(size_t n_, const Image* m) : n(n_), mask(m) {}
  void begin(int workers) override { sums.assign(workers, std::vector<int64_t>(n, 0)); }
  static int64_t fixed(float w) { return int64_t(double(w) * kVoteScale + 0.5); }  // w >= 0
  void visit(int worker, int x, int y, uint32_t g, float w) override {
    if (mask && !(mask->at(x, y) > 0.5f)) return;
    sums[worker][g] += fixed(w);
  }
  // One call per 8 pixels of a row (the rasteriser's lane group).
  void visit_row8(int worker, int x_base, int y, uint32_t g, const float* w, unsigned lanes) override {
    const float* m = mask ? &mask->data[size_t(y) * mask->width] : nullptr;
    int64_t sum = 0;
    for (int i = 0; i < 8; ++i)
      if ((lanes >> i) & 1u)
        if (!m || m[x_base + i] > 0.5f) sum += fixed(w[i]);
    sums[worker][g] += sum;
  }
  ViewVotes collect() const {
    ViewVotes v;
    for (size_t g = 0; g < n; ++g) {
      int64_t s = 0;
      for (const auto& w : sums) s += w[g];
      if (s != 0) {
        v.index.push_back(uint32_t(g));
        v.weight.push_back(s);
      }
    }
    return v;
  }
};

RenderSettings vote_settings(int threads) {
  RenderSettings s;
  s.color = false;
  s.depth = false;
  s.threads = threads;
  return s;
}

}  // namespace

std::vector<uint8_t> tiles_under_mask(const Image& mask, int grid_x, int grid_y) {
  std::vector<uint8_t> tiles(size_t(grid_x) * grid_y, 0);
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x)
      if (mask.at(x, y) > 0.5f) tiles[size_t(y / kTileSize) * grid_x + x / kTileSize] = 1;
  return tiles;
}

ViewVotes total_votes(const PreparedFrame& frame, int threads) {
  VoteVisitor v(frame.gaussians, nullptr);
  rasterize(frame, vote_settings(threads), nullptr, &v);
  return v.collect();
}

ViewVotes masked_votes(const PreparedFrame& frame, const Image& mask, int threads, const std::vector<float>* values,
                       Image* coverage, bool full_coverage) {
  if (mask.width != frame.camera.width || mask.height != frame.camera.height || mask.channels != 1)
    throw Error("masked_votes: mask does not match the view's resolution");
  VoteVisitor v(frame.gaussians, &mask);
  std::vector<uint8_t> tiles = tiles_under_mask(mask, frame.grid_x, frame.grid_y);
  if (full_coverage && values) std::fill(tiles.begin(), tiles.end(), uint8_t(1));
  RenderOutput r = rasterize(frame, vote_settings(threads), values, &v, &tiles);
  if (coverage && values) *coverage = std::move(r.value);
  return v.collect();
}

void VoteAccumulator::add(const ViewVotes& positive, const ViewVotes& total, int sign, const ViewVotes* neutral) {
  for (size_t k = 0; k < positive.index.size(); ++k) positive_[positive.index[k]] += sign * positive.weight[k];
  for (size_t k = 0; k < total.index.size(); ++k) total_[total.index[k]] += sign * total.weight[k];
  if (neutral)
    for (size_t k = 0; k < neutral->index.size(); ++k) total_[neutral->index[k]] -= sign * neutral->weight[k];
}

std::vector<bool> VoteAccumulator::select(double tau, double min_total) const {
  std::vector<bool> sel(total_.size(), false);
  const int64_t min_fixed = int64_t(std::ceil(min_total * kVoteScale));
  for (size_t j = 0; j < total_.size(); ++j)
    sel[j] = total_[j] > 0 && total_[j] >= min_fixed && double(positive_[j]) > tau * double(total_[j]);
  return sel;
}

std::vector<float> VoteAccumulator::ratios() const {
  std::vector<float> r(total_.size(), 0.f);
  for (size_t j = 0; j < total_.size(); ++j)
    if (total_[j] > 0) r[j] = float(double(positive_[j]) / double(total_[j]));
  return r;
}

}  // namespace isegman::segment
