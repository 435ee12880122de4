// The part/whole band of a view: where its mask is a part of a larger SAM candidate of its
// own (the back of a chair, the whole chair), what the larger candidate adds around the mask
// is left open between part and whole (votes.h WholeRule) instead of voting against.
#pragma once

#include <cstddef>

#include "core/image.h"
#include "core/mask.h"
#include "models/segmenter.h"

namespace isegman::segment {

// What the larger candidates that contain candidate `c` (>= 90 % of it, at most max_growth
// times its area, predicted IoU >= min_score) add around it, less `cut` (the negative
// clicks' region): the view cannot tell part from whole there. Empty when nothing is added.
Image whole_band(const models::SegmentResult& r, int c, const Mask* cut, double max_growth, double min_score);

// A part whose own mask shows, through its gaps, things well beyond its far side (foliage:
// the panels and the window behind a plant's fronds) has larger candidates that take in more
// of that background around it (the real fern: five views mask the fronds, and their larger
// candidate is the fronds with the panels under them). A whole's other parts lie beside the
// part (a chair's seat, a lamp's stem), not beyond what the part's gaps show.
struct BandBeyondPart {
  bool enabled = true;
  int erosion = 2;          // mask pixels this close to its outline do not count: their depth blends what lies beside
  double quantile = 0.8;    // the part's far side: this quantile of its inner pixels' rendered depth ...
  double margin = 0.1;      // ... times 1 + margin
  double min_share = 0.03;  // the part shows something beyond its far side in at least this share of its inner pixels
};

// Clears the band's rendered pixels (alpha > 0.5) that lie beyond the part's far side, when
// the part's mask shows something beyond it in at least min_share of its inner pixels: they
// then vote as any pixel outside the mask. `mask`, `depth` and `alpha` are the view's, one
// channel each at the band's size. Returns the number of pixels cleared.
size_t clear_band_beyond_part(Image& band, const Image& mask, const Image& depth, const Image& alpha,
                              const BandBeyondPart& o);

}  // namespace isegman::segment
