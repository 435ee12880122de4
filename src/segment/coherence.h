// A decision beyond one fixed tau: spatial coherence over the Gaussians' k nearest
// neighbours. A single vote-share threshold cannot fit every scene: coarse Gaussians of
// a thin pillar get shares of 0.5-0.8 (tau = 0.8 drops them), while a neighbour touching
// the object gets the same shares (tau = 0.5 takes it in). What tells them apart is the
// company they keep: a Gaussian with an undecided share is selected when most of its
// observed nearest neighbours are clearly selected (inside the pillar) and not when most
// are clearly not (the neighbour's own body).
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "core/scene.h"
#include "segment/votes.h"

namespace isegman::segment {

struct CoherenceOptions {
  double tau_low = 0.5;        // shares in (tau_low, tau] are decided by the neighbours
  int neighbours = 8;          // k
  double min_selected = 0.5;   // share of the observed neighbours that must be selected
};

// Nearest-neighbour queries over Gaussian centres (a hashed uniform grid: far outliers
// cost no memory).
class NeighbourIndex {
 public:
  explicit NeighbourIndex(const GaussianScene& scene);
  // The k nearest other Gaussians of Gaussian i (fewer when the scene is smaller).
  std::vector<uint32_t> nearest(uint32_t i, int k) const;

 private:
  int64_t key(int x, int y, int z) const;
  void cell_of(uint32_t i, int& x, int& y, int& z) const;
  const GaussianScene& scene_;
  double cell_ = 1;
  std::unordered_map<int64_t, std::vector<uint32_t>> cells_;
};

// The selection: share > tau (and enough weight), plus the undecided Gaussians (share in
// (tau_low, tau]) whose observed neighbours are mostly selected by share > tau.
std::vector<bool> coherent_selection(const VoteAccumulator& votes, const NeighbourIndex& index, double tau,
                                     double min_total, const CoherenceOptions& options = {});

}  // namespace isegman::segment
