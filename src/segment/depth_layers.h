// Depth layers of what a SAM mask shows: a mask drawn around foliage, a trellis or a
// fence also covers the wall seen through their gaps, and every Gaussian of that wall
// would get the mask's full vote. The Gaussians a mask's pixels blend are split into
// layers along the view's depth axis (separated by empty depth ranges); only the layer of
// the target (the one holding the click, or most of the current selection) keeps its
// votes. The others become neutral for this view: neither positive nor total weight, so
// a part of the object that is only seen through a gap here is judged by other views.
#pragma once

#include <vector>

#include "core/camera.h"
#include "core/scene.h"
#include "segment/votes.h"

namespace isegman::segment {

struct DepthLayerOptions {
  double bin = 0.01;          // histogram bin, relative depth (log scale)
  double min_gap = 0.04;      // empty depth range that separates layers, relative
  double empty_share = 0.002; // a bin with less of the mask's weight counts as empty
};

struct DepthLayer {
  double near = 0, far = 0;  // camera-space depth range
  double weight = 0;         // share of the mask's blending weight
};

// Layers of (depth, weight) samples, near to far.
std::vector<DepthLayer> depth_layers(const std::vector<float>& depth, const std::vector<double>& weight,
                                     const DepthLayerOptions& options = {});

struct GateReport {
  int layers = 0;            // layers the mask's content splits into
  DepthLayer kept;           // the target's layer
  double gated_share = 0;    // share of the mask's weight made neutral
};

// Keeps in `positive` only the Gaussians of the target's layer and moves the others into
// `neutral`. The target's layer is the one holding most of `selection`'s weight when the
// selection has weight in the mask, else the one nearest to any of `seed_depths`.
GateReport gate_by_depth(const GaussianScene& scene, const Camera& camera, ViewVotes& positive, ViewVotes& neutral,
                         const std::vector<double>& seed_depths, const std::vector<bool>* selection,
                         const DepthLayerOptions& options = {});

}  // namespace isegman::segment
