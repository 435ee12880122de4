// The next click of a simulated user, as interactive segmentation benchmarks place it
// (the protocol of RITM and SAM's click-by-click evaluation): at the most interior pixel of
// the larger error, positive in what the selection misses, negative in what it wrongly
// takes. "Larger" is the error region reaching deeper from its border (the image's edge
// counts as border), so a thin sliver along the object's outline does not draw the click
// while a missing part or a wrongly taken neighbour does.
#pragma once

#include <optional>

#include "core/click.h"
#include "core/image.h"

namespace isegman::segment {

// `truth` and `selection`: masks (> 0.5) of one view at the same resolution. No click when
// neither error reaches `min_depth` pixels from its border (nothing left worth a click).
std::optional<Click> corrective_click(const Image& truth, const Image& selection, double min_depth = 2.0);

}  // namespace isegman::segment
