// A decision beyond one fixed tau: spatial coherence over the Gaussians' k nearest
// neighbours. A single vote-share threshold cannot fit every scene: coarse Gaussians of
// a thin pillar get shares of 0.5-0.8 (tau = 0.8 drops them), while a neighbour touching
// the object gets the same shares (tau = 0.5 takes it in). What tells them apart is the
// company they keep: a Gaussian with an undecided share is selected when most of its
// observed nearest neighbours are clearly selected (inside the pillar) and not when most
// are clearly not (the neighbour's own body).
#pragma once

#include <vector>

#include "core/centre_index.h"
#include "segment/votes.h"

namespace isegman::segment {

struct CoherenceOptions {
  double tau_low = 0.5;        // shares in (tau_low, tau] are decided by the neighbours
  int neighbours = 8;          // k
  double min_selected = 0.5;   // share of the observed neighbours that must be selected
};

// The selection: share > tau (and enough weight), plus the undecided Gaussians (share in
// (tau_low, tau]) whose observed k nearest Gaussians (`index`, built over `scene`) are
// mostly selected by share > tau (or by the centre rule, votes.h).
// `strong` (optional): votes.select(tau, min_total, centre), when already known.
// `candidates` (optional): Gaussians outside which every positive vote sum is 0; with
// tau_low >= 0 only they can be undecided, so only they are visited (not all N).
std::vector<bool> coherent_selection(const VoteAccumulator& votes, const GaussianScene& scene, const CentreIndex& index,
                                     double tau, double min_total, const CoherenceOptions& options = {},
                                     const CentreRule& centre = {}, const std::vector<bool>* strong = nullptr,
                                     const std::vector<uint32_t>* candidates = nullptr, const WholeRule& whole = {});

}  // namespace isegman::segment
