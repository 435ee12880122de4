#include "io/colmap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "io/camera_test_util.h"

namespace isegman {
namespace {

using testing::Bytes;
using testing::TempDir;
using testing::expect_error;

const char kCamerasTxt[] =
    "# Camera list with one line of data per camera:\n"
    "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n"
    "1 PINHOLE 100 80 90 95 50.5 40.25\n"
    "\n"
    "7 SIMPLE_RADIAL 200 150 120 100 75 0.05\r\n";
// Image 3: 90 degrees about z, t = (1, 2, 3). Image 4 uses camera 7. Names have folders
// and extensions; the points line of image 3 is not empty, that of image 4 is.
const char kImagesTxt[] =
    "# Image list with two lines of data per image:\n"
    "3 0.70710678118654757 0 0 0.70710678118654757 1 2 3 1 sub/one.JPG\n"
    "10.5 20.5 -1 30 40 17\n"
    "4 1 0 0 0 0 0 0 7 two.png\n"
    "\n";

TEST(Colmap, ParsesHandWrittenTextModel) {
  std::vector<ColmapCamera> cams = parse_colmap_cameras_txt(kCamerasTxt, "cameras.txt");
  std::vector<ColmapImage> images = parse_colmap_images_txt(kImagesTxt, "images.txt");
  ASSERT_EQ(cams.size(), 2u);
  ASSERT_EQ(images.size(), 2u);
  EXPECT_EQ(images[0].name, "sub/one.JPG");
  std::vector<std::string> notes;
  std::vector<Camera> out = colmap_to_cameras(cams, images, "cameras.txt", "images.txt", "", &notes);
  ASSERT_EQ(out.size(), 2u);
  // Sorted by image name: "sub/one.JPG" < "two.png".
  const Camera& a = out[0];
  EXPECT_EQ(a.name, "one");
  EXPECT_EQ(a.id, 3);
  EXPECT_EQ(a.width, 100);
  EXPECT_EQ(a.height, 80);
  EXPECT_DOUBLE_EQ(a.fx, 90);
  EXPECT_DOUBLE_EQ(a.fy, 95);
  EXPECT_DOUBLE_EQ(a.cx, 50.5);
  EXPECT_DOUBLE_EQ(a.cy, 40.25);
  const double expect_r[3][3] = {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a.R.m[r][c], expect_r[r][c], 1e-12);
  // R (2, 1, 7) + t = (0, 4, 10): u = 50.5 + 90 * 0 / 10, v = 40.25 + 95 * 4 / 10.
  double u, v;
  ASSERT_TRUE(a.project({2, 1, 7}, u, v));
  EXPECT_NEAR(u, 50.5, 1e-12);
  EXPECT_NEAR(v, 78.25, 1e-12);

  const Camera& b = out[1];
  EXPECT_EQ(b.name, "two");
  EXPECT_DOUBLE_EQ(b.fx, 120);
  EXPECT_DOUBLE_EQ(b.fy, 120);
  EXPECT_DOUBLE_EQ(b.cx, 100);
  EXPECT_DOUBLE_EQ(b.cy, 75);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("distortion of camera 7 (SIMPLE_RADIAL"), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find("'two'"), std::string::npos) << notes[0];
}

// The same model as kCamerasTxt/kImagesTxt, written byte by byte.
Bytes hand_cameras_bin() {
  Bytes b;
  b.put<uint64_t>(2);
  b.put<uint32_t>(1).put<int32_t>(1).put<uint64_t>(100).put<uint64_t>(80);
  for (double p : {90.0, 95.0, 50.5, 40.25}) b.put(p);
  b.put<uint32_t>(7).put<int32_t>(2).put<uint64_t>(200).put<uint64_t>(150);
  for (double p : {120.0, 100.0, 75.0, 0.05}) b.put(p);
  return b;
}
Bytes hand_images_bin() {
  Bytes b;
  b.put<uint64_t>(2);
  b.put<uint32_t>(3);
  for (double v : {0.70710678118654757, 0.0, 0.0, 0.70710678118654757, 1.0, 2.0, 3.0}) b.put(v);
  b.put<uint32_t>(1).str("sub/one.JPG").put<uint64_t>(2);
  b.put(10.5).put(20.5).put<uint64_t>(std::numeric_limits<uint64_t>::max());
  b.put(30.0).put(40.0).put<uint64_t>(17);
  b.put<uint32_t>(4);
  for (double v : {1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0}) b.put(v);
  b.put<uint32_t>(7).str("two.png").put<uint64_t>(0);
  return b;
}

TEST(Colmap, BinaryMatchesText) {
  Bytes cb = hand_cameras_bin(), ib = hand_images_bin();
  std::vector<ColmapCamera> cams = parse_colmap_cameras_bin(cb.b.data(), cb.b.size(), "cameras.bin");
  std::vector<ColmapImage> images = parse_colmap_images_bin(ib.b.data(), ib.b.size(), "images.bin");
  std::vector<Camera> bin = colmap_to_cameras(cams, images, "c", "i", "", nullptr);
  std::vector<Camera> txt = colmap_to_cameras(parse_colmap_cameras_txt(kCamerasTxt, "c"),
                                              parse_colmap_images_txt(kImagesTxt, "i"), "c", "i", "", nullptr);
  testing::expect_same_cameras(txt, bin, 0.0);
  // The library's serialisers reproduce the hand-made bytes.
  EXPECT_EQ(serialize_colmap_cameras_bin(cams), cb.b);
}

TEST(Colmap, WritersRoundTripTextAndBinary) {
  TempDir dir;
  std::vector<Camera> rig = testing::make_rig();
  rig[1].fy = rig[1].fx * 1.01;  // two PINHOLE cameras, fx != fy
  rig[1].cx += 3.25;
  write_colmap_text(dir.mkdir("txt"), rig);
  write_colmap_binary(dir.mkdir("bin"), rig);
  std::string format;
  testing::expect_same_cameras(rig, read_colmap_model(dir / "txt", nullptr, &format));
  EXPECT_EQ(format, "COLMAP text");
  testing::expect_same_cameras(rig, read_colmap_model(dir / "bin", nullptr, &format));
  EXPECT_EQ(format, "COLMAP binary");
  // Cameras with equal intrinsics share one COLMAP camera.
  std::vector<ColmapCamera> cc;
  std::vector<ColmapImage> ci;
  cameras_to_colmap(rig, cc, ci);
  EXPECT_EQ(cc.size(), 3u);
  rig[1] = rig[0].resized(rig[0].width, rig[0].height);
  rig[1].name = "same";
  cameras_to_colmap(rig, cc, ci);
  EXPECT_EQ(cc.size(), 2u);
}

TEST(Colmap, SceneFolderLayouts) {
  TempDir dir;
  std::vector<Camera> rig = testing::make_rig();
  // scene/sparse/0 with scene/images: image paths point into images/.
  write_colmap_binary(dir.mkdir("scene/sparse/0"), rig);
  dir.mkdir("scene/images");
  EXPECT_EQ(find_colmap_model_dir(dir / "scene"), dir / "scene/sparse/0");
  std::vector<Camera> cams = read_colmap_model(dir / "scene");
  testing::expect_same_cameras(rig, cams);
  EXPECT_EQ(cams[0].image_path, dir / "scene/images/cam_a.png");
  // scene2/sparse (no 0): text; no images folder -> no image paths.
  write_colmap_text(dir.mkdir("scene2/sparse"), rig);
  cams = read_colmap_model(dir / "scene2");
  testing::expect_same_cameras(rig, cams);
  EXPECT_TRUE(cams[0].image_path.empty());
  // Both kinds in one folder: binary wins and a note says so.
  write_colmap_text(dir / "scene/sparse/0", rig);
  std::vector<std::string> notes;
  std::string format;
  read_colmap_model(dir / "scene/sparse/0", &notes, &format);
  EXPECT_EQ(format, "COLMAP binary");
  ASSERT_EQ(notes.size(), 1u);
  expect_error([&] { read_colmap_model(dir.mkdir("empty")); }, {"empty", "no COLMAP model"});
}

TEST(Colmap, DuplicateStemsKeepTheirFolders) {
  std::vector<ColmapCamera> cams = parse_colmap_cameras_txt("1 PINHOLE 10 10 5 5 5 5\n", "c");
  std::vector<ColmapImage> images =
      parse_colmap_images_txt("1 1 0 0 0 0 0 0 1 left/0001.jpg\n\n2 1 0 0 0 0 0 0 1 right/0001.jpg\n\n", "i");
  std::vector<Camera> out = colmap_to_cameras(cams, images, "c", "i", "", nullptr);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].name, "left/0001");
  EXPECT_EQ(out[1].name, "right/0001");
}

