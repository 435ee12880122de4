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
};

// Drops from `selection` the Gaussians that neither their own share (P/A > tau, with
// enough weight) nor the centre rule selects, unless a chain of selected Gaussians, each
// touching the next, joins them to one those select. `index` is built over `scene`.
// Returns the number dropped.
size_t drop_whole_islands(std::vector<bool>& selection, const VoteAccumulator& votes, const GaussianScene& scene,
                          const CentreIndex& index, double tau, double min_total, const CentreRule& centre,
                          const IslandOptions& options);

}  // namespace isegman::segment
