// Shared by the segmentation tests: a rectangular mask, the shape most of them vote with.
#pragma once

#include "core/image.h"

namespace isegman::segment::testing {

// A w x h one-channel mask set to 1 over columns [x0, x1) and rows [y0, y1).
inline Image box_mask(int w, int h, int x0, int x1, int y0, int y1) {
  Image m(w, h, 1);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) m.at(x, y) = 1.f;
  return m;
}

}  // namespace isegman::segment::testing
