// Real data: clicks on the fern and dtu24 fixtures (../shared/fixtures), with the real SAM.
// Skips when the fixtures or the model files are absent.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "core/click.h"
#include "io/scene_loader.h"
#include "render/rasterizer.h"
#include "segment/evaluation.h"
#include "segment/pipeline.h"
#include "segment/see_through.h"
#include "segment/test_sam.h"

namespace fs = std::filesystem;

namespace isegman::segment {
namespace {

using testing::sam_or_null;
using testing::view_options;

// Mean alpha of the selection rendered alone over a box of the camera's image.
double mean_alpha(const Image& alpha, int x0, int y0, int x1, int y1) {
  double sum = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) sum += alpha.at(x, y);
  return sum / double((x1 - x0) * (y1 - y0));
}

// The fern scene (loaded once for all its tests) and SAM; each test is skipped with a message
// when either is absent.
class FernFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(scene_dir())) GTEST_SKIP() << "fixtures not found at " << scene_dir() << "; skipping real-data test";
    if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  }
  static fs::path scene_dir() { return fs::path(ISEGMAN_FIXTURES_DIR) / "fern/scene"; }
  static const SceneBundle& fern() {
    static const SceneBundle b = load_scene(scene_dir().string());
    return b;
  }
  // The index of the camera named `name` (-1: none).
  static int camera(const std::string& name) {
    const Camera* cam = find_camera(fern().cameras, name);
    return cam ? int(cam - fern().cameras.data()) : -1;
  }
};

TEST_F(FernFixture, OneClickOnThePlantLeavesOutWhatShowsBehindItsFronds) {
  const SceneBundle& b = fern();
  const int c = camera("image010");
  ASSERT_GE(c, 0);
  const Camera* cam = &b.cameras[size_t(c)];
  // Boxes of image010 (504x378): a grey panel under the fronds, the window post right of the
  // trunk, the lit ledge at the left (all behind the plant) and the fronds with their gaps.
  struct Figures {
    size_t selected = 0;
    double panel = 0, post = 0, ledge = 0, fronds = 0;
  };
  auto click = [&](const SessionOptions& so) {
    auto session = segment_from_prompts(b, c, {pixel_centre_click(250, 200, 1)}, sam_or_null(), so, view_options(), "auto");
    const std::vector<bool>& sel = session->selection();
    Figures f;
    for (bool s : sel) f.selected += s;
    const Image alpha = render(b.gaussians.subset(sel), *cam, RenderSettings()).alpha;
    f.panel = mean_alpha(alpha, 272, 215, 312, 258);
    f.post = mean_alpha(alpha, 318, 215, 345, 262);
    f.ledge = mean_alpha(alpha, 5, 150, 70, 205);
    f.fronds = mean_alpha(alpha, 180, 60, 360, 170);
    return f;
  };
  SessionOptions kept;
  kept.beyond_part.band = kept.beyond_part.whole = false;
  const Figures now = click(SessionOptions()), before = click(kept);
  for (const auto& [name, f] : {std::pair{"default", now}, std::pair{"--keep-beyond-part", before}})
    std::printf("[ fern plant ] %s: %zu Gaussians; alpha over panel %.2f, post %.2f, ledge %.2f, fronds %.2f\n", name,
                f.selected, f.panel, f.post, f.ledge, f.fronds);
  // Without the rule the window post and the ledge are nearly fully selected: what the check catches.
  EXPECT_GT(before.post, 0.8);
  EXPECT_GT(before.ledge, 0.6);
  EXPECT_LT(now.post, 0.5);
  EXPECT_LT(now.ledge, 0.45);
  EXPECT_LT(now.panel, 0.5);
  EXPECT_GT(now.fronds, 0.85);  // the plant itself stays
}

// image010 (300, 170) lands on an inner frond: the fronds nearer than it, flanked by it,
// are all in SAM's mask at the click. They are no enclosure around something smaller (a cone
// in a cage): they touch the clicked frond in 3D (14 % of the Gaussians at its depth around
// the click), and rendered without them SAM there masks 45 % of that mask (the rest of the
// plant), above the quarter an enclosure leaves. Either test alone keeps the click in its
// view; SAM's alone at a half would not.
TEST_F(FernFixture, AClickAmongThePlantsFrondsDoesNotSeeThroughThem) {
  const int c = camera("image010");
  ASSERT_GE(c, 0);
  struct Figures {
    size_t selected = 0;
    int peeled = 0;
  };
  auto click = [&](const SessionOptions& so) {
    auto session =
        segment_from_prompts(fern(), c, {pixel_centre_click(300, 170, 1)}, sam_or_null(), so, view_options(), "auto");
    Figures f;
    for (const SegmentView& v : session->views()) f.peeled += v.name.find("_through") != std::string::npos;
    for (bool s : session->selection()) f.selected += s;
    return f;
  };
  // No 3D test; an enclosure below half of the mask without it, and with it.
  SessionOptions sam_alone, at_half, at_half_3d;
  sam_alone.see_through_options.max_enclosure_touch = at_half.see_through_options.max_enclosure_touch = 1;
  at_half.see_through_options.min_peeled_share = at_half_3d.see_through_options.min_peeled_share = 0.5;
  const Figures ours = click(SessionOptions()), by_sam = click(sam_alone), half = click(at_half),
                half_3d = click(at_half_3d);
  std::printf("[ fern plant ] click (300, 170): %zu Gaussians, %d peeled view(s); by SAM alone: %zu, %d; at half: %zu, "
              "%d; at half with the 3D test: %zu, %d\n",
              ours.selected, ours.peeled, by_sam.selected, by_sam.peeled, half.selected, half.peeled, half_3d.selected,
              half_3d.peeled);
  EXPECT_EQ(ours.peeled, 0);
  EXPECT_EQ(by_sam.peeled, 0);
  EXPECT_EQ(half.peeled, 1);  // the margin SAM's test has here
  EXPECT_EQ(half_3d.peeled, 0);  // the 3D test's
  EXPECT_GT(ours.selected, 30000u);  // the plant (44,111), not an inner frond alone
}