TEST(Colmap, TruncatedBinaryAtEveryOffsetIsAnError) {
  Bytes cb = hand_cameras_bin(), ib = hand_images_bin();
  for (size_t n = 0; n < cb.b.size(); ++n)
    expect_error([&] { parse_colmap_cameras_bin(cb.b.data(), n, "cameras.bin"); }, {"cameras.bin"});
  for (size_t n = 0; n < ib.b.size(); ++n)
    expect_error([&] { parse_colmap_images_bin(ib.b.data(), n, "images.bin"); }, {"images.bin"});
  // A cut in the middle of a record says "truncated".
  expect_error([&] { parse_colmap_cameras_bin(cb.b.data(), 8 + 48 + 8, "cameras.bin"); }, {"truncated"});
  Bytes one;
  one.put<uint64_t>(1).put<uint32_t>(1);
  for (double v : {1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0}) one.put(v);
  one.put<uint32_t>(1).str("a_rather_long_image_name_of_forty_chars.png").put<uint64_t>(0);
  expect_error([&] { parse_colmap_images_bin(one.b.data(), 8 + 4 + 7 * 8 + 4 + 20, "images.bin"); },
               {"truncated", "image name"});
  expect_error([&] { parse_colmap_images_bin(one.b.data(), one.b.size() - 3, "images.bin"); },
               {"truncated", "2D point count"});
  EXPECT_EQ(parse_colmap_images_bin(one.b.data(), one.b.size(), "images.bin").size(), 1u);
}

