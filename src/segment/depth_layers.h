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
  // Local layers (once a selection exists): the mask is cut into square regions of this
  // many pixels and each region is layered on its own, because one surface seen at a slant
  // (a wall, the ground) spans the whole depth range of the view and fills the gap a global
  // histogram needs, while locally the trellis bar is always in front of the wall. 0: global.
  int region = 32;
  double keep_share = 0.3;    // a local layer is kept when this share of it is selected
  double margin = 0.05;       // relative depth margin around the selection's local range
  int reach = 2;              // regions farther than this from the selection's stay neutral
  // A Gaussian occupies the depth range centre +- extent_sigmas standard deviations along the
  // view axis, not only its centre's bin: a coarse surface of few large Gaussians (a far
  // pillar in a real capture) has empty bins between its centres that are no real gap.
  // Only Gaussians holding at least empty_share of the weight fill bins this way. 0: centres.
  double extent_sigmas = 1.0;
};

struct DepthLayer {
  double near = 0, far = 0;  // camera-space depth range
  double weight = 0;         // share of the mask's blending weight
};

// Layers of (depth, weight) samples, near to far. `extent` (optional, one per sample): the
// standard deviation of the sample's depth (see extent_sigmas). The weights are whole
// numbers (fixed-point vote units): `threads` (0: every core) then changes nothing but speed.
std::vector<DepthLayer> depth_layers(const std::vector<float>& depth, const std::vector<double>& weight,
                                     const DepthLayerOptions& options = {},
                                     const std::vector<float>* extent = nullptr, int threads = 1);

// Standard deviation of Gaussian g's camera-space depth (its 3D covariance along the view axis).
float depth_extent(const GaussianScene& scene, const Camera& camera, size_t g);

struct GateReport {
  int layers = 0;            // layers the mask's content splits into
  DepthLayer kept;           // the target's layer
  double gated_share = 0;    // share of the mask's weight made neutral
  bool local = false;        // decided per region (local layers) rather than globally
};

// Keeps in `positive` only the Gaussians of the target's layer and moves the others into
// `neutral`. Without a selection seen through the mask (the first view), the target's
// layer is the global layer nearest to any of `seed_depths`. With one, each region keeps
// its local layers that hold the selection (the one holding most of it, and any that is
// at least keep_share selected); a region the selection does not reach keeps the local
// layers within the depth range (+- margin) kept in the nearest region it does reach.
// `threads` (0: every core) does not change the result.
GateReport gate_by_depth(const GaussianScene& scene, const Camera& camera, ViewVotes& positive, ViewVotes& neutral,
                         const std::vector<double>& seed_depths, const std::vector<bool>* selection,
                         const DepthLayerOptions& options = {}, int threads = 1);

}  // namespace isegman::segment
