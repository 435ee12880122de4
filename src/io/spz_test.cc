#include "io/spz.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <cstring>

#include "core/error.h"
#include "core/sh.h"
#include "io/format_test_util.h"

namespace isegman {
namespace {

using testing_formats::differences;
using testing_formats::plausible_scene;

std::vector<uint8_t> gz(const std::vector<uint8_t>& in) {
  z_stream zs{};
  EXPECT_EQ(deflateInit2(&zs, 6, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY), Z_OK);
  std::vector<uint8_t> out(deflateBound(&zs, in.size()) + 64);
  zs.next_in = const_cast<Bytef*>(in.data());
  zs.avail_in = uInt(in.size());
  zs.next_out = out.data();
  zs.avail_out = uInt(out.size());
  EXPECT_EQ(deflate(&zs, Z_FINISH), Z_STREAM_END);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  return out;
}

std::vector<uint8_t> gunzip(const std::vector<uint8_t>& in) {
  z_stream zs{};
  EXPECT_EQ(inflateInit2(&zs, 16 + MAX_WBITS), Z_OK);
  std::vector<uint8_t> out(1 << 22);
  zs.next_in = const_cast<Bytef*>(in.data());
  zs.avail_in = uInt(in.size());
  zs.next_out = out.data();
  zs.avail_out = uInt(out.size());
  EXPECT_EQ(inflate(&zs, Z_FINISH), Z_STREAM_END);
  out.resize(zs.total_out);
  inflateEnd(&zs);
  return out;
}

// The tolerances SPZ's quantisation allows (half a step of each field).
void expect_within_spz_steps(const GaussianScene& a, const GaussianScene& b, int version) {
  const auto d = differences(a, b);
  EXPECT_LE(d.position, 0.5 / 4096 + 1e-6);
  EXPECT_LE(d.log_scale, 1.0 / 32 + 1e-5);
  EXPECT_LE(d.alpha, 0.5 / 255 + 1e-5);
  EXPECT_LE(d.dc, 0.5 / (0.15 * 255) + 1e-5);
  // v2 rebuilds w from 8-bit x, y, z: coarse when w is small (up to ~0.2 rad).
  EXPECT_LE(d.rotation, version >= 3 ? 0.004 : 0.2);
  EXPECT_LE(d.sh, 8.5 / 128 + 1e-5);  // buckets of 16 above degree 1 (8 for degree 1)
}

TEST(Spz, RoundTripsEveryVersionAndDegreeWithinItsQuantisation) {
  for (int version : {2, 3, 4})
    for (int degree = 0; degree <= 3; ++degree) {
      SCOPED_TRACE("version " + std::to_string(version) + " degree " + std::to_string(degree));
      const GaussianScene s = plausible_scene(300, degree, 7 + degree);
      SpzWriteOptions o;
      o.version = version;
      const std::vector<uint8_t> bytes = serialize_spz(s, o);
      EXPECT_TRUE(looks_like_spz(bytes.data(), bytes.size()));
      const GaussianScene r = parse_spz(bytes.data(), bytes.size(), "mem.spz");
      ASSERT_EQ(r.size(), s.size());
      EXPECT_EQ(r.sh_degree, degree);
      expect_within_spz_steps(s, r, version);
      // Decoded values are fixed points of the quantisation (rotations up to rounding).
      const std::vector<uint8_t> again = serialize_spz(r, o);
      const auto d2 = differences(r, parse_spz(again.data(), again.size(), "again.spz"));
      EXPECT_LE(d2.position + d2.log_scale + d2.dc + d2.sh, 1e-5);
    }
}

TEST(Spz, StoresRubAxesAndFlipsShSoColoursAreUnchanged) {
  GaussianScene s;
  s.resize(1, 3);
  s.positions = {1.0f, 2.0f, 3.0f};
  const Quat q = Quat(0.9, 0.1, 0.3, -0.2).normalized();
  s.rotations = {float(q.w), float(q.x), float(q.y), float(q.z)};
  SplitMix64 r(3);
  for (int k = 3; k < 48; ++k) s.sh[k] = float(r.range(-0.5, 0.5));
  SpzWriteOptions v3;
  v3.version = 3;  // one gzip stream: the raw attributes are easy to look at
  const std::vector<uint8_t> raw = gunzip(serialize_spz(s, v3));
  ASSERT_GE(raw.size(), 16u + 9 + 1 + 3 + 3 + 4 + 45);
  auto fixed = [&](int c) {
    int32_t v = int32_t(raw[16 + 3 * c] | raw[17 + 3 * c] << 8 | raw[18 + 3 * c] << 16);
    if (v & 0x800000) v -= 0x1000000;
    return v / 4096.0;
  };
  EXPECT_EQ(fixed(0), 1.0);
  EXPECT_EQ(fixed(1), -2.0);  // RDF y down -> RUB y up
  EXPECT_EQ(fixed(2), -3.0);  // RDF z forward -> RUB z back
  // Read the stored SH as RUB coefficients: the colour seen along RUB direction
  // (x, -y, -z) must equal the original colour along (x, y, z).
  const uint8_t* sh = raw.data() + 16 + 9 + 1 + 3 + 3 + 4;
  float rub[48] = {};
  for (int k = 0; k < 45; ++k) rub[3 + k] = (float(sh[k]) - 128.0f) / 128.0f;
  const std::vector<uint8_t> file = serialize_spz(s, v3);
  const GaussianScene back = parse_spz(file.data(), file.size(), "mem");
  for (int c = 0; c < 3; ++c) rub[c] = back.sh[c];  // the DC band needs no flip
  const float dirs[2][3] = {{0.2f, 0.5f, 0.84f}, {-0.7f, 0.1f, 0.7f}};
  for (const float* d : dirs) {
    const float n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    float want[3], got[3];
    sh_to_rgb(3, back.sh.data(), d[0] / n, d[1] / n, d[2] / n, want);
    sh_to_rgb(3, rub, d[0] / n, -d[1] / n, -d[2] / n, got);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 1e-5);
  }
  // Rotation: conjugated by the flip, R_rub = F R F.
  const Quat rq = back.rotation(0).normalized();
  EXPECT_GT(std::fabs(rq.w * q.w + rq.x * q.x + rq.y * q.y + rq.z * q.z), 0.99999);
}

TEST(Spz, ReadsVersion1Float16PositionsAndVersion2Rotations) {
  // One Gaussian, version 1: float16 positions, 3-byte rotation.
  std::vector<uint8_t> raw = {'N', 'G', 'S', 'P', 1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0};
  const uint16_t half[3] = {0x3C00, 0xC000, 0x3800};  // 1, -2, 0.5
  for (uint16_t h : half) raw.insert(raw.end(), {uint8_t(h), uint8_t(h >> 8)});
  raw.push_back(255);                      // alpha
  raw.insert(raw.end(), {128, 128, 128});  // colour
  raw.insert(raw.end(), {160, 160, 160});  // scales: 160/16 - 10 = 0
  raw.insert(raw.end(), {128, 128, 128});  // rotation xyz ~ 0 -> identity
  const std::vector<uint8_t> file = gz(raw);
  const GaussianScene s = parse_spz(file.data(), file.size(), "v1.spz");
  ASSERT_EQ(s.size(), 1u);
  EXPECT_FLOAT_EQ(s.positions[0], 1.0f);
  EXPECT_FLOAT_EQ(s.positions[1], 2.0f);  // RUB -2 -> RDF 2
  EXPECT_FLOAT_EQ(s.positions[2], -0.5f);
  EXPECT_FLOAT_EQ(s.scales[0], 0.0f);
  EXPECT_NEAR(s.rotations[0], 1.0f, 1e-4);
}

TEST(Spz, TruncatedOrCorruptFilesNameTheFileAndNeverCrash) {
  const GaussianScene s = plausible_scene(200, 2, 11);
  for (int version : {3, 4}) {
    SpzWriteOptions o;
    o.version = version;
    const std::vector<uint8_t> bytes = serialize_spz(s, o);
    for (size_t cut : {size_t(0), size_t(1), size_t(10), size_t(31), bytes.size() / 2, bytes.size() - 1}) {
      try {
        parse_spz(bytes.data(), cut, "broken.spz");
        ADD_FAILURE() << "accepted a file cut at " << cut;
      } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()).rfind("broken.spz: ", 0), 0u) << e.what();
      }
    }
    SplitMix64 r(version);
    for (int trial = 0; trial < 300; ++trial) {
      std::vector<uint8_t> bad = bytes;
      for (int k = 0; k < 3; ++k) bad[r.next() % bad.size()] ^= uint8_t(1 + r.next() % 255);
      try {
        const GaussianScene g = parse_spz(bad.data(), bad.size(), "flipped.spz");
        EXPECT_EQ(g.size() * 3, g.positions.size());
      } catch (const Error&) {
      }
    }
  }
  const std::vector<uint8_t> text = {'h', 'e', 'l', 'l', 'o'};
  EXPECT_THROW(parse_spz(text.data(), text.size(), "x.spz"), Error);
}

