// Negative clicks in 3D. A negative click on something the selection took marks it as not
// the object. The cut in SAM's masks (session.h, negative_regions) removes it only where SAM
// segments it apart from the object; where SAM cannot (a grey box standing before the grey
// watering can that was clicked beside it), the negative click changed nothing. In 3D the two
// may still stand apart: the selected Gaussians the negative click's pixel shows, and every
// selected Gaussian a chain of touching selected Gaussians joins to them, leave the
// selection, unless that chain reaches what a positive click's pixel shows (then the
// negative click is on the object itself, or on something joined to it, and touching alone
// cannot part them).
#pragma once

#include <cstdint>
#include <vector>

#include "core/centre_index.h"
#include "core/scene.h"
#include "render/rasterizer.h"
#include "segment/whole_islands.h"

namespace isegman::segment {

// The selected Gaussians pixel (x, y) of `frame` shows: those blending there at least half
// the largest weight a selected Gaussian blends there. Empty when none is selected there.
std::vector<uint32_t> selected_at_pixel(const PreparedFrame& frame, const std::vector<bool>& selection, int x, int y,
                                        int threads = 1);

struct NegativeCut {
  size_t removed = 0;  // Gaussians that left the selection
  int cut = 0;         // negative clicks whose island left
  int joined = 0;      // negative clicks joined to a positive click's Gaussians (nothing left)
};

// Removes from `selection` the island of each negative click's Gaussians (`negative_seeds`,
// one list per click), unless it holds one of `positive_seeds`. Two selected Gaussians touch
// as in drop_whole_islands (`link`, its link_sigmas). `index` is built over `scene`.
NegativeCut cut_negative_islands(std::vector<bool>& selection, const GaussianScene& scene, const CentreIndex& index,
                                 const std::vector<uint32_t>& positive_seeds,
                                 const std::vector<std::vector<uint32_t>>& negative_seeds, const IslandOptions& link);

}  // namespace isegman::segment
