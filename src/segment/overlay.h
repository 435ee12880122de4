// Per-view evidence pictures: the view's image with the SAM mask, the rendered 3D
// selection, the clicks it received, the truth where known, and a border saying whether inspection accepted it.
#pragma once

#include "core/image.h"
#include "segment/session.h"

namespace isegman::segment {

// rgb: the view image; coverage: the selection's coverage in the view (may be empty);
// truth (optional, may be empty): the true object's mask, outlined in cyan where it is known
// (the evaluation's synthetic tasks), so an overlay shows what was missed and what was not wanted.
Image make_overlay(const Image& rgb, const ViewState& state, const Image& coverage, const Image& truth = {});

}  // namespace isegman::segment
