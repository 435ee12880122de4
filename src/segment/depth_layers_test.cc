#include "segment/depth_layers.h"

#include <gtest/gtest.h>

#include <cmath>

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

TEST(DepthLayers, LargeGaussiansBridgeTheEmptyBinsBetweenTheirCentresButNotARealGap) {
  // A coarse far surface: five big Gaussians at 10.0-10.8 whose centres leave 5 % gaps
  // (more than min_gap), each 0.3 deep (sd); a thin bar at 6.0 well in front of them.
  std::vector<float> depth = {6.0f, 6.01f, 10.0f, 10.5f, 11.0f, 11.55f, 12.1f};
  std::vector<double> weight = {2, 2, 1, 1, 1, 1, 1};
  std::vector<float> extent = {0.01f, 0.01f, 0.3f, 0.3f, 0.3f, 0.3f, 0.3f};
  const auto by_centres = depth_layers(depth, weight);
  const auto by_extents = depth_layers(depth, weight, {}, &extent);
  EXPECT_GE(by_centres.size(), 4u);  // the surface falls apart between its centres
  ASSERT_EQ(by_extents.size(), 2u);  // one surface, and the bar in front of it
  EXPECT_NEAR(by_extents[0].far, 6.01, 0.07);
  EXPECT_NEAR(by_extents[1].near, 10.0 - 0.3, 0.11);  // the layer spans the extents too
  EXPECT_NEAR(by_extents[1].weight, 5.0 / 9.0, 1e-9);
  DepthLayerOptions centres_only;
  centres_only.extent_sigmas = 0;
  EXPECT_EQ(depth_layers(depth, weight, centres_only, &extent).size(), by_centres.size());
  // A Gaussian below the empty share does not bridge: noise cannot join two layers.
  std::vector<float> z2 = {4.0f, 8.0f, 6.0f};
  std::vector<double> w2 = {1000, 1000, 0.1};
  std::vector<float> e2 = {0.01f, 0.01f, 3.0f};
  EXPECT_EQ(depth_layers(z2, w2, {}, &e2).size(), 2u);
}

TEST(DepthLayers, DepthExtentIsTheSpreadAlongTheViewAxis) {
  GaussianScene scene;
  scene.positions = {0, 0, 5, 0, 0, 5};
  scene.opacity = {0, 0};
  // A disc thin along z (0.01) and wide in x, y (0.5), and the same disc turned 90 degrees
  // about y, so its 0.5 extent points along the view axis.
  scene.scales = {std::log(0.5f), std::log(0.5f), std::log(0.01f), std::log(0.5f), std::log(0.5f), std::log(0.01f)};
  const float h = std::sqrt(0.5f);
  scene.rotations = {1, 0, 0, 0, h, 0, h, 0};
  Camera cam = Camera::look_at({0, 0, 0}, {0, 0, 1}, {0, -1, 0}, 64, 64, 60);
  EXPECT_NEAR(depth_extent(scene, cam, 0), 0.01, 1e-4);
  EXPECT_NEAR(depth_extent(scene, cam, 1), 0.5, 1e-4);
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

TEST(DepthLayers, LocalLayersSeparateABarFromASlantedWallBehindIt) {
  // A wall seen at a slant (depth 3.5 .. 4.5 across the view) with a bar 0.6 in front of
  // it on the left half: the bar's and the wall's depths overlap over the view, so one
  // histogram finds no gap, but in every 32-pixel region the bar is clearly in front.
  GaussianScene scene;
  std::vector<uint32_t> index;
  std::vector<int64_t> weight;
  std::vector<bool> selection;
  enum Kind { SelectedBar, UnselectedBar, Wall };
  std::vector<Kind> kind;
  auto add = [&](double x, double z, Kind k) {
    index.push_back(uint32_t(index.size()));
    weight.push_back(100);
    scene.positions.insert(scene.positions.end(), {float(x), 0.f, float(z)});
    scene.opacity.push_back(0);
    selection.push_back(k == SelectedBar);
    kind.push_back(k);
  };
  for (int i = 0; i <= 200; ++i) {
    const double x = -1 + 0.01 * i, wall = 4 + 0.5 * x;
    add(x, wall, Wall);
    if (x <= 0.1) add(x, wall - 0.6, x < -0.2 ? SelectedBar : UnselectedBar);
  }
  Camera cam = Camera::look_at({0, 0, 0}, {0, 0, 1}, {0, -1, 0}, 256, 256, 60);
  ViewVotes global{index, weight}, local{index, weight}, neutral;
  DepthLayerOptions global_options;
  global_options.region = 0;
  GateReport g = gate_by_depth(scene, cam, global, neutral, {3.0}, &selection, global_options);
  EXPECT_EQ(g.layers, 1);  // one layer: everything votes, the wall too
  EXPECT_EQ(global.index.size(), index.size());

  GateReport r = gate_by_depth(scene, cam, local, neutral, {3.0}, &selection);
  EXPECT_TRUE(r.local);
  std::vector<bool> kept(index.size(), false);
  for (uint32_t i : local.index) kept[i] = true;
  int wall_kept = 0, selected_lost = 0, continuation_kept = 0, continuation = 0;
  for (size_t i = 0; i < index.size(); ++i) {
    if (kind[i] == Wall) wall_kept += kept[i];
    if (kind[i] == SelectedBar) selected_lost += !kept[i];
    if (kind[i] == UnselectedBar) {
      ++continuation;
      continuation_kept += kept[i];
    }
  }
  EXPECT_EQ(wall_kept, 0);
  EXPECT_EQ(selected_lost, 0);
  // The bar's unselected continuation is in the selection's depth range next door: kept.
  EXPECT_EQ(continuation_kept, continuation);
  EXPECT_EQ(local.index.size() + neutral.index.size(), index.size());
}

}  // namespace
}  // namespace isegman::segment
