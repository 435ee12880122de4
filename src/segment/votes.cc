#include "segment/votes.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"

namespace isegman::segment {
namespace {

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
  return weight_sums(frame, nullptr, vote_settings(threads));
}

ViewVotes masked_votes(const PreparedFrame& frame, const Image& mask, int threads, const std::vector<float>* values,
                       Image* coverage, bool full_coverage) {
  if (mask.width != frame.camera.width || mask.height != frame.camera.height || mask.channels != 1)
    throw Error("masked_votes: mask does not match the view's resolution");
  return weight_sums(frame, &mask, vote_settings(threads), values, coverage, full_coverage && values);
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
