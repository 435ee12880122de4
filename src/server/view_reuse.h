// Recompute only what an edit changed: after an edit the segmentation needs views of the
// edited scene, but a view whose render the edit cannot have changed keeps its render
// and SAM embedding (the costly part); only its prepared frame and all-pixel votes,
// which index Gaussians, are recomputed.
//
// What changed is found by content: every Gaussian of the scene before and after is
// matched by its parameters (a multiset match, so removals, insertions and reorderings
// are all seen); the unmatched ones of either side are the affected Gaussians. A view is
// unchanged when none of them reaches its image: the rasteriser's own 3-sigma footprint
// (render/projection.h) of each lies outside the image or the Gaussian is culled. Then
// every pixel is computed from the same Gaussians in the same order, and the render is
// bit-identical (the depth sort is stable in index order, which removals and appends
// keep).
#pragma once

#include <cstdint>
#include <vector>

#include "core/camera.h"
#include "core/scene.h"
#include "render/rasterizer.h"
#include "segment/views.h"

namespace isegman::server {

struct SceneDiff {
  bool everything = false;        // the SH degree changed: treat every view as changed
  std::vector<uint32_t> removed;  // indices in `before` of Gaussians gone or changed
  std::vector<uint32_t> added;    // indices in `after` of Gaussians new or changed
  bool empty() const { return !everything && removed.empty() && added.empty(); }
};

SceneDiff diff_scenes(const GaussianScene& before, const GaussianScene& after);

// Whether a Gaussian of the diff can contribute to a pixel of `camera` under `settings`
// (near plane, blur).
bool diff_reaches_view(const GaussianScene& before, const GaussianScene& after, const SceneDiff& diff,
                       const Camera& camera, const RenderSettings& settings);

// The view of `after` made from `donor`, a view of the scene before the edit that the
// edit does not reach: render, depth, alpha and embedding reused; frame and votes
// recomputed for `after`'s Gaussian indices. Equal to what segment::build_view gives.
segment::SegmentView reuse_view(const segment::SegmentView& donor, const GaussianScene& after,
                                const segment::ViewOptions& options);

// The render settings segment::build_view uses for a view.
RenderSettings view_render_settings(const segment::ViewOptions& options);

}  // namespace isegman::server
