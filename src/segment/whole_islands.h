// Part and whole in 3D. The part/whole rule (votes.h, WholeRule) selects what the views
// that segment a whole vote for while the other views leave it open: the rest of a chair
// whose back one view masked. A neighbour that SAM merged into its mask in some views (a
// potted plant standing beside the clicked shrub) passes that rule just the same. What tells
// them apart is that a whole grows from the part the votes choose on their own: the chair's
// seat touches its back, the plant beside the shrub stands apart.
#pragma once

#include <cstddef>
#include <vector>

#include "core/centre_index.h"
#include "core/scene.h"
#include "segment/votes.h"

namespace isegman::segment {

struct IslandOptions {
  bool enabled = false;
  // Two Gaussians touch when their centres lie within link_sigmas x (the largest scale of
  // one + that of the other) of each other: 1, their one-sigma ellipsoids meet (the porch's
  // shrub 83.8 -> 94.1 with 1, 83.9 with 1.5, unchanged with 3: the geranium beside it
  // stays joined).
  double link_sigmas = 1.0;
  // A whole grows from a part that is a real share of it: what the whole rule alone
  // selects stays only when the part it touches (selected on its own votes) is at least
  // this fraction of its size. With 10 of 20 views taking in the geranium beside a clicked
  // shrub, 3 of its 1,183 Gaussians pass on their own (the porch at 960x720); a compound
  // object's other part holds far more (the courtyard lamp's base: 218 of 460).
  double min_own_share = 0.02;
};

// How far the touch rule's neighbour search reaches past a Gaussian's own scale: the 95th
// percentile of the linked Gaussians' largest scales (`scales`, reordered), so that one huge
// Gaussian does not widen every search. 0 when there are none.
float touch_reach(std::vector<float>& scales);

// The touch rule of the island steps (here and negative_islands.h): two selected Gaussians
// touch when their centres lie within link_sigmas x (the largest scale of one + that of the
// other). A search reaches as far as a high percentile of the selection's scales allows, so
// one huge Gaussian does not widen every search.
class TouchingGaussians {
 public:
  // `index` is built over `scene`; both and `selection` must outlive this. `threads`: for
  // the selection's scales (0 = all cores).
  TouchingGaussians(const GaussianScene& scene, const CentreIndex& index, const std::vector<bool>& selection,
                    double link_sigmas, int threads = 1);
  // f(j) for every selected Gaussian j != g that touches g.
  template <class F>
  void for_each(uint32_t g, F&& f) const {
    const double sg = scene_.largest_scale(g);
    const Vec3 p = scene_.position(g);
    for (uint32_t j : index_.within(p, link_ * (sg + reach_))) {
      if (j == g || !selection_[j]) continue;
      const double link = link_ * (sg + scene_.largest_scale(j));
      const Vec3 d = scene_.position(j) - p;
      if (d.x * d.x + d.y * d.y + d.z * d.z <= link * link) f(j);
    }
  }

 private:
  const GaussianScene& scene_;
  const CentreIndex& index_;
  const std::vector<bool>& selection_;
  double link_, reach_ = 0;
};

// Drops from `selection` the Gaussians that neither their own share (P/A > tau, with
// enough weight) nor the centre rule selects (the dependent ones), set by set (dependent
// Gaussians joined by chains, each touching the next), unless the set touches a part
// those do select (such Gaussians joined by chains) of at least min_own_share of the
// set's size, and at least one Gaussian. `index` is built over `scene`. Returns the
// number dropped. `threads`: for the neighbour searches (0 = all cores; the same result).
size_t drop_whole_islands(std::vector<bool>& selection, const VoteAccumulator& votes, const GaussianScene& scene,
                          const CentreIndex& index, double tau, double min_total, const CentreRule& centre,
                          const IslandOptions& options, int threads = 1);

}  // namespace isegman::segment
