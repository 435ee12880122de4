// segment_from_prompts with "auto" voting views on the synthetic scene (real SAM; skips
// when the model files are absent).
#include "segment/pipeline.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "app/demo_scene.h"
#include "segment/propagation.h"
#include "segment/test_sam.h"

namespace fs = std::filesystem;

namespace isegman::segment {
namespace {

using testing::sam_or_null;

TEST(PipelineAutoViews, ChoosesKViewsThatSeeTheClickedPoint) {
  auto sam = sam_or_null();
  if (!sam) GTEST_SKIP() << "SAM model files absent";
  DemoSceneOptions opt;
  opt.width = 480;
  opt.height = 360;
  DemoScene demo = make_demo_scene(opt);  // 24 cameras
  int cam = -1;
  double x = 0, y = 0;
  ASSERT_TRUE(demo_click(demo, 1, cam, x, y));
  const Click click = pixel_centre_click(x, y, 1);
  const ViewOptions vo = testing::view_options();
  PipelineTimings t;
  auto s = segment_from_prompts(demo.bundle, cam, {click}, sam, SessionOptions(), vo, "auto:6", &t);
  ASSERT_EQ(s->views().size(), 6u);
  EXPECT_EQ(t.views, 6);
  ASSERT_GE(view_of_camera(*s, cam), 0);
  // Every chosen view sees the clicked surface point.
  const SegmentView& clicked = s->views()[size_t(view_of_camera(*s, cam))];
  Vec3 X;
  ASSERT_TRUE(surface_point(clicked, click.x, click.y, 0.5, X));
  for (const SegmentView& v : s->views()) {
    double u, w, z;
    ASSERT_TRUE(v.camera.project(X, u, w, &z)) << v.name;
    EXPECT_TRUE(u >= 0 && w >= 0 && u < v.camera.width && w < v.camera.height) << v.name;
    EXPECT_TRUE(std::is_sorted(s->views().begin(), s->views().end(),
                               [](const SegmentView& a, const SegmentView& b) { return a.camera_index < b.camera_index; }));
  }
  // The selection is the clicked object.
  size_t inter = 0, uni = 0;
  for (size_t i = 0; i < demo.labels.size(); ++i) {
    const bool truth = demo.labels[i] == 1, sel = s->selection()[i];
    inter += truth && sel;
    uni += truth || sel;
  }
  const double iou = uni ? double(inter) / double(uni) : 0;
  std::printf("auto:6 views, Gaussian IoU %.3f\n", iou);
  EXPECT_GT(iou, 0.5);
  // "auto" with no more cameras than K keeps them all.
  EXPECT_EQ(sample_views(demo.bundle.cameras, "auto:24").size(), 24u);
}

}  // namespace
}  // namespace isegman::segment
