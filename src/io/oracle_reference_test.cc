// Files written by the reference tools (npm @playcanvas/splat-transform 2.7.1 and spz-js
// 1.2.5; tools/format_oracles/make_reference.sh regenerates them) from
// tests/data/formats/source.ply: isegman must read each back to the source within the
// format's stated per-attribute tolerances.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "io/format_test_util.h"
#include "io/gaussian_file.h"
#include "io/ply.h"
#include "io/spz.h"

namespace fs = std::filesystem;

namespace isegman {
namespace {

using testing_formats::Differences;
using testing_formats::differences;

const fs::path kData = fs::path(ISEGMAN_SOURCE_DIR) / "tests" / "data" / "formats";

// Tools may reorder (Morton order): pair each decoded Gaussian with the nearest source
// centre (the source's Gaussians are ~0.1 apart, the formats' position error < 0.01).
std::vector<uint32_t> match_by_position(const GaussianScene& src, const GaussianScene& got) {
  std::vector<uint32_t> order(got.size());
  for (size_t j = 0; j < got.size(); ++j) {
    double best = 1e300;
    for (size_t i = 0; i < src.size(); ++i) {
      double d = 0;
      for (int a = 0; a < 3; ++a) {
        const double e = src.positions[3 * i + a] - got.positions[3 * j + a];
        d += e * e;
      }
      if (d < best) {
        best = d;
        order[j] = uint32_t(i);
      }
    }
  }
  return order;
}

struct Tolerance {
  const char* file;
  SplatFormat format;
  Differences max;  // per-attribute bounds
  bool unconverted_axes = false;  // the writer stored PLY (RDF) axes instead of RUB
};

TEST(OracleReference, ToolWrittenFilesReadBackToTheSource) {
  const GaussianScene src = read_ply((kData / "source.ply").string());
  ASSERT_EQ(src.size(), 300u);
  ASSERT_EQ(src.sh_degree, 3);
  // position, mean position, log-scale, alpha, rotation (rad), f_dc, f_rest
  const Tolerance cases[] = {
      {"splat-transform_v3.spz", SplatFormat::kSpz, {0.5 / 4096 + 1e-6, 1, 1.0 / 32 + 1e-5, 0.5 / 255 + 1e-5, 0.005, 0.5 / 38.25 + 1e-5, 8.5 / 128}},
      {"splat-transform_v4.spz", SplatFormat::kSpz, {0.5 / 4096 + 1e-6, 1, 1.0 / 32 + 1e-5, 0.5 / 255 + 1e-5, 0.005, 0.5 / 38.25 + 1e-5, 8.5 / 128}},
      // spz-js 1.2.5 writes version 2 without converting PLY axes to RUB.
      {"spz-js_v2.spz", SplatFormat::kSpz, {0.5 / 4096 + 1e-6, 1, 1.0 / 32 + 1e-5, 0.5 / 255 + 1e-5, 0.2, 0.5 / 38.25 + 1e-5, 8.5 / 128}, true},
      {"splat-transform.compressed.ply", SplatFormat::kCompressedPly, {0.0025, 1, 0.002, 0.5 / 255 + 1e-5, 0.005, 0.007, 1.0 / 64 + 1e-5}},
      // SOG: 8-bit smallest-three rotations, 256-entry codebooks, and here a 256-entry SH
      // palette (k-means) for 300 Gaussians, hence the loose f_rest bound.
      {"splat-transform.sog", SplatFormat::kSog, {0.001, 1, 0.02, 1.0 / 255 + 1e-5, 0.04, 0.02, 0.35}},
  };
  for (const Tolerance& t : cases) {
    SCOPED_TRACE(t.file);
    const LoadedGaussians l = load_gaussians((kData / t.file).string());
    EXPECT_EQ(l.format, t.format);
    ASSERT_EQ(l.scene.size(), src.size());
    EXPECT_EQ(l.scene.sh_degree, 3);
    const GaussianScene got = t.unconverted_axes ? flip_y_z(l.scene) : l.scene;
    const Differences d = differences(src, got, match_by_position(src, got));
    std::printf("%-32s position %.3g, log-scale %.3g, alpha %.3g, rotation %.3g rad, f_dc %.3g, f_rest %.3g\n", t.file,
                d.position, d.log_scale, d.alpha, d.rotation, d.dc, d.sh);
    EXPECT_LE(d.position, t.max.position);
    EXPECT_LE(d.log_scale, t.max.log_scale);
    EXPECT_LE(d.alpha, t.max.alpha);
    EXPECT_LE(d.rotation, t.max.rotation);
    EXPECT_LE(d.dc, t.max.dc);
    EXPECT_LE(d.sh, t.max.sh);
  }
}

}  // namespace
}  // namespace isegman
