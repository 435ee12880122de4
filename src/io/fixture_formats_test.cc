// Real data: each fixture scene's PLY goes through every lossy format and back; the
// attributes stay within the formats' quantisation and renders of the round-tripped scene
// match renders of the original (PSNR over a few training views).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "io/format_test_util.h"
#include "io/gaussian_file.h"
#include "io/scene_loader.h"
#include "render/rasterizer.h"

namespace fs = std::filesystem;

namespace isegman {
namespace {

using testing_formats::differences;

struct Case {
  SplatFormat format;
  double min_psnr;  // dB, renders of the round trip vs renders of the original
};

class FixtureFormats : public ::testing::TestWithParam<std::string> {};

TEST_P(FixtureFormats, RoundTripsKeepRendersClose) {
  const fs::path root = fs::path(ISEGMAN_FIXTURES_DIR) / GetParam() / "scene";
  if (!fs::exists(root)) GTEST_SKIP() << "fixture " << root << " not found; skipping real-data test";
  const SceneBundle b = load_scene(root.string());
  const GaussianScene& s = b.gaussians;
  for (const Case& c : {Case{SplatFormat::kSpz, 33.0}, Case{SplatFormat::kCompressedPly, 38.0},
                        Case{SplatFormat::kSog, 42.0}}) {
    SCOPED_TRACE(splat_format_name(c.format));
    std::vector<uint32_t> order;
    const std::vector<uint8_t> bytes = serialize_gaussians(s, c.format, nullptr, &order);
    const GaussianScene r = parse_gaussians(bytes.data(), bytes.size(), c.format, "roundtrip");
    ASSERT_EQ(r.size(), s.size());
    const auto d = differences(s, r, order);
    if (c.format == SplatFormat::kSpz) {
      EXPECT_LE(d.position, 0.5 / 4096 + 1e-5);
      EXPECT_LE(d.alpha, 0.5 / 255 + 1e-5);
      EXPECT_LE(d.rotation, 0.005);  // 9-bit smallest-three components
    }
    double sum = 0, worst = 1e9;
    const size_t views = std::min<size_t>(3, b.cameras.size());
    for (size_t k = 0; k < views; ++k) {
      const Camera& cam = b.cameras[k * b.cameras.size() / views];
      const double p = psnr(render(s, cam).color, render(r, cam).color);
      sum += p;
      worst = std::min(worst, p);
    }
    std::printf("%s %s: %zu bytes (%.1f%% of PLY), max errors: position %.3g, log-scale %.3g, alpha %.3g, "
                "rotation %.3g rad, f_dc %.3g, f_rest %.3g; render PSNR mean %.2f dB, worst %.2f dB\n",
                GetParam().c_str(), splat_format_name(c.format), bytes.size(),
                100.0 * bytes.size() / serialize_gaussians(s, SplatFormat::kPly).size(), d.position, d.log_scale,
                d.alpha, d.rotation, d.dc, d.sh, sum / views, worst);
    EXPECT_GE(worst, c.min_psnr);
  }
}

INSTANTIATE_TEST_SUITE_P(Fixtures, FixtureFormats, ::testing::Values("fern", "dtu24"));

}  // namespace
}  // namespace isegman
