#include "server/scene_name.h"

#include <gtest/gtest.h>

namespace isegman::server {
namespace {

TEST(SceneName, TrainerFolderFileStemOrTheFolderAboveAGenericName) {
  EXPECT_EQ(scene_name("/data/garden/point_cloud/iteration_30000/point_cloud.ply"), "garden");
  // The fixtures and the demo keep the trainer output in a folder called "scene".
  EXPECT_EQ(scene_name("/work/shared/fixtures/fern/scene/point_cloud/iteration_7000/point_cloud.ply"), "fern");
  EXPECT_EQ(scene_name("/tmp/isegman-demo/scene/point_cloud/iteration_1/point_cloud.ply"), "isegman-demo");
  EXPECT_EQ(scene_name("/data/bicycle.splat"), "bicycle");
  EXPECT_EQ(scene_name("/data/room/output/scene.ply"), "room");
  EXPECT_EQ(scene_name("/data/kitchen/point_cloud.ply"), "kitchen");
  EXPECT_EQ(scene_name("relative/truck.compressed.ply"), "truck.compressed");
  EXPECT_EQ(scene_name(""), "scene");
  EXPECT_EQ(scene_name("/scene.ply"), "scene");
}

}  // namespace
}  // namespace isegman::server