// Clicks drawn on the far pillar at the frame's edge (`isegman ablation --clicks-per-task 6
// --only fern_pillar` prints the draws), scored on the task's hand-made masks. The pillar is
// ~130 coarse Gaussians scattered a few per cent in depth, crossed by fronds far in front.
// At (465, 219) the clicked pixel gives 0.44 of its weight to the pillar's own nearer
// Gaussians, flanked by its farther ones; at (475, 209) the pixel is clear, but the window's
// flanked pixels include those nearer Gaussians. Either way see-through cut among them and
// peeled the pillar's front away (IoU 0.02 and 0.585); the front-weight guard stops the
// first peel, and the cut at the widest depth gap (behind the fronds) mends the second.
// The pillar stands from the floor to the ceiling around it, so the surroundings' surface
// interpolated across its mask runs through it: at (465, 219) and (465, 158) the background
// gate set aside the pillar's Gaussians behind that surface (IoU 0.680 each) until it stood
// aside where most of what it would move lies far behind the surface.
TEST_F(FernFixture, ClicksOnTheFarPillarsCoarseSurfaceDoNotPeelItAway) {
  const EvalTask task = read_task(std::string(ISEGMAN_SOURCE_DIR) + "/eval/fixture_tasks/fern_pillar", ISEGMAN_FIXTURES_DIR);
  ASSERT_EQ(fs::canonical(task.scene_dir), fs::canonical(scene_dir()));
  const SceneBundle& b = fern();
  const int c = camera(task.view);
  ASSERT_GE(c, 0);
  auto score = [&](double x, double y) {
    auto session = segment_from_prompts(b, c, {pixel_centre_click(x, y, 1)}, sam_or_null(), SessionOptions(),
                                        view_options(), "auto");
    return score_task(task, b, session->selection()).iou;
  };
  const double veiled = score(465, 219), clear = score(475, 209), upper = score(465, 158);
  std::printf("[ fern pillar ] click (465, 219): IoU %.3f; (475, 209): %.3f; (465, 158): %.3f\n", veiled, clear,
              upper);
  EXPECT_GT(veiled, 0.75);
  EXPECT_GT(clear, 0.75);
  EXPECT_GT(upper, 0.75);
}

// dtu24's roof box, which the short training left half transparent, clicked low on its front
// face (153, 80 in 000024, one of the ablation's drawn clicks): there the box lies 2 % before
// the wall seen through it, flanked by it, so it looked like bars in front of the clicked wall.
// Cut away, it took the roof with it, SAM's answer at the click in that render was 87 % of the
// view (the building's inside), and the selection was 18,021 Gaussians (IoU 9.4).
TEST(Dtu24Fixture, AClickOnTheHalfTransparentRoofBoxDoesNotCutTheRoofAway) {
  const fs::path root = ISEGMAN_FIXTURES_DIR;
  if (!fs::exists(root / "dtu24/scene")) GTEST_SKIP() << "fixtures not found at " << root << "; skipping real-data test";
  if (!sam_or_null()) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  const EvalTask task = read_task(std::string(ISEGMAN_SOURCE_DIR) + "/eval/fixture_tasks/dtu24_roofbox", root.string());
  SceneBundle b = load_scene(task.scene_dir);
  const Camera* cam = find_camera(b.cameras, task.view);
  ASSERT_NE(cam, nullptr);
  auto run = [&](double max_share) {
    SessionOptions so;
    so.see_through_options.max_peeled_view_share = max_share;
    auto session = segment_from_prompts(b, int(cam - b.cameras.data()), {pixel_centre_click(153, 80, 1)}, sam_or_null(),
                                        so, view_options(), "auto");
    return score_task(task, b, session->selection());
  };
  const TaskResult guarded = run(SeeThroughOptions{}.max_peeled_view_share), cut = run(1.0);
  std::printf("[ roof box ] click (153, 80): IoU %.3f (%zu Gaussians); with the cut allowed %.3f (%zu)\n", guarded.iou,
              guarded.selected, cut.iou, cut.selected);
  EXPECT_GT(guarded.iou, 0.5);
  EXPECT_LT(guarded.selected, 2000u);
  EXPECT_LT(cut.iou, 0.3);  // what the guard is for: without it the cut still happens here
}

}  // namespace
}  // namespace isegman::segment
