// Visibility-based Gaussian voting (VGV). Pixels vote for Gaussians with their
// alpha-blending weight w_ij = alpha_j prod_{l<j} (1 - alpha_l): positive votes
// P_j = sum over masked pixels, all votes A_j = sum over every pixel of the accepted views.
// Sums are kept in 2^-24 fixed point (render/visibility.h), so they are exact, independent
// of thread count and order, and a view's contribution can be removed again bit-exactly.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/image.h"
#include "core/zeroed_array.h"
#include "render/rasterizer.h"
#include "render/visibility.h"

namespace isegman::segment {

constexpr double kVoteScale = kWeightScale;  // 2^24 fixed-point units per unit weight

// One view's sparse contribution: Gaussian indices (ascending) with their summed weights.
using ViewVotes = GaussianWeights;

// All votes of a view (mask independent): one full pass over the prepared frame, or, for
// a compacted frame (compact_frame), its stored per-tile sums.
ViewVotes total_votes(const PreparedFrame& frame, int threads = 0);
// Votes from the pixels where mask > 0.5 (mask at the frame's resolution); only the tiles
// the mask touches are rasterised (of a compacted frame: only those it covers partly).
// With `values` (one per Gaussian, e.g. the current selection as 0/1) the same pass also
// renders their coverage into `coverage` (1 channel, the frame's size) at the mask's pixels
// (0 elsewhere): inspection and voting share one rasterisation.
ViewVotes masked_votes(const PreparedFrame& frame, const Image& mask, int threads = 0,
                       const std::vector<float>* values = nullptr, Image* coverage = nullptr);

// Centre evidence, for Gaussians on an object's outline. A coarse Gaussian of a thin object
// (a pillar a few Gaussians wide) spills over the mask's edge in every view, so its share
// P/A stays at 0.5-0.8, exactly like a neighbour's Gaussian that spills into the mask. What
// tells them apart is where the Gaussian is: the object's own projects its centre inside the
// mask. C_j sums the view totals A_jv of the views whose mask holds j's centre.
struct CentreRule {
  bool enabled = false;
  double tau_low = 0.5;     // shares in (tau_low, tau] may be decided by centre evidence
  double min_centred = 0.7; // ... when C/A exceeds this (the centre inside the masks of nearly every view)
  // A centre hidden outside the mask counts by where the Gaussian shows (centred_votes) when
  // no mask pixel lies within this share of the view's longer side (12 pixels at 480): a
  // mask's outline is a few pixels off the object's, and the object's own rim hides what
  // lies just behind it (0, 3, 6, 12 pixels: the torus's floor 97.7, 98.0, 98.9, 99.0).
  double hidden_margin = 1.0 / 40;
  int hidden_margin_pixels(const Camera& c) const {
    return int(std::lround(hidden_margin * std::max(c.width, c.height)));
  }
};

// Part and whole (session.h, whole_neutral): a view whose mask is a part of one of its own
// larger SAM candidates (the back of a chair, and the whole chair) leaves the rest of that
// candidate open. Its weights there are W_j, neither for nor against. A Gaussian is also
// selected when P/(A - W) exceeds tau and P/A exceeds min_share: the views that segment the
// whole decide, provided they hold a sizeable share of its evidence (a neighbour that a
// few masks spill onto does not).
struct WholeRule {
  bool enabled = false;
  double min_share = 0.3;
};

// Dense sums, one per Gaussian, in zero pages that cost nothing until a view votes there
// (core/zeroed_array.h): a round starts a fresh accumulator.
class VoteAccumulator {
 public:
  explicit VoteAccumulator(size_t gaussians = 0)
      : positive_(gaussians), total_(gaussians), centred_(gaussians), whole_(gaussians) {}
  size_t size() const { return total_.size(); }
  // sign = +1 adds a view, -1 removes it again. `neutral` (optional): weights of the
  // view's total that count neither way (depth-gated content of the mask). `centred`
  // (optional): the view totals of the Gaussians whose centre lies inside the mask. `whole`
  // (optional): weights of the view's total left open between part and whole (WholeRule).
  // `threads`: workers for long lists (0: every core); the sums do not depend on it.
  void add(const ViewVotes& positive, const ViewVotes& total, int sign = 1, const ViewVotes* neutral = nullptr,
           const ViewVotes* centred = nullptr, const ViewVotes* whole = nullptr, int threads = 1);
  // Gaussians whose positive share P/A exceeds tau (or, with the centre rule, tau_low when
  // their centre evidence C/A exceeds min_centred) and whose total weight A is at least
  // min_total (in pixel-weight units); with the whole rule, also those it selects.
  std::vector<bool> select(double tau, double min_total, const CentreRule& centre = {},
                           const WholeRule& whole = {}) const;
  // The same decision for one Gaussian j, with min_fixed = min_fixed(min_total).
  bool selects(size_t j, double tau, int64_t min_fixed, const CentreRule& centre = {}, const WholeRule& whole = {}) const {
    if (!(total_[j] > 0 && total_[j] >= min_fixed)) return false;
    const double a = double(total_[j]), p = double(positive_[j]);
    return p > tau * a || (centre.enabled && p > centre.tau_low * a && double(centred_[j]) > centre.min_centred * a) ||
           (whole.enabled && p > whole.min_share * a && p > tau * (a - double(whole_[j])));
  }
  static int64_t min_fixed(double min_total) { return int64_t(std::ceil(min_total * kVoteScale)); }
  // P/A per Gaussian (0 where A is 0).
  std::vector<float> ratios() const;
  const ZeroedArray<int64_t>& positive() const { return positive_; }
  const ZeroedArray<int64_t>& total() const { return total_; }
  const ZeroedArray<int64_t>& centred() const { return centred_; }
  const ZeroedArray<int64_t>& whole() const { return whole_; }
  bool operator==(const VoteAccumulator& o) const {
    return positive_ == o.positive_ && total_ == o.total_ && centred_ == o.centred_ && whole_ == o.whole_;
  }

