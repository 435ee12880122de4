#include "io/llff.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/image.h"
#include "io/camera_test_util.h"
#include "io/image_io.h"

namespace isegman {
namespace {

using testing::TempDir;
using testing::expect_error;

// One LLFF row from the columns [down, right, back, centre] and (h, w, f).
std::vector<double> row(Vec3 down, Vec3 right, Vec3 back, Vec3 centre, double h, double w, double f,
                        double near_b = 1, double far_b = 10) {
  Vec3 cols[5] = {down, right, back, centre, {h, w, f}};
  std::vector<double> r;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 5; ++k) r.push_back(cols[k][i]);
  r.push_back(near_b);
  r.push_back(far_b);
  return r;
}

NpyArray array_of(const std::vector<std::vector<double>>& rows) {
  NpyArray a;
  a.dtype = "<f8";
  a.shape = {rows.size(), 17};
  for (const auto& r : rows) a.data.insert(a.data.end(), r.begin(), r.end());
  return a;
}

TEST(Llff, AxisOrderIsDownRightBack) {
  // A camera at (1, 2, 3) whose right is world +x, down world +y and forward world +z:
  // the OpenCV identity rotation. LLFF stores it as [down, right, back] = [+y, +x, -z].
  NpyArray a = array_of({row({0, 1, 0}, {1, 0, 0}, {0, 0, -1}, {1, 2, 3}, 300, 400, 500)});
  std::vector<Camera> cams = llff_to_cameras(a, "p.npy", {});
  ASSERT_EQ(cams.size(), 1u);
  const Camera& c = cams[0];
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(c.R.m[r][k], r == k ? 1 : 0, 1e-15);
  EXPECT_NEAR(c.center().x, 1, 1e-15);
  EXPECT_NEAR(c.center().z, 3, 1e-15);
  EXPECT_EQ(c.name, "000");
  EXPECT_EQ(c.width, 400);
  EXPECT_EQ(c.height, 300);
  EXPECT_DOUBLE_EQ(c.cx, 200);
  EXPECT_DOUBLE_EQ(c.cy, 150);
  double u, v;
  // 5 ahead, 1 to the right and 2 down of the camera.
  ASSERT_TRUE(c.project({2, 4, 8}, u, v));
  EXPECT_NEAR(u, 200 + 500 * 1.0 / 5, 1e-12);
  EXPECT_NEAR(v, 150 + 500 * 2.0 / 5, 1e-12);
}

TEST(Llff, RotatedCameraProjectsAlongItsAxes) {
  // Forward = world -x (back = +x), right = world -z, down = world -y: a point at 4 along
  // -x lies on the optical axis.
  NpyArray a = array_of({row({0, -1, 0}, {0, 0, -1}, {1, 0, 0}, {0, 0, 0}, 100, 100, 50)});
  Camera c = llff_to_cameras(a, "p.npy", {})[0];
  double u, v;
  ASSERT_TRUE(c.project({-4, 0, 0}, u, v));
  EXPECT_NEAR(u, 50, 1e-12);
  EXPECT_NEAR(v, 50, 1e-12);
  ASSERT_TRUE(c.project({-4, 0, -2}, u, v));  // to the right
  EXPECT_NEAR(u, 50 + 50 * 2.0 / 4, 1e-12);
  ASSERT_TRUE(c.project({-4, 2, 0}, u, v));  // up = above the centre
  EXPECT_NEAR(v, 50 - 50 * 2.0 / 4, 1e-12);
  EXPECT_FALSE(c.project({4, 0, 0}, u, v));  // behind
  EXPECT_GT(c.R.det(), 0);
}

TEST(Llff, WriterRoundTripsAndRefusesWhatLlffCannotHold) {
  std::vector<Camera> rig = testing::make_rig();
  std::vector<double> rows = cameras_to_llff(rig, 0.5, 20);
  NpyArray a = array_of({});
  a.shape = {rig.size(), 17};
  a.data = rows;
  std::vector<std::pair<double, double>> bounds;
  std::vector<Camera> back = llff_to_cameras(a, "p.npy", {"x/cam_a.png", "x/cam_b.png", "x/cam_c.png"}, &bounds);
  testing::expect_same_cameras(rig, back);
  EXPECT_EQ(back[1].image_path, "x/cam_b.png");
  ASSERT_EQ(bounds.size(), 3u);
  EXPECT_EQ(bounds[2], std::make_pair(0.5, 20.0));
  rig[0].fy *= 1.1;
  expect_error([&] { cameras_to_llff(rig, 1, 2); }, {"cam_a", "fx != fy"});
}

TEST(Llff, ImagesFolderNamesAndDownscaledSize) {
  TempDir dir;
  std::vector<Camera> rig = testing::make_rig();  // 640 x 480
  write_llff(dir / "poses_bounds.npy", rig, 1, 10);
  // No images folder: numbered names.
  std::vector<Camera> cams = read_llff(dir / "poses_bounds.npy");
  EXPECT_EQ(cams[2].name, "002");
  // images_4 with three 160x120 photos (sorted names), another folder ignored.
  dir.mkdir("images_4");
  dir.mkdir("images_8x");
  Image img(160, 120, 3, 0.5f);
  for (const char* n : {"c.png", "a.png", "b.png"}) write_png(dir / ("images_4/" + std::string(n)), img);
  std::vector<std::string> notes;
  cams = read_llff(dir / "poses_bounds.npy", {}, &notes);
  ASSERT_EQ(cams.size(), 3u);
  EXPECT_EQ(cams[0].name, "a");
  EXPECT_EQ(cams[2].name, "c");
  EXPECT_EQ(cams[1].image_path, dir / "images_4/b.png");
  EXPECT_EQ(cams[1].width, 160);
  EXPECT_EQ(cams[1].height, 120);
  EXPECT_NEAR(cams[1].fx, rig[1].fx / 4, 1e-9);
  EXPECT_NEAR(cams[1].cx, 80, 1e-12);
  ASSERT_GE(notes.size(), 1u);
  EXPECT_NE(notes[0].find("scaled"), std::string::npos) << notes[0];
  // An explicit target width wins over the photos.
  LlffOptions opt;
  opt.target_width = 80;
  cams = read_llff(dir / "poses_bounds.npy", opt);
  EXPECT_EQ(cams[0].width, 80);
  EXPECT_EQ(cams[0].height, 60);
  EXPECT_NEAR(cams[0].fy, rig[0].fy / 8, 1e-9);
  // images/ is preferred to images_N; a count mismatch falls back to numbers with a note.
  dir.mkdir("images");
  write_png(dir / "images/only.png", img);
  notes.clear();
  cams = read_llff(dir / "poses_bounds.npy", {}, &notes);
  EXPECT_EQ(cams[0].name, "000");
  EXPECT_EQ(cams[0].width, 640);
  ASSERT_GE(notes.size(), 1u);
  EXPECT_NE(notes[0].find("1 images for 3 poses"), std::string::npos) << notes[0];
}

TEST(Llff, InvalidArraysAreRefused) {
  auto good = row({0, 1, 0}, {1, 0, 0}, {0, 0, -1}, {0, 0, 0}, 300, 400, 500);
  NpyArray a = array_of({good});
  a.shape = {1, 15};
  a.data.resize(15);
  expect_error([&] { llff_to_cameras(a, "p.npy", {}); }, {"p.npy", "N x 17", "(1, 15)"});
  auto bad = good;
  bad[7] = std::nan("");
  expect_error([&] { llff_to_cameras(array_of({good, bad}), "p.npy", {}); }, {"row 1", "non-finite"});
  bad = good;
  bad[4] = 0;  // height
  expect_error([&] { llff_to_cameras(array_of({bad}), "p.npy", {}); }, {"image height"});
  bad = good;
  bad[9] = 400.5;  // width
  expect_error([&] { llff_to_cameras(array_of({bad}), "p.npy", {}); }, {"image width"});
  bad = good;
  bad[14] = -5;  // focal
  expect_error([&] { llff_to_cameras(array_of({bad}), "p.npy", {}); }, {"focal"});
  bad = good;
  bad[0] = 2;  // not a rotation
  expect_error([&] { llff_to_cameras(array_of({bad}), "p.npy", {}); }, {"orthonormal"});
  bad = good;
  bad[16] = 0.5;  // far < near
  expect_error([&] { llff_to_cameras(array_of({bad}), "p.npy", {}); }, {"depth bounds"});
  a = array_of({});
  a.shape = {0, 17};
  expect_error([&] { llff_to_cameras(a, "p.npy", {}); }, {"no cameras"});
}

}  // namespace
}  // namespace isegman
