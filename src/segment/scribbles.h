// Clicks from scribbles: benchmarks such as NVOS give the user's intent as scribble
// images; the click-based method samples a few well-spread clicks from them.
#pragma once

#include <vector>

#include "core/image.h"
#include "segment/pipeline.h"

namespace isegman::segment {

// Up to `count` pixels of the scribble (non-zero pixels), spread out by farthest-point
// sampling starting from the pixel nearest the scribble's centroid. Deterministic.
std::vector<Click> clicks_from_scribble(const Image& scribble, int count, int label);

}  // namespace isegman::segment
