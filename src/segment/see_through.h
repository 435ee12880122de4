// Seeing through occluders at a click: a click on an object seen through the gaps of
// something nearer (a vase behind a trellis, a crate behind a post) gives SAM only the
// fragments between the bars. When, around the click, thin things nearer than the clicked
// surface are flanked on both sides by that surface (it is seen around them), the view is
// rendered again without everything up to just behind them (a near plane) and SAM
// segments the object whole; its votes then come from that peeled render too.
#pragma once

#include <cstdint>
#include <vector>

#include "core/camera.h"
#include "core/centre_index.h"
#include "core/image.h"
#include "core/scene.h"
#include "render/rasterizer.h"

namespace isegman::segment {

struct SeeThroughOptions {
  double window = 0.08;       // half-size of the window around the click, share of the longer side
  double flank = 0.03;        // how far (share of the longer side) the surface must reappear on both sides
  double gap = 0.02;          // relative depth by which an occluder is nearer than the clicked surface
  double band = 0.15;         // relative depth behind the clicked surface that still counts as it
  double min_share = 0.05;    // flanked occluder pixels needed, share of the window's pixels
  double max_in_mask = 0.5;   // no peeling when SAM's mask at the click already holds this share of them...
  // ... unless they are an enclosure around a smaller thing (a cone inside a mesh cage), not the
  // clicked thing's own near parts (a plant's near leaves). An enclosure stands apart in 3D
  // from what it encloses: of what SAM's mask at the click holds at the clicked surface's
  // depth around the click, at most max_enclosure_touch touches what the mask holds nearer
  // than the cut (enclosure_contact: a playpen's toy 0-0.5 %, a cage's cone 0.1 %, a vase
  // behind a net curtain 0.7-0.9 %), where a plant's nearer leaves run on into the clicked
  // ones (5-11 % in the evaluation set, 14 % on the fern). And rendered without them, what
  // SAM segments at the click is under min_peeled_share of that mask (the fern: 45 %).
  double max_enclosure_touch = 0.02;
  double link_sigmas = 1.0;  // the touch rule's reach (whole_islands.h)
  double min_peeled_share = 0.25;
  // No peeling when the clicked pixel gives more than this blending weight to things nearer
  // than its surface (a click through a gap sees the surface clearly: at most ~0.05 there).
  double max_click_front_weight = 0.25;
  // No peeling when this share of the current selection's blending weight in the view comes
  // from Gaussians nearer than the cut: a later click at the edge of a selected object (the
  // sliver the first click missed) can find the object's own near side flanked by what lies
  // behind it, and the cut would peel the selection itself away.
  double max_selection_peeled = 0.5;
  // No peeling when, rendered without the occluders, SAM's own answer at the click covers
  // more than this share of the view: the cut went through the scene itself (a
  // half-transparent box on a roof, whose cut took the roof off and showed SAM the
  // building's inside as one region), not past bars in front of one object (a vase behind a
  // trellis: 1.7 % of the view; the fern's planter 13 %).
  double max_peeled_view_share = 0.5;
};

struct Occluders {
  bool found = false;
  double cut = 0;        // camera-space depth just behind the occluders: render from here on
  double share = 0;      // share of the window's pixels that are flanked occluders
  double surface = 0;    // depth of the clicked surface
  double click_front_weight = 0;  // the clicked pixel's blending weight nearer than that surface
  std::vector<uint32_t> pixels;  // the flanked occluder pixels (y * width + x)
};

// Looks for flanked occluders around continuous pixel (x, y) of a prepared view. A pixel's
// surface is the centre depth of the Gaussian at which its accumulated blending weight
// reaches 0.5 (none where it never does): unlike the expected depth it does not blend a
// bar's edge with the wall behind it. The occluders end at the widest relative depth gap
// among the flanked pixels and the clicked surface (one leaving at least min_share of the
// window in front): flanked pixels beyond a wider gap than the one to the surface are that
// surface's own nearer parts, and the cut falls before them.
Occluders find_occluders(const GaussianScene& scene, const PreparedFrame& frame, double x, double y,
                         const SeeThroughOptions& options = {}, int threads = 0);

// How much of what a click shows touches the occluders found there: of the Gaussians in
// `shown` (those SAM's mask at the click blends in `camera`) whose centres lie at the clicked
// surface's depth (from occ.cut to options.band behind occ.surface) and project within
// options.window of pixel (x, y), the share that touches one of `shown` nearer than the cut.
// Two Gaussians touch when their centres lie within link_sigmas x the sum of their largest
// scales (whole_islands.h). `index` is built over `scene`. 0 when nothing lies there;
// `threads` (0: every core) does not change the result.
double enclosure_contact(const GaussianScene& scene, const CentreIndex& index, const Camera& camera,
                         const std::vector<uint32_t>& shown, const Occluders& occ, double x, double y,
                         const SeeThroughOptions& options = {}, int threads = 0);

}  // namespace isegman::segment
