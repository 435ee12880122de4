// The part/whole band of a view: where its mask is a part of a larger SAM candidate of its
// own (the back of a chair, the whole chair), what the larger candidate adds around the mask
// is left open between part and whole (votes.h WholeRule) instead of voting against. And
// what a part's gaps show behind it, which SAM's larger masks around foliage take in.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/click.h"
#include "core/image.h"
#include "core/mask.h"
#include "models/segmenter.h"

namespace isegman::segment {

// What the larger candidates that contain candidate `c` (>= 90 % of it, at most max_growth
// times its area, predicted IoU >= min_score) add around it, less `cut` (the negative
// clicks' region): the view cannot tell part from whole there. Empty when nothing is added.
Image whole_band(const models::SegmentResult& r, int c, const Mask* cut, double max_growth, double min_score);

// A part whose own mask shows, through its gaps, things well beyond its far side (foliage:
// the panels and the window behind a plant's fronds) has larger masks that take in more of
// that background around it. On the real fern five views mask the fronds and fifteen the
// fronds with the panels, the planter and the window under and behind them. A whole's other
// parts lie beside the part (a chair's seat, a lamp's stem), not as deep as what its gaps show.
struct BeyondPart {
  bool band = true;   // a view that took the part: its band's background is not left open
  bool whole = true;  // a view that took the larger mask: its background does not vote
  int erosion = 2;          // mask pixels this close to its outline do not count: their depth blends what lies beside
  double quantile = 0.8;    // the part's far side: this quantile of its inner pixels' rendered depth ...
  double margin = 0.1;      // ... times 1 + margin
  double min_share = 0.03;  // the part shows something beyond its far side in at least this share of its inner pixels
  // ... through gaps: with nearer pixels of the part on both sides along the row or the
  // column, within this share of the image's larger side
  double max_gap = 0.03;
  // The background begins at this quantile of the depths the part shows beyond its far side
  // (above the nearest: a plant's own deeper leaves show through its gaps too).
  double background_quantile = 0.3;
  double min_part = 1.0 / 6, max_part = 0.95;  // a larger mask's part: its largest other candidate of this share of its area
};

// The rendered depth from which the part (`part` > 0.5) shows background through its gaps:
// the background_quantile of the depths of its gap pixels (inner pixels beyond its far side
// between nearer pixels of it), where they are at least min_share of its inner pixels
// (rendered, alpha > 0.5, `erosion` pixels in from its outline); +infinity where the part
// shows no such thing. One channel each, the same size.
float seen_through_depth(const Image& part, const Image& depth, const Image& alpha, const BeyondPart& o);

// Clears the band's rendered pixels (alpha > 0.5) at or beyond the depth the view's part
// (`mask`) shows through its gaps: they then vote as any pixel outside the mask. Returns the
// number of pixels cleared.
size_t clear_band_beyond_part(Image& band, const Image& mask, const Image& depth, const Image& alpha, const BeyondPart& o);

// A view's mask (`mask`: SAM's candidate `chosen`, less the negative clicks' region, 0/1 per
// pixel) less its rendered pixels outside its part at or beyond the depth the part shows
// through its gaps. The part is the largest other candidate of min_part..max_part of the
// mask's area lying >= 90 % inside it and holding every positive click of `clicks` (there
// must be one): what the click is on. Returns the number of pixels cleared.
size_t trim_beyond_part(std::vector<uint8_t>& mask, const models::SegmentResult& r, int chosen,
                        const std::vector<Click>& clicks, const Image& depth, const Image& alpha, const BeyondPart& o);

}  // namespace isegman::segment