TEST(Colmap, AbsurdCountsAreRefusedBeforeAllocating) {
  Bytes cb = hand_cameras_bin();
  uint64_t huge = uint64_t(1) << 60;
  std::memcpy(cb.b.data(), &huge, 8);
  expect_error([&] { parse_colmap_cameras_bin(cb.b.data(), cb.b.size(), "cameras.bin"); },
               {"cameras.bin", "camera count"});
  Bytes ib = hand_images_bin();
  std::memcpy(ib.b.data(), &huge, 8);
  expect_error([&] { parse_colmap_images_bin(ib.b.data(), ib.b.size(), "images.bin"); }, {"image count"});
  // A huge 2D point count inside the first image.
  ib = hand_images_bin();
  size_t at = 8 + 4 + 7 * 8 + 4 + std::string("sub/one.JPG").size() + 1;
  uint64_t points = std::numeric_limits<uint64_t>::max() / 2;
  std::memcpy(ib.b.data() + at, &points, 8);
  expect_error([&] { parse_colmap_images_bin(ib.b.data(), ib.b.size(), "images.bin"); }, {"2D points"});
  // A count smaller than the records present leaves trailing bytes.
  ib = hand_images_bin();
  ib.b[0] = 1;
  expect_error([&] { parse_colmap_images_bin(ib.b.data(), ib.b.size(), "images.bin"); }, {"unexpected bytes"});
}

TEST(Colmap, InvalidContentIsRefused) {
  // Unknown model id.
  Bytes b;
  b.put<uint64_t>(1).put<uint32_t>(1).put<int32_t>(99).put<uint64_t>(10).put<uint64_t>(10);
  for (int k = 0; k < 4; ++k) b.put(5.0);
  expect_error([&] { parse_colmap_cameras_bin(b.b.data(), b.b.size(), "cameras.bin"); },
               {"cameras.bin", "unknown camera model id 99"});
  // NaN parameter, zero size.
  Bytes cb = hand_cameras_bin();
  double nan = std::numeric_limits<double>::quiet_NaN();
  std::memcpy(cb.b.data() + 8 + 24 + 8, &nan, 8);
  expect_error([&] { parse_colmap_cameras_bin(cb.b.data(), cb.b.size(), "cameras.bin"); }, {"non-finite"});
  cb = hand_cameras_bin();
  std::memset(cb.b.data() + 8 + 8, 0, 8);
  expect_error([&] { parse_colmap_cameras_bin(cb.b.data(), cb.b.size(), "cameras.bin"); }, {"zero image size"});
  // NaN and zero quaternions.
  Bytes ib = hand_images_bin();
  std::memcpy(ib.b.data() + 8 + 4 + 8, &nan, 8);
  expect_error([&] { parse_colmap_images_bin(ib.b.data(), ib.b.size(), "images.bin"); }, {"images.bin", "non-finite"});
  ib = hand_images_bin();
  std::memset(ib.b.data() + 8 + 4, 0, 32);
  expect_error([&] { parse_colmap_images_bin(ib.b.data(), ib.b.size(), "images.bin"); }, {"zero rotation"});
  // Duplicate ids.
  expect_error([] { parse_colmap_cameras_txt("1 PINHOLE 10 10 5 5 5 5\n1 PINHOLE 10 10 5 5 5 5\n", "c.txt"); },
               {"c.txt", "line 2", "appears twice"});
  // Text: unknown model, wrong parameter count, junk numbers, NaN, zero size.
  expect_error([] { parse_colmap_cameras_txt("1 PINHOLY 10 10 5 5 5 5\n", "c.txt"); }, {"unknown camera model 'PINHOLY'"});
  expect_error([] { parse_colmap_cameras_txt("1 OPENCV 10 10 5 5 5 5\n", "c.txt"); }, {"takes 8 parameters, found 4"});
  expect_error([] { parse_colmap_cameras_txt("1 PINHOLE 10 10 5 5x 5 5\n", "c.txt"); }, {"line 1", "'5x'"});
  expect_error([] { parse_colmap_cameras_txt("1 PINHOLE 10 10 5 nan 5 5\n", "c.txt"); }, {"not finite"});
  expect_error([] { parse_colmap_cameras_txt("1 PINHOLE 0 10 5 5 5 5\n", "c.txt"); }, {"zero image size"});
  expect_error([] { parse_colmap_cameras_txt("1 PINHOLE -10 10 5 5 5 5\n", "c.txt"); }, {"width"});
  expect_error([] { parse_colmap_images_txt("1 1 0 0 0 0 0 0 1\n", "i.txt"); }, {"i.txt", "expected IMAGE_ID"});
  expect_error([] { parse_colmap_images_txt("1 1 0 0 inf 0 0 0 1 a.png\n", "i.txt"); }, {"QZ", "not finite"});
}

