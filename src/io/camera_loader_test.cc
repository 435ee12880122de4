#include "io/camera_loader.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "io/camera_test_util.h"
#include "io/cameras_json.h"
#include "io/colmap.h"
#include "io/llff.h"
#include "io/transforms_json.h"

namespace isegman {
namespace {

using testing::TempDir;
using testing::expect_error;

// Writes `rig` in every format under `dir`; returns (path to load, expected format).
std::vector<std::pair<std::string, std::string>> write_all_formats(const TempDir& dir, const std::vector<Camera>& rig) {
  dir.mkdir("inria");
  write_cameras_json(dir / "inria/cameras.json", rig);
  write_colmap_text(dir.mkdir("ctxt/sparse/0"), rig);
  write_colmap_binary(dir.mkdir("cbin/sparse"), rig);
  write_colmap_binary(dir.mkdir("cbin_model"), rig);
  write_llff(dir.mkdir("llff") + "/poses_bounds.npy", rig, 0.5, 30);
  dir.mkdir("llff/images");
  for (const Camera& c : rig) testing::write_text(dir / ("llff/images/" + c.name + ".png"), "");  // names only
  write_transforms_json(dir.mkdir("ns") + "/transforms.json", rig);
  return {{dir / "inria/cameras.json", "INRIA cameras.json"},
          {dir / "inria", "INRIA cameras.json"},
          {dir / "ctxt", "COLMAP text"},
          {dir / "ctxt/sparse/0", "COLMAP text"},
          {dir / "ctxt/sparse/0/images.txt", "COLMAP text"},
          {dir / "ctxt/sparse/0/cameras.txt", "COLMAP text"},
          {dir / "cbin", "COLMAP binary"},
          {dir / "cbin_model/images.bin", "COLMAP binary"},
          {dir / "cbin_model", "COLMAP binary"},
          {dir / "llff/poses_bounds.npy", "LLFF poses_bounds.npy"},
          {dir / "llff", "LLFF poses_bounds.npy"},
          {dir / "ns/transforms.json", "transforms.json (nerfstudio / NeRF)"},
          {dir / "ns", "transforms.json (nerfstudio / NeRF)"}};
}

TEST(CameraLoader, TheSameRigLoadsIdenticallyFromEveryFormat) {
  TempDir dir;
  std::vector<Camera> rig = testing::make_rig();
  const Vec3 point{0.4, -0.3, 0.7};
  for (const auto& [path, format] : write_all_formats(dir, rig)) {
    SCOPED_TRACE(path);
    CameraLoadReport report;
    std::vector<Camera> cams = load_cameras(path, &report);
    EXPECT_EQ(report.format, format);
    testing::expect_same_cameras(rig, cams);
    for (const Camera& r : rig) {
      const Camera* c = find_camera(cams, r.name);
      ASSERT_NE(c, nullptr);
      double u0, v0, u1, v1;
      ASSERT_TRUE(r.project(point, u0, v0));
      ASSERT_TRUE(c->project(point, u1, v1));
      EXPECT_NEAR(u0, u1, 1e-7);
      EXPECT_NEAR(v0, v1, 1e-7);
      EXPECT_GT(u0, 0);
      EXPECT_LT(u0, r.width);
    }
  }
}

TEST(CameraLoader, UnknownInputsNameThePath) {
  TempDir dir;
  testing::write_text(dir / "notes.txt", "hello\n");
  expect_error([&] { load_cameras(dir / "notes.txt"); }, {"notes.txt", "unrecognised camera file format"});
  testing::write_text(dir / "obj.json", "{\"fl_x\": 3}");
  expect_error([&] { load_cameras(dir / "obj.json"); }, {"obj.json", "'frames'"});
  expect_error([&] { load_cameras(dir.str()); }, {dir.str(), "no cameras found"});
  expect_error([&] { load_cameras(dir / "missing.json"); }, {"missing.json"});
  // cameras.txt alone (no images.txt) is not a model.
  write_colmap_text(dir.mkdir("half"), testing::make_rig());
  std::filesystem::remove(dir / "half/images.txt");
  expect_error([&] { load_cameras(dir / "half/cameras.txt"); }, {"cameras.txt", "COLMAP"});
  // Errors inside a format keep naming the file.
  testing::write_bytes(dir / "bad.npy", {0x93, 'N', 'U', 'M', 'P', 'Y', 1, 0, 4, 0, '{', '}', ' ', '\n'});
  expect_error([&] { load_cameras(dir / "bad.npy"); }, {"bad.npy", "descr"});
}

TEST(CameraLoader, DistortionNotesReachTheReport) {
  TempDir dir;
  dir.mkdir("m");
  testing::write_text(dir / "m/cameras.txt", "1 OPENCV 64 48 50 50 32 24 0.01 0 0 0\n");
  testing::write_text(dir / "m/images.txt", "1 1 0 0 0 0 0 0 1 im0.jpg\n\n");
  CameraLoadReport report;
  std::vector<Camera> cams = load_cameras(dir / "m", &report);
  ASSERT_EQ(cams.size(), 1u);
  EXPECT_EQ(cams[0].name, "im0");
  ASSERT_EQ(report.notes.size(), 1u);
  EXPECT_NE(report.notes[0].find("OPENCV"), std::string::npos);
  EXPECT_NE(report.notes[0].find("im0"), std::string::npos);
}

// The real fern cameras (an INRIA cameras.json) survive COLMAP text, COLMAP binary,
// LLFF and transforms.json round trips.
TEST(CameraLoader, FernRoundTripsThroughEveryFormat) {
  const std::string fern = std::string(ISEGMAN_FIXTURES_DIR) + "/fern/scene/cameras.json";
  if (!std::filesystem::exists(fern)) GTEST_SKIP() << "fixture " << fern << " not present";
  CameraLoadReport report;
  std::vector<Camera> ref = load_cameras(fern, &report);
  ASSERT_EQ(report.format, "INRIA cameras.json");
  ASSERT_EQ(ref.size(), 20u);
  TempDir dir;
  for (const auto& [path, format] : write_all_formats(dir, ref)) {
    SCOPED_TRACE(path);
    testing::expect_same_cameras(ref, load_cameras(path));
  }
}

}  // namespace
}  // namespace isegman
