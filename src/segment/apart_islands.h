// What the clicked view leaves out and 3D sets apart. Most views' SAM masks may take in a
// neighbour standing beside the clicked object (a playpen beside a climbing triangle, both of
// wood-pale bars): they vote for it, and the clicked view, whose mask is the object alone,
// leaves it open as part or whole (votes.h, WholeRule), so it is selected. The clicked view
// is the one the user looked at, and 3D tells a neighbour from the rest of the object: the
// rest of a chair touches its clicked back, the playpen stands apart from the triangle.
// A set of selected Gaussians joined by chains of touching Gaussians (whole_islands.h) that
// holds nothing a positive click's pixel shows, while a clicked view sees a real share of it
// outside its mask, leaves the selection. So does one that a clicked view sees behind the
// gaps of something nearer (a vase behind a clicked trellis: SAM's mask of a lattice takes in
// what shows between its bars, in every view) when it is an object's worth of Gaussians, and
// one that a clicked view sees behind the clicked surface (a bookcase SAM merges with the
// plant standing before it) while the set joined to the click is an object's worth itself.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/camera.h"
#include "core/scene.h"
#include "segment/votes.h"
#include "segment/whole_islands.h"

namespace isegman::segment {

struct ApartOptions {
  bool enabled = false;
  // A Gaussian is inside a clicked view's mask when the mask holds at least this share of
  // what it blends in the view, and seen outside it when the mask holds at most
  // outside_share of it (and it blends at least the vote's minimum weight there).
  double inside_share = 0.5;
  double outside_share = 0.1;
  // A set leaves only when a clicked view sees at least this share of its Gaussians outside
  // its mask: a set the clicked view barely glimpses (a part only the other views show) is
  // the other views' to decide.
  double min_seen_share = 0.25;
  // Gaussians larger than this many times the selection's median scale neither link nor
  // leave: a few broad flat Gaussians of a floor the selection took join all that stands on it.
  double max_link_scale = 4;
  // ... but one that touches what leaves and nothing that stays leaves with it (the floor's
  // broad Gaussians under a neighbour: the climbing triangle 65.3 -> 75.3).
  bool broad_follow = true;
  // A set leaves only when it holds at least this share of as many selected Gaussians as
  // the clicked views' masks hold: a neighbour of the object's own kind of size. A small set
  // apart may be a part of the object that touches nothing selected (a lamp's stem reaching
  // up into its shade, 460 Gaussians against the shade's 2,000).
  double min_size_share = 0.5;
  // Seen through the object's gaps: a vase standing behind a clicked trellis, a ball behind a
  // clicked fence. Every view's mask of the lattice takes in what shows between its bars, and
  // the depth layers keep it when it stands close behind. In a clicked view a selected
  // Gaussian lies behind when, within flank_share of the longer image side on both sides
  // (along a row or a column), selected Gaussians seen there are nearer than it by
  // behind_gap (relative depth); centres gathered in cells of cell_share.
  bool behind = true;
  double cell_share = 0.01;
  double flank_share = 0.03;
  double behind_gap = 0.03;
  // A set apart leaves when a clicked view sees at least this share of what it sees of it
  // behind, and it holds at least behind_size_share as many Gaussians as the rest of the
  // selection: an object of its own. A leaf cluster or a rib behind the others is a part
  // (25-332 Gaussians seen 50-100 % behind, 0.08-0.09 x the rest of the shrub or skeleton);
  // the vase behind the trellis holds 1.1 x, the ball behind the fence 1.8 x.
  double min_behind_share = 0.6;
  double behind_size_share = 0.25;
  // A selected Gaussian a clicked view sees deeper than the clicked surface (the median
  // depth of what the clicks' pixels show) by this share also lies behind (0 = off), where
  // the set joined to the clicks holds min_click_set_share of what the clicked masks hold.
  double behind_click_gap = 0.05;
  double min_click_set_share = 0.2;
  // A set mostly seen behind but too small to leave on its own leaves, once a set has, when
  // it lies nearer to what leaves than to what stays (pieces of a bookcase that the plant's
  // leaves part), measured in a grid of nearest_cells cells along the selection's longest side.
  bool nearest_follow = true;
  int nearest_cells = 64;
};

// One view with a positive click: the votes of its mask before any gate (the pixels the user's
// mask covers) and its all-pixel votes. Both ascending by Gaussian, as the rasteriser's
// contribution lists are.
struct ClickedViewVotes {
  const ViewVotes* inside = nullptr;
  const ViewVotes* total = nullptr;
  const Camera* camera = nullptr;  // the view's camera: where its Gaussians lie (behind)
};

struct ApartReport {
  size_t removed = 0;  // Gaussians that left the selection
  int islands = 0;     // sets that left
};

// Removes from `selection` every set of selected Gaussians, joined by chains of touching
// selected Gaussians (`link`, as whole islands; Gaussians over max_link_scale x the median
// link nothing, and with broad_follow leave when they touch only what leaves), that holds none of `click_gaussians` (what the positive clicks'
// pixels show: negative_islands.h, selected_at_pixel), of which some clicked view sees at
// least min_seen_share of the Gaussians outside its mask, and which holds at least
// min_size_share as many Gaussians as the clicked masks; or of which a clicked view with a
// camera sees min_behind_share of what it sees behind (and min_seen_share of the set), and
// which holds behind_size_share as many Gaussians as the rest of the selection; behind is
// behind the gaps of nearer selected Gaussians, or behind_click_gap deeper than the clicked
// surface where the set joined to the clicks holds min_click_set_share of in_masks. With
// nearest_follow, once a set has left, a set seen behind that way but too small to leave alone
// leaves when it lies nearer to what leaves than to the set joined to the clicks. `min_weight`: the weight (in pixels)
// a Gaussian must blend in a view to count as seen there. Nothing leaves without clicked
// views or click Gaussians.
ApartReport drop_apart_islands(std::vector<bool>& selection, const GaussianScene& scene,
                               const std::vector<ClickedViewVotes>& clicked,
                               const std::vector<uint32_t>& click_gaussians, double min_weight,
                               const ApartOptions& options, const IslandOptions& link);

}  // namespace isegman::segment
