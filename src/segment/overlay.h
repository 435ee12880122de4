// Per-view evidence pictures: the view's image with the SAM mask, the rendered 3D
// selection, the clicks it received, and a border saying whether inspection accepted it.
#pragma once

#include "core/image.h"
#include "segment/session.h"

namespace isegman::segment {

// rgb: the view image; coverage: the selection's coverage in the view (may be empty).
Image make_overlay(const Image& rgb, const ViewState& state, const Image& coverage);

}  // namespace isegman::segment