 private:
  ZeroedArray<int64_t> positive_, total_, centred_, whole_;
};

// The view totals (from `total`, ascending like `positive`) of the Gaussians of `positive`
// whose centre projects inside mask > 0.5 (the camera's resolution) and is not hidden
// there: its depth is at most the rendered expected depth (`depth`, same size) plus a 5 %
// margin and two of its depth standard deviations. A Gaussian behind the object (the roof
// under a turret) has its centre inside the mask but hidden, and only its rim shows.
// An empty `depth` skips that test.
//
// Where the centre cannot be checked, the view counts a Gaussian that shows mostly inside
// the mask (positive weight above half its view total; a depth-gated Gaussian has left
// `positive` altogether): its centre projects outside the frame, or is hidden by a nearer
// surface that the mask leaves out (no mask pixel within `margin` pixels of it:
// CentreRule::hidden_margin_pixels). A real capture's thin pillar has coarse
// Gaussians that reach up behind the ceiling: their centres are hidden there, and their
// lower parts are the pillar's top. A centre hidden by the object itself (a wall behind a
// trellis, the floor in a ring) stays unchecked and does not count.
ViewVotes centred_votes(const GaussianScene& scene, const Camera& camera, const Image& mask, const Image& depth,
                        const ViewVotes& positive, const ViewVotes& total, int margin = 12, int threads = 1);

// The summed weight of the votes of the flagged Gaussians (one flag per Gaussian): a
// selection's share of a view. Whole fixed-point units, so the same in any order.
int64_t flagged_weight(const ViewVotes& votes, const std::vector<bool>& flags, int threads = 1);

// Bounding tiles of mask > 0.5 pixels, as a tile mask for rasterize().
std::vector<uint8_t> tiles_under_mask(const Image& mask, int grid_x, int grid_y);

}  // namespace isegman::segment
