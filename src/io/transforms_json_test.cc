#include "io/transforms_json.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/image.h"
#include "io/camera_test_util.h"
#include "io/image_io.h"
#include "io/image_size.h"

namespace isegman {
namespace {

using testing::TempDir;
using testing::expect_error;

// One frame at (0, 0, 5) with the identity OpenGL rotation: it looks down world -z at
// the origin, its image up is world +y.
const char kOneFrame[] = R"({
  "fl_x": 100, "fl_y": 110, "cx": 32.5, "cy": 24.25, "w": 64, "h": 48,
  "k1": 0.0, "p1": 0.0,
  "frames": [{"file_path": "images/frame_0001.jpg",
              "transform_matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 5], [0, 0, 0, 1]]}]
})";

TEST(TransformsJson, OpenGlAxesBecomeOpenCv) {
  std::vector<std::string> notes;
  std::vector<Camera> cams = parse_transforms_json(kOneFrame, "t.json", "/data/scene", &notes);
  ASSERT_EQ(cams.size(), 1u);
  const Camera& c = cams[0];
  EXPECT_EQ(c.name, "frame_0001");
  EXPECT_EQ(c.image_path, "/data/scene/images/frame_0001.jpg");
  EXPECT_EQ(c.width, 64);
  EXPECT_DOUBLE_EQ(c.fy, 110);
  EXPECT_DOUBLE_EQ(c.cy, 24.25);
  const double diag[3] = {1, -1, -1};
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(c.R.m[r][k], r == k ? diag[r] : 0.0);
  double u, v;
  ASSERT_TRUE(c.project({0, 0, 0}, u, v));
  EXPECT_NEAR(u, 32.5, 1e-12);
  EXPECT_NEAR(v, 24.25, 1e-12);
  ASSERT_TRUE(c.project({1, 0, 0}, u, v));  // world +x: right of the centre
  EXPECT_NEAR(u, 32.5 + 100 * 1.0 / 5, 1e-12);
  ASSERT_TRUE(c.project({0, 1, 0}, u, v));  // world +y: above the centre
  EXPECT_NEAR(v, 24.25 - 110 * 1.0 / 5, 1e-12);
  EXPECT_TRUE(notes.empty());  // zero distortion is not worth a note
}

TEST(TransformsJson, NerfSyntheticAngleAndSizeFromThePhoto) {
  TempDir dir;
  dir.mkdir("train");
  write_png(dir / "train/r_0.png", Image(80, 60, 3, 0.2f));
  testing::write_text(dir / "transforms_train.json", R"({"camera_angle_x": 0.6911112070083618,
    "frames": [{"file_path": "./train/r_0",
                "transform_matrix": [[0, 0, 1, 4], [1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 0, 1]]}]})");
  std::vector<Camera> cams = read_transforms_json(dir / "transforms_train.json");
  ASSERT_EQ(cams.size(), 1u);
  EXPECT_EQ(cams[0].name, "r_0");
  EXPECT_EQ(cams[0].image_path, dir / "train/r_0.png");
  EXPECT_EQ(cams[0].width, 80);
  EXPECT_EQ(cams[0].height, 60);
  EXPECT_NEAR(cams[0].fx, 40 / std::tan(0.6911112070083618 / 2), 1e-9);
  EXPECT_DOUBLE_EQ(cams[0].fy, cams[0].fx);
  // Camera at (4, 0, 0), OpenGL back = +x: it looks at the origin along -x.
  double u, v;
  ASSERT_TRUE(cams[0].project({0, 0, 0}, u, v));
  EXPECT_NEAR(u, 40, 1e-12);
  EXPECT_NEAR(v, 30, 1e-12);
  ASSERT_TRUE(cams[0].project({0, 0, 1}, u, v));  // OpenGL up = column 1 = world +z
  EXPECT_LT(v, 30);
  // No w/h and no photo: the error names the JSON and the missing photo.
  testing::write_text(dir / "t2.json", R"({"camera_angle_x": 0.7, "frames": [{"file_path": "./train/r_9",
    "transform_matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}]})");
  expect_error([&] { read_transforms_json(dir / "t2.json"); }, {"t2.json", "r_9", "image size"});
}

TEST(TransformsJson, PerFrameIntrinsicsWinAndDistortionIsNoted) {
  std::vector<std::string> notes;
  std::vector<Camera> cams = parse_transforms_json(R"({
    "camera_model": "OPENCV", "fl_x": 100, "w": 64, "h": 48, "k1": -0.02,
    "frames": [
      {"file_path": "a.png", "transform_matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]},
      {"file_path": "b.png", "fl_x": 90, "fl_y": 91, "cx": 30, "w": 60, "h": 40,
       "transform_matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0]]}]})",
                                                   "t.json", "", &notes);
  ASSERT_EQ(cams.size(), 2u);
  EXPECT_DOUBLE_EQ(cams[0].fx, 100);
  EXPECT_DOUBLE_EQ(cams[0].fy, 100);
  EXPECT_DOUBLE_EQ(cams[0].cx, 32);
  EXPECT_DOUBLE_EQ(cams[1].fx, 90);
  EXPECT_DOUBLE_EQ(cams[1].fy, 91);
  EXPECT_DOUBLE_EQ(cams[1].cx, 30);
  EXPECT_DOUBLE_EQ(cams[1].cy, 20);
  EXPECT_EQ(cams[1].height, 40);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("k1"), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find("a.png"), std::string::npos) << notes[0];
}

TEST(TransformsJson, WriterRoundTrips) {
  std::vector<Camera> rig = testing::make_rig();
  testing::expect_same_cameras(rig, parse_transforms_json(cameras_to_transforms_json(rig), "t.json", ""));
  rig[2].cx += 1.5;  // per-frame intrinsics
  rig[1].fy *= 1.02;
  testing::expect_same_cameras(rig, parse_transforms_json(cameras_to_transforms_json(rig), "t.json", ""));
}

TEST(TransformsJson, InvalidFilesAreRefused) {
  const std::string m = R"("transform_matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])";
  auto parse = [](const std::string& s) { return parse_transforms_json(s, "bad.json", ""); };
  expect_error([&] { parse("{\"frames\": [}"); }, {"bad.json", "invalid JSON"});
  expect_error([&] { parse("{\"fl_x\": 5}"); }, {"bad.json", "'frames'"});
  expect_error([&] { parse("{\"frames\": []}"); }, {"empty"});
  expect_error([&] { parse("{\"w\": 4, \"h\": 4, \"frames\": [{\"file_path\": \"a\", " + m + "}]}"); }, {"no focal length"});
  expect_error([&] { parse("{\"fl_x\": 5, \"w\": 0, \"h\": 4, \"frames\": [{\"file_path\": \"a\", " + m + "}]}"); },
               {"'w'"});
  expect_error([&] { parse("{\"fl_x\": \"5\", \"w\": 4, \"h\": 4, \"frames\": [{\"file_path\": \"a\", " + m + "}]}"); },
               {"'fl_x' is not a number"});
  expect_error([&] { parse(R"({"fl_x": 5, "w": 4, "h": 4, "frames": [{"file_path": "a",
      "transform_matrix": [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 1, 1]]}]})"); }, {"last row"});
  expect_error([&] { parse(R"({"fl_x": 5, "w": 4, "h": 4, "frames": [{"file_path": "a",
      "transform_matrix": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}]})"); }, {"4x4"});
  expect_error([&] { parse(R"({"fl_x": 5, "w": 4, "h": 4, "frames": [{"transform_matrix": []}]})"); }, {"file_path"});
}

TEST(ImageSize, ReadsPngAndJpegHeaders) {
  Image img(37, 21, 3, 0.4f);
  std::vector<uint8_t> png = encode_png(img), jpg = encode_jpeg(img);
  int w = 0, h = 0;
  ASSERT_TRUE(parse_image_size(png.data(), png.size(), w, h));
  EXPECT_EQ(w, 37);
  EXPECT_EQ(h, 21);
  w = h = 0;
  ASSERT_TRUE(parse_image_size(jpg.data(), jpg.size(), w, h));
  EXPECT_EQ(w, 37);
  EXPECT_EQ(h, 21);
  for (size_t n = 0; n < 24; ++n) EXPECT_FALSE(parse_image_size(png.data(), n, w, h));
  EXPECT_FALSE(parse_image_size(jpg.data(), 40, w, h));
  TempDir dir;
  EXPECT_FALSE(read_image_size(dir / "missing.png", w, h));
}

}  // namespace
}  // namespace isegman
