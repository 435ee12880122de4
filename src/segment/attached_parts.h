// Attached parts: what a minority of the views masks with the object, where it is attached.
// SAM often masks a compound object differently per view: the broom's handle alone in most
// views and the handle with its bristles in a few, a kettle without and with its spout, a
// bottle without and with its cap. The part the minority adds gets their positive votes and
// the others' votes against, so its share stays well under tau and the vote keeps only the
// intersection. The part/whole rule (votes.h) helps only where the other views' own larger
// candidates hold it. Here a Gaussian whose evidence a sizeable minority of the views holds
// in their masks (P / (A - W) above min_share) joins the selection when a chain of such
// Gaussians, each touching the next, attaches it to the selection.
//
// Two kinds of Gaussian never join: what several views set aside from the target (their
// depth layers: another layer than the target's; their background gate: the surface behind
// it, such as the wall seen through a wheel's spokes, which SAM's disk masks hold), and a neighbour
// that whole islands set apart (whole_islands.h: the plant beside the clicked shrub), with
// what attaches to it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/centre_index.h"
#include "core/scene.h"
#include "segment/votes.h"

namespace isegman::segment {

struct AttachedPartsOptions {
  bool enabled = false;
  // P / (A - W) a candidate needs: 0.35 takes a part 7 of 20 views mask (the broom's
  // bristles: 92.8 here, 86.1 with 0.4); P / A must also exceed min_plain_share.
  double min_share = 0.35;
  double min_plain_share = 0.2;
  // A set whole islands dropped is a neighbour (and repels what attaches to it) when it holds
  // at least this share of the selection's size; fewer are stray specks.
  double min_neighbour_share = 0.05;
  double link_sigmas = 1.0;  // the touch rule of whole_islands.h
  // Views that must set a Gaussian aside to keep it out. One view's gate is wrong now and
  // then: at 960x720 the broom's bristles, which the minority that masks them would add,
  // scored 80.2 when one view kept them out, 86.0 with two (90.6 with three, which also let
  // more of the floor join the rug).
  int min_set_aside_views = 2;
  // A view whose mask lies less than this share on the selection (it takes in far more than
  // the object: the shelf of books beside a clicked globe, a mask nine times the globe's)
  // does not vouch for a part: its votes do not count in P here. The broom's whole-broom
  // views lie half on its handle.
  double min_view_overlap = 0.25;
};

// Adds to `selection` the attached parts. `candidates`: every Gaussian with a positive vote
// (ascending; outside them P = 0). `set_aside`: per Gaussian, the number of views whose
// depth layers or background gate set it aside (may be empty). `apart`: the Gaussians whole
// islands dropped (ascending). `excluded`: one flag per Gaussian never to select (may be
// empty). `index` is built over `scene`. Returns the number added. `threads`: for the
// searches of what touches the selection (0 = all cores; the same result). `wide` (optional):
// the positive votes of views whose masks lie mostly off the selection, taken from P here.
size_t add_attached_parts(std::vector<bool>& selection, const VoteAccumulator& votes, double min_total,
                          const std::vector<uint32_t>& candidates, const std::vector<uint8_t>& set_aside,
                          const std::vector<uint32_t>& apart, const std::vector<bool>& excluded,
                          const GaussianScene& scene, const CentreIndex& index, const AttachedPartsOptions& options,
                          int threads = 1, const std::vector<ViewVotes>* wide = nullptr);

}  // namespace isegman::segment