// Fuzzer finding: tokens were split on all white space (\f, \v too) but the name was
// located by spaces and tabs only, so substr() threw std::out_of_range.
TEST(Colmap, FuzzRegressionFormFeedBeforeTheName) {
  std::vector<ColmapImage> images = parse_colmap_images_txt("1 1 0 0 0 0 0 0 2\fb.png\n\n", "i.txt");
  ASSERT_EQ(images.size(), 1u);
  EXPECT_EQ(images[0].name, "b.png");
  images = parse_colmap_images_txt("1 1 0 0 0 0 0 0 2 my photo.png \v\n\n", "i.txt");
  EXPECT_EQ(images[0].name, "my photo.png");
}

TEST(Colmap, ImageWithMissingCameraNamesBothFiles) {
  std::vector<ColmapCamera> cams = parse_colmap_cameras_txt("1 PINHOLE 10 10 5 5 5 5\n", "cams.txt");
  std::vector<ColmapImage> images = parse_colmap_images_txt("1 1 0 0 0 0 0 0 2 a.png\n\n", "imgs.txt");
  expect_error([&] { colmap_to_cameras(cams, images, "cams.txt", "imgs.txt", "", nullptr); },
               {"imgs.txt", "'a.png'", "camera 2", "cams.txt"});
  expect_error([&] { colmap_to_cameras(cams, {}, "cams.txt", "imgs.txt", "", nullptr); }, {"imgs.txt", "no images"});
  cams[0].width = uint64_t(1) << 33;  // built in memory: would wrap in an int
  expect_error([&] { colmap_to_cameras(cams, parse_colmap_images_txt("1 1 0 0 0 0 0 0 1 a.png\n", "i"), "cams.txt",
                                       "imgs.txt", "", nullptr); },
               {"cams.txt", "implausible image size"});
}

TEST(Colmap, FisheyeAndOtherModelsByParameterCount) {
  std::vector<ColmapCamera> cams = parse_colmap_cameras_txt(
      "1 OPENCV_FISHEYE 64 48 30 31 32 24 0 0 0 0\n"
      "2 FULL_OPENCV 64 48 30 31 32 24 0.1 0 0 0 0 0 0 0\n"
      "3 RADIAL 64 48 30 32 24 0 0\n",
      "c");
  std::vector<ColmapImage> images = parse_colmap_images_txt(
      "1 1 0 0 0 0 0 0 1 a.png\n\n2 1 0 0 0 0 0 0 2 b.png\n\n3 1 0 0 0 0 0 0 3 c.png\n\n", "i");
  std::vector<std::string> notes;
  std::vector<Camera> out = colmap_to_cameras(cams, images, "c", "i", "", &notes);
  EXPECT_DOUBLE_EQ(out[0].fy, 31);
  EXPECT_DOUBLE_EQ(out[1].cx, 32);
  EXPECT_DOUBLE_EQ(out[2].fy, 30);
  // Fisheye is always noted; FULL_OPENCV with k1 != 0 is noted; RADIAL with zeros is not.
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_NE(notes[0].find("fisheye"), std::string::npos);
  EXPECT_NE(notes[1].find("FULL_OPENCV"), std::string::npos);
}

}  // namespace
}  // namespace isegman
