// EIP, Epipolar-guided Interaction Propagation: a click in one view becomes a click in
// every other view where its target can be seen.
//   epipolar: the paper — walk the feature-grid cells along the click's epipolar line and
//             take the cell whose feature is most similar to the clicked one;
//   depth:    reproject the 3D point at the rendered expected depth;
//   hybrid:   the epipolar search restricted to a window around the depth reprojection.
// With depth available, a click whose 3D point is hidden behind the rendered surface of
// a view, or projects outside it, is not sent there.
#pragma once

#include <string>

#include "core/click.h"
#include "segment/views.h"

namespace isegman::segment {

enum class PropagationMode { Epipolar, Depth, Hybrid };
PropagationMode parse_mode(const std::string& name);
const char* mode_name(PropagationMode mode);

struct PropagationOptions {
  PropagationMode mode = PropagationMode::Hybrid;
  double window_cells = 2.0;     // hybrid: search radius around the reprojection, in grid cells
  double occlusion_tolerance = 0.05;  // relative depth slack before a point counts as hidden
  double min_alpha = 0.5;        // a pixel with less accumulated alpha has no surface
  // Hybrid, when the clicked point is hidden in a view: false (default) sends no click
  // there (the view may still be prompted from the 3D selection); true searches the whole
  // epipolar line as the paper does, which often lands on the occluder.
  bool hidden_fallback = false;
  // Hybrid: where the target view's rendered depth at the reprojection agrees with the
  // point's own depth (within this share), that pixel shows the clicked surface point and
  // the feature search is skipped: a 64x64 feature cell is wider than a thin pole, and its
  // best match moves the click onto the wall beside it. 0: always search.
  double depth_agreement = 0.02;
};

struct Propagated {
  bool sent = false;
  Click click;
  float affinity = 0;   // feature similarity of the match (epipolar / hybrid)
  std::string reason;   // why it was not sent
};

// 3D point under a view's pixel at the rendered expected depth; false without surface.
bool surface_point(const SegmentView& view, double u, double v, double min_alpha, Vec3& point);

Propagated propagate(const SegmentView& from, const Click& click, const SegmentView& to,
                     const PropagationOptions& options, double scene_extent);

}  // namespace isegman::segment
