#include "server/scene_binary.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace isegman::server {
namespace {

template <typename T>
T read_at(const std::vector<uint8_t>& b, size_t at) {
  T v;
  std::memcpy(&v, b.data() + at, sizeof(T));
  return v;
}

GaussianScene two_gaussians() {
  GaussianScene g;
  g.resize(2, 1);
  g.positions = {1, 2, 3, -4, 5.5f, -6};
  // Gaussian 0: scales (2, 1, 0.5), rotated 90 degrees about z; Gaussian 1: unit, identity.
  g.scales = {std::log(2.f), 0.f, std::log(0.5f), 0, 0, 0};
  const float h = std::sqrt(0.5f);
  g.rotations = {2 * h, 0, 0, 2 * h, 1, 0, 0, 0};  // unnormalised on purpose
  g.opacity = {0.f, 100.f};                      // 0.5 and ~1
  const float c0 = 0.28209479177387814f;
  float* sh0 = g.sh_of(0);
  sh0[0] = 0.f, sh0[1] = 0.25f / c0, sh0[2] = -2.f;  // r 0.5, g 0.75, b clamped to 0
  sh0[3] = 9.f;                                      // a degree-1 term: not in the base colour
  return g;
}

TEST(SceneBinary, SplatsCarryPositionColourOpacityAndCovariance) {
  const std::vector<uint8_t> b = pack_splats(two_gaussians(), 0x1122334455667788ull);
  // Degree 1: 9 rest coefficients (3 per channel) per Gaussian after the band scales.
  ASSERT_EQ(b.size(), kSceneBinaryHeaderBytes + 2 * kSplatRecordBytes + kColourRangeBytes + kShScalesBytes + 2 * 9);
  EXPECT_EQ(std::string(b.begin(), b.begin() + 4), "ISGS");
  EXPECT_EQ(read_at<uint32_t>(b, 4), 3u);
  EXPECT_EQ(read_at<uint32_t>(b, 8), 2u);
  EXPECT_EQ(read_at<uint32_t>(b, 12), kSplatRecordBytes);
  EXPECT_EQ(read_at<uint64_t>(b, 16), 0x1122334455667788ull);
  EXPECT_EQ(read_at<uint32_t>(b, 24), 1u);  // SH degree
  EXPECT_EQ(read_at<uint32_t>(b, 28), 9u);  // SH bytes per Gaussian

  const size_t r0 = kSceneBinaryHeaderBytes, r1 = r0 + kSplatRecordBytes;
  EXPECT_EQ(read_at<float>(b, r0), 1.f);
  EXPECT_EQ(read_at<float>(b, r0 + 8), 3.f);
  EXPECT_EQ(read_at<float>(b, r1 + 4), 5.5f);
  // With SH the colour bytes span the base colours' range: [0.5 - 2 C0, 1] here.
  const double lo = 0.5 - 2 * 0.28209479177387814, span = 1 - lo;
  const size_t range = kSceneBinaryHeaderBytes + 2 * kSplatRecordBytes;
  EXPECT_NEAR(read_at<float>(b, range), lo, 1e-6);
  EXPECT_EQ(read_at<float>(b, range + 4), 1.f);
  EXPECT_EQ(b[r0 + 12], std::lround((0.5 - lo) / span * 255));
  EXPECT_EQ(b[r0 + 13], std::lround((0.75 - lo) / span * 255));
  EXPECT_EQ(b[r0 + 14], 0);
  EXPECT_EQ(b[r0 + 15], 128);  // opacity sigmoid(0)
  EXPECT_EQ(b[r1 + 15], 255);
  // Rotating diag(4, 1, 0.25) by 90 degrees about z swaps the x and y variances.
  const float want0[6] = {1, 0, 0, 4, 0, 0.25f};
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(read_at<float>(b, r0 + 16 + 4 * k), want0[k], 1e-5) << k;
  const float want1[6] = {1, 0, 0, 1, 0, 1};
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(read_at<float>(b, r1 + 16 + 4 * k), want1[k], 1e-6) << k;
}

TEST(SceneBinary, ShRestIsQuantisedPerBand) {
  GaussianScene g = two_gaussians();
  g.sh_of(0)[4] = -4.5f;  // coefficient 1, green: half of the band's largest magnitude
  g.sh_of(1)[8] = 1.f;    // coefficient 2, blue
  const std::vector<uint8_t> b = pack_splats(g, 1);
  const size_t scales = kSceneBinaryHeaderBytes + 2 * kSplatRecordBytes + kColourRangeBytes,
               rest = scales + kShScalesBytes;
  EXPECT_EQ(read_at<float>(b, scales), 9.f);  // band 1: the largest |c|
  EXPECT_EQ(read_at<float>(b, scales + 4), 0.f);
  // Gaussian 0: coefficient 1 r = 9 -> 255, g = -4.5 -> 128 - 64 (127 * 0.5 rounded), the rest 0 -> 128.
  EXPECT_EQ(b[rest + 0], 255);
  EXPECT_EQ(b[rest + 1], 64);
  for (int j = 2; j < 9; ++j) EXPECT_EQ(b[rest + j], 128) << j;
  EXPECT_EQ(b[rest + 9 + 5], 128 + 14);  // 127 / 9 rounded
  // Degree 0: no SH section.
  GaussianScene flat;
  flat.resize(1, 0);
  EXPECT_EQ(pack_splats(flat, 1).size(), kSceneBinaryHeaderBytes + kSplatRecordBytes + kColourRangeBytes);
}

// The rasteriser clamps a colour at 0 only, after adding every SH degree, and blends
// colours above 1: the colour bytes span the scene's base colours, negative ones only
// where SH may bring them back up.
TEST(SceneBinary, ColourBytesSpanTheBaseColoursTheRasteriserUses) {
  const float c0 = 0.28209479177387814f;
  GaussianScene g = two_gaussians();
  g.sh_of(1)[0] = 1.f / c0;  // red 1.5
  g.sh_of(1)[1] = 9.f / c0;  // green 9.5: beyond the range the page is sent
  const std::vector<uint8_t> b = pack_splats(g, 1);
  const size_t range = kSceneBinaryHeaderBytes + 2 * kSplatRecordBytes;
  const float lo = read_at<float>(b, range), hi = read_at<float>(b, range + 4);
  EXPECT_LT(lo, 0.f);
  EXPECT_EQ(hi, kColourHigh);
  const size_t r1 = kSceneBinaryHeaderBytes + kSplatRecordBytes;
  EXPECT_NEAR(lo + (hi - lo) * b[r1 + 12] / 255.0, 1.5, (hi - lo) / 510.0 + 1e-6);
  EXPECT_EQ(b[r1 + 13], 255);

  // Without SH a negative colour is 0 in every direction; one above 1 still counts.
  GaussianScene flat;
  flat.resize(1, 0);
  flat.sh_of(0)[0] = 0.7f / c0;
  flat.sh_of(0)[1] = -1.f / c0;
  const std::vector<uint8_t> f = pack_splats(flat, 1);
  const size_t flat_range = kSceneBinaryHeaderBytes + kSplatRecordBytes;
  EXPECT_EQ(read_at<float>(f, flat_range), 0.f);
  EXPECT_FLOAT_EQ(read_at<float>(f, flat_range + 4), 1.2f);
  EXPECT_EQ(f[kSceneBinaryHeaderBytes + 12], 255);
  EXPECT_EQ(f[kSceneBinaryHeaderBytes + 13], 0);
}

TEST(SceneBinary, SelectionBytesFlagSelectedAndHidden) {
  const std::vector<bool> selected = {true, false, true, false};
  const std::vector<bool> hidden = {false, false, true, true};
  const std::vector<uint8_t> b = pack_selection(selected, hidden, 42, 7);
  ASSERT_EQ(b.size(), kSceneBinaryHeaderBytes + 4);
  EXPECT_EQ(std::string(b.begin(), b.begin() + 4), "ISGM");
  EXPECT_EQ(read_at<uint32_t>(b, 8), 4u);
  EXPECT_EQ(read_at<uint32_t>(b, 12), 2u);  // hidden count
  EXPECT_EQ(read_at<uint64_t>(b, 16), 42u);
  EXPECT_EQ(read_at<uint64_t>(b, 24), 7u);
  EXPECT_EQ(b[32], 1);
  EXPECT_EQ(b[33], 0);
  EXPECT_EQ(b[34], 3);
  EXPECT_EQ(b[35], 2);
  // Nothing hidden: an empty flag vector.
  const std::vector<uint8_t> c = pack_selection(selected, {}, 42, 8);
  EXPECT_EQ(read_at<uint32_t>(c, 12), 0u);
  EXPECT_EQ(c[34], 1);
}

}  // namespace
}  // namespace isegman::server
