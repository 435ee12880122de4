// Real data: every training camera of each fixture scene is rendered and compared with
// its training photo; the mean PSNR must be within 0.5 dB of the trainer's own figure.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "io/image_io.h"
#include "io/scene_loader.h"
#include "render/rasterizer.h"

namespace fs = std::filesystem;

namespace isegman {
namespace {

class FixturePsnr : public ::testing::TestWithParam<std::string> {};

TEST_P(FixturePsnr, RendersReproduceTheTrainingPhotos) {
  const fs::path root = fs::path(ISEGMAN_FIXTURES_DIR) / GetParam();
  if (!fs::exists(root / "meta.json")) GTEST_SKIP() << "fixture " << root << " not found; skipping real-data test";
  nlohmann::json meta = nlohmann::json::parse(std::ifstream(root / "meta.json"));
  const double trainer_psnr = meta.at("train_psnr").get<double>();
  SceneBundle b = load_scene((root / "scene").string());
  ASSERT_FALSE(b.cameras.empty());
  RenderSettings s;
  for (int c = 0; c < 3; ++c) s.background[c] = meta.at("background")[c].get<float>();
  double sum = 0, worst = 1e9;
  for (const Camera& cam : b.cameras) {
    ASSERT_FALSE(cam.image_path.empty()) << "no photo for camera " << cam.name;
    Image photo = read_image(cam.image_path, 3);
    ASSERT_EQ(photo.width, cam.width);
    RenderOutput r = render(b.gaussians, cam, s);
    const double p = psnr(r.color, photo);
    sum += p;
    worst = std::min(worst, p);
  }
  const double mean = sum / double(b.cameras.size());
  std::printf("[ fixture ] %s: mean PSNR %.3f dB over %zu views (worst %.2f); trainer reported %.2f dB\n",
              GetParam().c_str(), mean, b.cameras.size(), worst, trainer_psnr);
  EXPECT_NEAR(mean, trainer_psnr, 0.5);
}

INSTANTIATE_TEST_SUITE_P(Fixtures, FixturePsnr, ::testing::Values("fern", "dtu24"));

}  // namespace
}  // namespace isegman
