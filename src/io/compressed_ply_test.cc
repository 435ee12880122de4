#include "io/compressed_ply.h"

#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "io/format_test_util.h"

namespace isegman {
namespace {

using testing_formats::differences;
using testing_formats::plausible_scene;

TEST(CompressedPly, RoundTripsWithinChunkQuantisation) {
  for (int degree = 0; degree <= 3; ++degree) {
    SCOPED_TRACE("degree " + std::to_string(degree));
    const GaussianScene s = plausible_scene(1000, degree, 21 + degree);
    std::vector<uint32_t> order;
    const std::vector<uint8_t> bytes = serialize_compressed_ply(s, true, &order);
    EXPECT_TRUE(is_compressed_ply(bytes.data(), bytes.size()));
    const GaussianScene r = parse_compressed_ply(bytes.data(), bytes.size(), "mem.compressed.ply");
    ASSERT_EQ(r.size(), s.size());
    EXPECT_EQ(r.sh_degree, degree);
    const auto d = differences(s, r, order);
    // Positions: half a step of 10 bits over a chunk's range (at most the scene's 6 units).
    EXPECT_LE(d.position, 0.5 * 6.0 / 1023 + 1e-5);
    EXPECT_LE(d.log_scale, 0.5 * 6.0 / 1023 + 1e-5);
    EXPECT_LE(d.alpha, 0.5 / 255 + 1e-5);
    EXPECT_LE(d.dc, 0.5 / 255 * (1.0 / 0.2820948) * 1.0 + 1e-4);  // colour range <= 1 (in 0.5 + C0 f_dc)
    EXPECT_LE(d.rotation, 0.004);
    EXPECT_LE(d.sh, 8.0 / 256 / 2 + 1e-5);
  }
}

TEST(CompressedPly, KeepsOrderWhenAskedAndMortonOrderTightensChunks) {
  const GaussianScene s = plausible_scene(65536, 0, 3, 50.0);  // 256 chunks
  std::vector<uint32_t> order;
  const std::vector<uint8_t> kept = serialize_compressed_ply(s, false, &order);
  for (size_t i = 0; i < order.size(); ++i) ASSERT_EQ(order[i], i);
  const auto dk = differences(s, parse_compressed_ply(kept.data(), kept.size(), "k"), order);
  const std::vector<uint8_t> sorted = serialize_compressed_ply(s, true, &order);
  const auto ds = differences(s, parse_compressed_ply(sorted.data(), sorted.size(), "s"), order);
  // Chunks straddling a Morton cell boundary still span the scene, so compare the mean.
  EXPECT_LT(ds.mean_position, dk.mean_position / 3);
}

TEST(CompressedPly, TruncatedOrCorruptFilesNameTheFile) {
  const GaussianScene s = plausible_scene(600, 1, 9);
  const std::vector<uint8_t> bytes = serialize_compressed_ply(s);
  for (size_t cut : {size_t(3), size_t(100), bytes.size() / 2, bytes.size() - 1}) {
    try {
      parse_compressed_ply(bytes.data(), cut, "cut.compressed.ply");
      ADD_FAILURE() << "accepted a file cut at " << cut;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()).rfind("cut.compressed.ply: ", 0), 0u) << e.what();
    }
  }
  std::string text(bytes.begin(), bytes.end());
  const size_t at = text.find("element chunk 3");
  ASSERT_NE(at, std::string::npos);
  text[at + 14] = '9';  // wrong chunk count
  EXPECT_THROW(parse_compressed_ply(reinterpret_cast<const uint8_t*>(text.data()), text.size(), "x"), Error);
}

}  // namespace
}  // namespace isegman
