// Issue 11 items 1 and 12 (io side): camera files with duplicate ids/names, implausible
// intrinsics or sizes, names with NUL bytes, and PLY files with bytes after the data are
// refused with errors naming the file and the value.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <functional>

#include "core/error.h"
#include "core/scene.h"
#include "core/test_dirs.h"
#include "io/atomic_file.h"
#include "io/camera_loader.h"
#include "io/camera_test_util.h"
#include "io/cameras_json.h"
#include "io/ply.h"

namespace fs = std::filesystem;

namespace isegman {
namespace {
using testing::make_rig;

std::string temp_file(const std::string& name) {
  static const fs::path d = isegman::testing::fresh_temp_dir("isegman-untrusted", "");
  return (d / name).string();
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(UntrustedCameras, DuplicateIdsOrNamesAreRefused) {
  std::vector<Camera> rig = make_rig();
  rig[2].name = rig[0].name;
  const std::string path = temp_file("dup_names.json");
  write_cameras_json(path, rig);
  std::string e = error_of([&] { load_cameras(path); });
  EXPECT_NE(e.find("two cameras are named 'cam_a'"), std::string::npos) << e;
  EXPECT_NE(e.find(path), std::string::npos) << e;
  rig = make_rig();
  rig[1].id = rig[0].id;
  write_cameras_json(path, rig);
  e = error_of([&] { load_cameras(path); });
  EXPECT_NE(e.find("two cameras have the id"), std::string::npos) << e;
}

TEST(UntrustedCameras, ImplausibleValuesAreNamed) {
  Camera c = make_rig()[0];
  c.fx = 1e300;
  std::string e = error_of([&] { c.validate("cams.json"); });
  EXPECT_NE(e.find("focal length"), std::string::npos) << e;
  c = make_rig()[0];
  c.width = c.height = 65536;
  e = error_of([&] { c.validate("cams.json"); });
  EXPECT_NE(e.find("65536x65536"), std::string::npos) << e;
  c = make_rig()[0];
  c.width = 32768;
  c.height = 32768;  // each side allowed, but 2^30 pixels is not
  EXPECT_THROW(c.validate("cams.json"), Error);
  c = make_rig()[0];
  c.name = std::string("a\0b", 3);
  e = error_of([&] { c.validate("cams.json"); });
  EXPECT_NE(e.find("control character"), std::string::npos) << e;
  c = make_rig()[0];
  c.name = "../../etc/x";  // allowed as a name; made safe where it becomes a file name
  EXPECT_NO_THROW(c.validate("cams.json"));
}

TEST(UntrustedPly, TrailingBytesAreRefused) {
  GaussianScene s;
  s.resize(3, 0);
  std::vector<uint8_t> bytes = serialize_ply(s);
  EXPECT_EQ(parse_ply(bytes.data(), bytes.size(), "ok.ply").size(), 3u);
  bytes.insert(bytes.end(), 17, 0xAB);
  const std::string e = error_of([&] { parse_ply(bytes.data(), bytes.size(), "tail.ply"); });
  EXPECT_NE(e.find("tail.ply"), std::string::npos) << e;
  EXPECT_NE(e.find("17 trailing bytes"), std::string::npos) << e;
}

}  // namespace
}  // namespace isegman
