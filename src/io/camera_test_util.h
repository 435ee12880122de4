// Shared helpers of the camera format tests (header only; not part of the library).
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/error.h"

namespace isegman::testing {

// A fresh temporary folder, removed with its contents at the end of the test.
class TempDir {
 public:
  TempDir() {
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() /
            ("isegman-io-test-" + std::to_string(rd()) + "-" + std::to_string(rd()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string str() const { return path_.string(); }
  std::string operator/(const std::string& rel) const { return (path_ / rel).string(); }
  std::string mkdir(const std::string& rel) const {
    std::filesystem::create_directories(path_ / rel);
    return (path_ / rel).string();
  }

 private:
  std::filesystem::path path_;
};

inline void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}
inline void write_bytes(const std::string& path, const std::vector<uint8_t>& b) {
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
}

// Little-endian byte builder for hand-made binary files.
struct Bytes {
  std::vector<uint8_t> b;
  template <typename T>
  Bytes& put(T v) {
    uint8_t tmp[sizeof(T)];
    std::memcpy(tmp, &v, sizeof(T));
    b.insert(b.end(), tmp, tmp + sizeof(T));
    return *this;
  }
  Bytes& str(const std::string& s) {
    b.insert(b.end(), s.begin(), s.end());
    b.push_back(0);
    return *this;
  }
};

// A small rig of three pinhole cameras around the origin, all looking at it, with a
// single focal length and a centred principal point (so LLFF can express it too).
inline std::vector<Camera> make_rig() {
  std::vector<Camera> rig;
  const Vec3 eyes[3] = {{0.3, -0.2, -4.0}, {3.0, -1.0, -2.5}, {-2.0, 1.5, -3.2}};
  const char* names[3] = {"cam_a", "cam_b", "cam_c"};
  for (int i = 0; i < 3; ++i) {
    Camera c = Camera::look_at(eyes[i], {0.1, 0.05, 0.2}, {0.1, -1.0, 0.05}, 640, 480, 55.0 + 7 * i);
    c.id = i;
    c.name = names[i];
    rig.push_back(c);
  }
  return rig;
}

inline void expect_same_camera(const Camera& a, const Camera& b, double tol = 1e-9) {
  SCOPED_TRACE("camera " + a.name + " vs " + b.name);
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_NEAR(a.fx, b.fx, tol);
  EXPECT_NEAR(a.fy, b.fy, tol);
  EXPECT_NEAR(a.cx, b.cx, tol);
  EXPECT_NEAR(a.cy, b.cy, tol);
  for (int r = 0; r < 3; ++r) {
    EXPECT_NEAR(a.t[r], b.t[r], tol) << "t[" << r << "]";
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(a.R.m[r][c], b.R.m[r][c], tol) << "R[" << r << "][" << c << "]";
  }
}

// Expects `cams` to hold the cameras of `ref` (matched by name, any order).
inline void expect_same_cameras(const std::vector<Camera>& ref, const std::vector<Camera>& cams, double tol = 1e-9) {
  ASSERT_EQ(ref.size(), cams.size());
  for (const Camera& r : ref) {
    const Camera* c = find_camera(cams, r.name);
    ASSERT_NE(c, nullptr) << "no camera named " << r.name;
    expect_same_camera(r, *c, tol);
  }
}

// Expects fn() to throw isegman::Error whose message contains every given fragment.
template <typename Fn>
void expect_error(Fn fn, std::initializer_list<std::string> fragments) {
  try {
    fn();
    ADD_FAILURE() << "expected an isegman::Error";
  } catch (const Error& e) {
    std::string msg = e.what();
    for (const std::string& f : fragments) EXPECT_NE(msg.find(f), std::string::npos) << "message: " << msg << "\nmissing: " << f;
  }
}

}  // namespace isegman::testing
