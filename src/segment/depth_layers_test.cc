#include "segment/depth_layers.h"

#include <gtest/gtest.h>

namespace isegman::segment {
namespace {

TEST(DepthLayers, SplitsAtAnEmptyDepthRangeAndBridgesSmallOnes) {
  // Foliage spread over 3.8-4.4 (small gaps inside) and a wall at 5.5-5.6 behind it.
  std::vector<float> depth;
  std::vector<double> weight;
  for (double z = 3.8; z < 4.4; z += 0.02) depth.push_back(float(z)), weight.push_back(1.0);
  for (double z = 5.5; z < 5.6; z += 0.01) depth.push_back(float(z)), weight.push_back(3.0);
  const auto layers = depth_layers(depth, weight);
  ASSERT_EQ(layers.size(), 2u);
  EXPECT_NEAR(layers[0].near, 3.8, 0.05);
  EXPECT_NEAR(layers[0].far, 4.4, 0.06);
  EXPECT_NEAR(layers[1].near, 5.5, 0.06);
  EXPECT_NEAR(layers[0].weight + layers[1].weight, 1.0, 1e-9);
  std::printf("[ layers ] %.2f-%.2f (%.0f%%), %.2f-%.2f (%.0f%%)\n", layers[0].near, layers[0].far,
              100 * layers[0].weight, layers[1].near, layers[1].far, 100 * layers[1].weight);
}

TEST(DepthLayers, ContinuousDepthIsOneLayer) {
  std::vector<float> depth;
  std::vector<double> weight;
  for (double z = 2.0; z < 6.0; z += 0.03) depth.push_back(float(z)), weight.push_back(1.0);
  EXPECT_EQ(depth_layers(depth, weight).size(), 1u);
  EXPECT_TRUE(depth_layers({}, {}).empty());
}

TEST(DepthLayers, GateKeepsTheSeededLayerAndMakesTheRestNeutral) {
  // Two Gaussians in front (z = 2 along +z of an identity camera), one far behind (z = 4).
  GaussianScene scene;
  scene.positions = {0, 0, 2, 0.1f, 0, 2.02f, 0, 0, 4};
  scene.opacity = {0, 0, 0};
  Camera cam = Camera::look_at({0, 0, 0}, {0, 0, 1}, {0, -1, 0}, 64, 64, 60);
  ViewVotes positive{{0, 1, 2}, {100, 100, 500}}, neutral;
  ViewVotes front = positive, back = positive;
  GateReport r = gate_by_depth(scene, cam, front, neutral, {2.01}, nullptr);
  EXPECT_EQ(r.layers, 2);
  EXPECT_EQ(front.index, (std::vector<uint32_t>{0, 1}));
  EXPECT_EQ(neutral.index, (std::vector<uint32_t>{2}));
  EXPECT_NEAR(r.gated_share, 500.0 / 700.0, 1e-9);
  // A selection that lies behind wins over the seed.
  std::vector<bool> sel = {false, false, true};
  ViewVotes neutral_front;
  gate_by_depth(scene, cam, back, neutral_front, {2.01}, &sel);
  EXPECT_EQ(back.index, (std::vector<uint32_t>{2}));
  EXPECT_EQ(neutral_front.index, (std::vector<uint32_t>{0, 1}));
  // Neutral weight leaves the total: the gated Gaussian has no vote at all from this view.
  VoteAccumulator acc(3);
  ViewVotes total{{0, 1, 2}, {100, 100, 500}};
  acc.add(front, total, +1, &neutral);
  EXPECT_EQ(acc.total()[2], 0);
  EXPECT_EQ(acc.positive()[0], 100);
  acc.add(front, total, -1, &neutral);
  EXPECT_EQ(acc, VoteAccumulator(3));
}

}  // namespace
}  // namespace isegman::segment
