// How far inside a region a pixel lies, and the point a click is propagated from.
#pragma once

#include <cstdint>
#include <vector>

#include "core/click.h"
#include "core/image.h"

namespace isegman::segment {

// Two-pass chamfer (3-4) distance of every pixel of `inside` (w x h, nonzero = in) to the
// nearest pixel outside; 3 units per pixel step. Outside pixels are 0. `border_outside`:
// the image's border counts as outside (a region leaving the frame ends there) or not (a
// region leaving the frame goes on beyond it).
std::vector<int> chamfer_distance(const std::vector<uint8_t>& inside, int w, int h, bool border_outside);

struct AnchorOptions {
  bool enabled = false;  // measured neutral over drawn clicks (docs/evaluation.md): an option
  double radius = 0.04;           // how far the anchor may move from the click, as a share of the width
  // The clicked surface: pixels at most this much nearer or farther (relative depth) than the
  // clicked pixel. Farther is tight: what gaps show lies behind (a wall 8 cm behind a
  // bicycle's spokes is 3 % farther); nearer is loose: an edge pixel's depth blends the
  // object with what lies behind it.
  double nearer_tolerance = 0.05, farther_tolerance = 0.01;
  double min_alpha = 0.5;         // a pixel with less accumulated alpha has no surface
};

// The pixel other views receive a positive click from: of the clicked surface in the
// clicked view's mask (mask pixels within the depth band around the clicked pixel's, connected
// to it) and within `radius` of the click, the one farthest from that surface's outline, with
// distances counted up to the radius (so the nearest pixel that far inside on a large
// object, the middle of a thin one; the nearest such one on ties). A click near a thin post's edge reprojects onto the post's edge
// in other views, and SAM takes the wall there; the post's middle reprojects onto its middle.
// Returns the click unchanged when it is not on the mask's surface or already farthest.
Click interior_anchor(const Image& mask, const Image& depth, const Image& alpha, const Click& click,
                      const AnchorOptions& options);

}  // namespace isegman::segment