TEST(Spz, LargeScenesUseFewerFractionalBitsAndSayWhy) {
  GaussianScene s = plausible_scene(10, 0, 5);
  s.positions[0] = 5000.0f;  // beyond 12 fractional bits' +-2048
  std::vector<std::string> notes;
  const std::vector<uint8_t> bytes = serialize_spz(s, {}, &notes);
  ASSERT_FALSE(notes.empty());
  EXPECT_NE(notes[0].find("fractional bits"), std::string::npos);
  const GaussianScene r = parse_spz(bytes.data(), bytes.size(), "mem");
  EXPECT_NEAR(r.positions[0], 5000.0f, 0.01f);
}

}  // namespace
}  // namespace isegman

namespace isegman {
namespace {

TEST(Spz, HighlyCompressibleScenesStillRoundTrip) {
  // Identical Gaussians compress far beyond 1000:1 per zstd stream; still a valid file.
  GaussianScene s;
  s.resize(200000, 3);
  for (int version : {3, 4}) {
    SpzWriteOptions o;
    o.version = version;
    const std::vector<uint8_t> bytes = serialize_spz(s, o);
    const GaussianScene r = parse_spz(bytes.data(), bytes.size(), "same.spz");
    EXPECT_EQ(r.size(), s.size());
  }
}

}  // namespace
}  // namespace isegman
