// Background seen through an object's gaps at nearly the object's depth: the floor inside a
// ring lying on it, a wall a few centimetres behind a plant's back leaves. SAM fills such
// gaps, and the depth layers (depth_layers.h) cannot cut them off because no empty depth
// range separates the background from the object there. What gives them away is that they
// continue the surface around the mask: the floor inside the ring lies on the plane of the
// floor outside it. Per mask pixel, the depth the surroundings' surface would have there is
// interpolated from the pixels just outside the mask; a Gaussian whose centre lies on or
// behind that surface is background for this view and its vote becomes neutral (the views
// where it is not seen through a gap judge it).
#pragma once

#include <cstdint>
#include <vector>

#include "core/camera.h"
#include "core/image.h"
#include "core/scene.h"
#include "segment/votes.h"

namespace isegman::segment {

struct BackgroundOptions {
  int skip = 2;               // pixels of the mask's outside border skipped (their depth blends both sides)
  int extent = 4;             // a sample's surface must go on smoothly for twice this many pixels further out
  int max_span = 0;           // longest run across the mask interpolated, pixels (0: no limit)
  int min_directions = 2;     // of the four lines (row, column, diagonals), this many must give an estimate
  double agreement = 0.01;    // ... agreeing within this relative inverse depth
  double tolerance = 0.01;    // a Gaussian this close (relative inverse depth) to the surface counts as on it
  // ... unless the clicked Gaussians lie within it, at least twice this far in front: then half
  // their (weighted median) offset (0 or >= tolerance: the fixed tolerance alone)
  double min_tolerance = 0.003;
  // Offsets are measured from where the surroundings' own Gaussians lie (their weighted
  // median offset from the rendered surface), and the tolerance follows their scatter
  // (surroundings_surface): the rendered depth blends nearer Gaussians in and lies ~1 % in
  // front of a clean wall's centres, so a thin object 2 cm in front of the wall looked on
  // it; a trained wall's Gaussians scatter about it. The tolerance is spread_scale x their
  // interquartile range, within [min_tolerance, tolerance]; 0: the rendered surface and the
  // fixed tolerance.
  double spread_scale = 2.0;
  int min_spread_samples = 20;  // fewer Gaussians centred there: the fixed tolerance
  // A flat Gaussian counts as lying in the surface only when its normal is within about 35
  // degrees of the surface's (|cos| >= this); 0: depth alone decides.
  double min_alignment = 0.8;
  double seed_radius = 3;     // pixels around a click whose Gaussians are the target
  // ... widened (doubling) up to this when none of them has a surface estimate (seed_radius: never)
  double max_seed_radius = 24;
  // A background hides what lies behind it: when more than this share of the weight the gate
  // would move lies over far_behind x the tolerance (before it is narrowed to the clicked
  // Gaussians) behind the estimate, and the clicked Gaussians do not lie clearly (as far) in
  // front of it, the estimate runs through the target (a pillar from the floor to the ceiling
  // around it) and nothing is moved (1: never). Behind a clearly nearer target (a fence) it
  // is what the gaps show.
  double max_far_behind = 1.0 / 3;
  double far_behind = 3;
  double occluder_margin = 0.03;  // outside pixels nearer than the target's near depth less this share are occluders
  // Mask pixels no line estimates take the plane the samples around the mask lie on, where
  // at least plane_min_share of them do (RANSAC, plane_trials triples) on three of its sides.
  bool plane = true;
  double plane_min_share = 0.5;
  int plane_trials = 200;
};

// The camera depth below which `share` of the votes' weight lies: the target's near side in
// the view (the background's samples must lie beyond it).
// `threads`: workers for the depths (0: every core); the result does not depend on it.
double near_depth(const GaussianScene& scene, const Camera& camera, const ViewVotes& votes, double share,
                  int threads = 1);

// The surroundings' inverse depth per pixel of mask > 0.5, 0 where there is no estimate.
// Along the row, the column and both diagonals through the pixel, the nearest usable pixels
// outside the mask on both sides (rendered: alpha > 0.5, `skip` pixels past the border, not
// nearer than `near_limit`, and at the same depth `extent` pixels further out) are interpolated linearly in inverse depth, which is exact
// for a plane; the estimate is the mean over the lines when at least min_directions of them
// give one and they agree. `threads` (0: every core) does not change the result.
Image background_inverse_depth(const Image& mask, const Image& depth, const Image& alpha, double near_limit,
                               const BackgroundOptions& options = {}, int threads = 1);

// Where the surroundings' Gaussians lie against the rendered surface: offset (relative
// inverse depth, > 0: in front) from which a view's Gaussians are judged, and the
// tolerance about it.
struct SurroundingsSurface {
  double offset = 0;
  double tolerance = -1;  // < 0: BackgroundOptions::tolerance
};

// The surroundings' surface in this view, from the Gaussians centred on the pixels just
// outside the mask (from skip to skip + 2 x extent pixels out, rendered, not nearer than
// near_limit): the weighted median of their offsets from the rendered surface there, and
// spread_scale x the offsets' weighted interquartile range within [min_tolerance, tolerance].
// The rendered surface and the fixed tolerance when fewer than min_spread_samples Gaussians
// are centred there or spread_scale is 0. `total`: the view's Gaussians with their weights
// (all its votes); of a list longer than 2^18 every k-th is read, k = its length / 2^18
// (rounded down). `threads` (0: every core) does not change the result.
// `index` (optional, surroundings_index of the same view and list): only the Gaussians
// centred in the cells around the mask are read; the result is the same.
struct SurroundingsIndex;
SurroundingsSurface surroundings_surface(const GaussianScene& scene, const Camera& camera, const Image& mask,
                                         const Image& depth, const Image& alpha, const ViewVotes& total,
                                         double near_limit, const BackgroundOptions& options = {}, int threads = 1,
                                         const SurroundingsIndex* index = nullptr);

// The Gaussians surroundings_surface reads of a view (every k-th of its votes, as there),
// filed by the cell of kCell x kCell pixels their centre projects to, so that a mask reads
// only the cells around it rather than a pass over the view's ~10^6 Gaussians. A view's
// Gaussians and camera do not change: built once per view (segment/views.cc).
struct SurroundingsIndex {
  static constexpr int kCell = 32;
  size_t votes = 0;  // the length of the list it was built from
  int width = 0, height = 0, grid_x = 0, grid_y = 0;
  std::vector<uint32_t> start;    // per cell (row-major) into `entries`, grid_x * grid_y + 1
  std::vector<uint32_t> entries;  // positions in the list, ascending within a cell
  size_t bytes() const { return (start.capacity() + entries.capacity()) * sizeof(uint32_t); }
};
SurroundingsIndex surroundings_index(const GaussianScene& scene, const Camera& camera, const ViewVotes& total);

// What is known of the target in the view: the clicked pixels and the current selection
// (null before the first vote).
struct BackgroundTarget {
  struct Seed {
    double x = 0, y = 0;  // continuous pixel coordinates (core/click.h)
    double depth = 0;     // the view's rendered depth there (0: not known)
  };
  std::vector<Seed> seeds;
  const std::vector<bool>* selection = nullptr;
};

// Moves from `positive` to `neutral` (kept ascending) the Gaussians whose centre projects
// onto a pixel with a background estimate and lies on or behind that surface. Nothing is
// moved when that would take the target itself: most of the weight of the Gaussians centred
// within seed_radius of a click (the object is not told from the surroundings by depth
// here), or, where the view has no click, more than half of the selection's weight in the
// mask. Where no Gaussian centred within seed_radius of a click has an estimate, the nearest
// that have one (out to max_seed_radius) stand for the clicked ones, and nothing is moved
// when they lie on or behind the surface (weighted median offset within the tolerance).
// Where a click has no Gaussian centred within seed_radius (a coarse target of a few
// large Gaussians), or none with an estimate out to max_seed_radius, its pixel tells
// instead: nothing is moved when its rendered depth lies on or behind the surroundings'
// rendered surface there (within the tolerance). Nor when
// most of what would be moved lies far behind the surface and the clicked Gaussians do not
// lie clearly in front of it (max_far_behind). Returns the number moved.
// `threads` (0: every core) does not change the result.
// `surface`: where the surroundings' Gaussians lie (surroundings_surface; default: on the
// rendered surface, within the fixed tolerance).
size_t gate_background(const GaussianScene& scene, const Camera& camera, const Image& background,
                       const BackgroundTarget& target, ViewVotes& positive, ViewVotes& neutral,
                       const BackgroundOptions& options = {}, int threads = 1, const SurroundingsSurface& surface = {});

}  // namespace isegman::segment
