#include "core/selection.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>

#include "core/error.h"
#include "core/scene.h"

namespace isegman {
namespace {

GaussianScene scene_of(size_t n) {
  GaussianScene s;
  s.resize(n, 1);
  for (size_t i = 0; i < n; ++i) s.positions[3 * i] = float(i);
  return s;
}

std::string temp_path(const std::string& name) {
  return ::testing::TempDir() + "/isegman_sel_" + std::to_string(::getpid()) + "_" + name;
}

TEST(Selection, RoundTripWithAndWithoutScores) {
  GaussianScene scene = scene_of(13);  // not a multiple of 8: exercises the last byte
  std::vector<bool> m(13, false);
  m[0] = m[7] = m[8] = m[12] = true;
  Selection s = Selection::from_mask(scene, m);
  EXPECT_EQ(s.count(), 4u);
  std::vector<uint8_t> bytes = serialize_selection(s);
  EXPECT_EQ(bytes.size(), 40u + 2u);
  // Gaussian 0 and 7 are bits 0 and 7 of byte 0; 8 and 12 bits 0 and 4 of byte 1.
  EXPECT_EQ(bytes[40], 0x81);
  EXPECT_EQ(bytes[41], 0x11);
  Selection r = parse_selection(bytes.data(), bytes.size(), "mem");
  EXPECT_EQ(r.mask, m);
  EXPECT_TRUE(r.score.empty());
  EXPECT_EQ(r.scene_fingerprint, scene.fingerprint());
  EXPECT_NO_THROW(r.check_matches(scene, "mem"));

  s.score.resize(13);
  for (int i = 0; i < 13; ++i) s.score[i] = 0.1f * float(i) - 0.3f;
  const std::string path = temp_path("a.isel");
  write_selection(path, s);
  Selection f = read_selection(path);
  EXPECT_EQ(f.mask, m);
  EXPECT_EQ(f.score, s.score);
  EXPECT_EQ(f.gaussian_count, 13u);
  std::remove(path.c_str());
}

TEST(Selection, DetectsOtherScene) {
  GaussianScene scene = scene_of(5);
  Selection s = Selection::all_of(scene);
  GaussianScene other = scene;
  other.opacity[2] = 1.f;
  EXPECT_THROW(s.check_matches(other, "sel"), Error);
  GaussianScene bigger = scene_of(6);
  try {
    s.check_matches(bigger, "sel.isel");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("sel.isel"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("5 Gaussians"), std::string::npos);
  }
}

TEST(Selection, AcceptsAFileSavedWithTheLegacyFingerprint) {
  // Selection files saved before the fingerprint changed carry the FNV-1a one.
  GaussianScene scene = scene_of(9);
  Selection s = Selection::all_of(scene);
  s.scene_fingerprint = scene.legacy_fingerprint();
  EXPECT_NO_THROW(s.check_matches(scene, "old.isel"));
  GaussianScene other = scene;
  other.opacity[2] = 1.f;
  EXPECT_THROW(s.check_matches(other, "old.isel"), Error);
}

TEST(Selection, RejectsCorruptFiles) {
  GaussianScene scene = scene_of(10);
  Selection s = Selection::none_of(scene);
  s.mask[3] = true;
  std::vector<uint8_t> good = serialize_selection(s);
  auto expect_bad = [](std::vector<uint8_t> b, const char* why) {
    EXPECT_THROW(parse_selection(b.data(), b.size(), "bad"), Error) << why;
  };
  std::vector<uint8_t> b = good;
  b[0] = 'X';
  expect_bad(b, "magic");
  b = good;
  b[8] = 2;
  expect_bad(b, "version");
  b = good;
  b.pop_back();
  expect_bad(b, "truncated");
  b = good;
  b.push_back(0);
  expect_bad(b, "trailing");
  b = good;
  b[41] |= 0x80;  // bit 15 > n = 10
  expect_bad(b, "bits past end");
  b = good;
  b[32] = 2;  // declared count
  expect_bad(b, "count");
  b = good;
  b[12] = 4;  // unknown flag
  expect_bad(b, "flags");
  expect_bad(std::vector<uint8_t>(good.begin(), good.begin() + 20), "short header");
  // Non-finite score.
  s.score.assign(10, 0.f);
  b = serialize_selection(s);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&b[b.size() - 4], &nan, 4);
  expect_bad(b, "nan score");
  EXPECT_THROW(read_selection(temp_path("missing.isel")), Error);
}

TEST(Selection, FromMaskChecksSize) {
  GaussianScene scene = scene_of(3);
  EXPECT_THROW(Selection::from_mask(scene, {true, false}), Error);
  EXPECT_TRUE(Selection::none_of(scene).empty());
  EXPECT_EQ(Selection::all_of(scene).count(), 3u);
}

}  // namespace
}  // namespace isegman
