#include "edit/scene_format.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "core/sh.h"
#include "edit/splat_format.h"
#include "edit/test_scenes.h"
#include "io/atomic_file.h"
#include "io/ply.h"

namespace isegman::edit {
namespace {

std::string temp(const std::string& name) {
  const std::string dir = ::testing::TempDir() + "/isegman_fmt_" + std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  return dir + "/" + name;
}

TEST(Splat, RecordLayoutAndRoundTrip) {
  GaussianScene s = testing::random_scene(64, 2, 1, false, false);
  // One Gaussian with hand-picked values to check the byte layout.
  s.positions[0] = 1.5f;
  s.scales[0] = std::log(0.25f);
  s.sh_of(0)[0] = rgb_to_sh_dc(1.0f);
  s.opacity[0] = 0.f;  // alpha 0.5 -> 128
  s.rotations[0] = 2.f;
  s.rotations[1] = s.rotations[2] = s.rotations[3] = 0.f;
  std::vector<std::string> notes;
  const std::vector<uint8_t> bytes = serialize_splat(s, &notes);
  ASSERT_EQ(bytes.size(), 64u * 32u);
  float f;
  std::memcpy(&f, &bytes[0], 4);
  EXPECT_EQ(f, 1.5f);
  std::memcpy(&f, &bytes[12], 4);
  EXPECT_NEAR(f, 0.25f, 1e-7);
  EXPECT_EQ(bytes[24], 255);
  EXPECT_EQ(bytes[27], 128);
  EXPECT_EQ(bytes[28], 255);  // w = 1 -> 256 clamped
  EXPECT_EQ(bytes[29], 128);
  ASSERT_FALSE(notes.empty());
  EXPECT_NE(notes[0].find("SH bands"), std::string::npos);

  const GaussianScene r = parse_splat(bytes.data(), bytes.size(), "mem");
  ASSERT_EQ(r.size(), 64u);
  EXPECT_EQ(r.sh_degree, 0);
  for (size_t i = 0; i < r.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(r.positions[3 * i + a], s.positions[3 * i + a]);
      EXPECT_NEAR(r.scales[3 * i + a], s.scales[3 * i + a], 1e-6);
      const double c0 = std::clamp(0.5 + kShC0 * s.sh_of(i)[a], 0.0, 1.0);
      EXPECT_NEAR(0.5 + kShC0 * r.sh_of(i)[a], c0, 0.5 / 255 + 1e-6);
    }
    EXPECT_NEAR(r.activated_opacity(i), s.activated_opacity(i), 0.5 / 255 + 1e-6);
    const Quat a = s.rotation(i).normalized(), b = r.rotation(i);
    const double d = std::fabs(a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z);
    EXPECT_GT(d, 0.9995);  // same rotation up to 8-bit quantisation
  }
  // A second pass is lossless: bytes are a fixed point.
  EXPECT_EQ(serialize_splat(r), bytes);
}

TEST(Splat, RejectsCorruptData) {
  std::vector<uint8_t> b(33, 0);
  EXPECT_THROW(parse_splat(b.data(), b.size(), "x.splat"), Error);
  EXPECT_THROW(parse_splat(b.data(), 0, "x.splat"), Error);
  GaussianScene s = testing::random_scene(2, 0, 2, false, false);
  std::vector<uint8_t> good = serialize_splat(s);
  std::vector<uint8_t> bad = good;
  const float nan = NAN;
  std::memcpy(&bad[4], &nan, 4);
  EXPECT_THROW(parse_splat(bad.data(), bad.size(), "x.splat"), Error);
  bad = good;
  const float neg = -1.f;
  std::memcpy(&bad[32 + 12], &neg, 4);
  EXPECT_THROW(parse_splat(bad.data(), bad.size(), "x.splat"), Error);
  bad = good;
  std::fill(bad.begin() + 28, bad.begin() + 32, 128);
  EXPECT_THROW(parse_splat(bad.data(), bad.size(), "x.splat"), Error);
}

TEST(SceneFormat, DetectsByContentNotExtension) {
  const GaussianScene s = testing::random_scene(40, 3, 3);
  const std::string splat_named_ply = temp("really_a_splat.ply");
  write_file_atomic(splat_named_ply, serialize_splat(s));
  SceneFormat f;
  std::vector<std::string> notes;
  const GaussianScene r = read_scene_file(splat_named_ply, &f, &notes);
  EXPECT_EQ(f, SceneFormat::kSplat);
  EXPECT_EQ(r.size(), 40u);
  ASSERT_FALSE(notes.empty());
  EXPECT_NE(notes[0].find("content is .splat"), std::string::npos);

  const std::string ply_named_splat = temp("really_a_ply.splat");
  write_file_atomic(ply_named_splat, serialize_ply(s));
  const GaussianScene p = read_scene_file(ply_named_splat, &f);
  EXPECT_EQ(f, SceneFormat::kPly);
  EXPECT_TRUE(testing::same_scene(p, s));

  const std::string text = temp("notes.txt");
  write_file_atomic(text, std::string("hello, this is not a scene at all.\n"));
  EXPECT_THROW(read_scene_file(text), Error);
  // 32 bytes of text: passes the size test, fails the record test.
  write_file_atomic(text, std::string("abcdefghijklmnopqrstuvwxyz012345"));
  EXPECT_THROW(read_scene_file(text), Error);
}

TEST(SceneFormat, WritesByExtensionAtomicallyAndNeverOverAnInput) {
  const GaussianScene s = testing::random_scene(30, 1, 4);
  const std::string in = temp("input.ply");
  write_scene_file(in, s, {});
  EXPECT_TRUE(testing::same_scene(read_ply(in), s));
  const std::string out = temp("out.splat");
  std::vector<std::string> notes;
  write_scene_file(out, s, {in}, &notes);
  EXPECT_EQ(read_scene_file(out).size(), 30u);
  EXPECT_FALSE(notes.empty());
  try {
    write_scene_file(in, s, {in});
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("refusing to overwrite"), std::string::npos);
  }
  EXPECT_THROW(write_scene_file(temp("out.obj"), s, {}), Error);
  GaussianScene bad = s;
  bad.positions[4] = NAN;
  EXPECT_THROW(write_scene_file(temp("bad.ply"), bad, {}), Error);
  EXPECT_THROW(write_scene_file(temp("bad.splat"), bad, {}), Error);
  EXPECT_FALSE(std::filesystem::exists(temp("bad.ply")));
  EXPECT_FALSE(std::filesystem::exists(temp("bad.splat")));
  // No temporary files left behind.
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(in).parent_path()))
    EXPECT_EQ(e.path().string().find(".tmp-"), std::string::npos) << e.path();
}

}  // namespace
}  // namespace isegman::edit
