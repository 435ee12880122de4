#include "segment/negative_islands.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace isegman::segment {
namespace {

// Gaussians of scale 1 cm in a row along x: the object (0..9, x = 0..9 cm) and, 20 cm
// apart, a box the selection also took (10..19, x = 30..39 cm); with `bridge`, the gap is
// filled with selected Gaussians (20..39) that join the two.
GaussianScene row(bool bridge) {
  GaussianScene s;
  auto add = [&](float x) {
    s.positions.insert(s.positions.end(), {x, 0.f, 0.f});
    s.scales.insert(s.scales.end(), {std::log(0.01f), std::log(0.01f), std::log(0.002f)});
    s.rotations.insert(s.rotations.end(), {1, 0, 0, 0});
    s.opacity.push_back(0);
  };
  for (int i = 0; i < 20; ++i) add(0.01f * float(i < 10 ? i : i + 20));
  if (bridge)
    for (int i = 0; i < 20; ++i) add(0.01f * float(10 + i));
  return s;
}

TEST(NegativeIslands, ANegativeClickTakesOutTheIslandItShows) {
  const GaussianScene s = row(false);
  const CentreIndex index(s);
  std::vector<bool> selection(s.size(), true);
  IslandOptions link;
  const NegativeCut cut = cut_negative_islands(selection, s, index, {2, 3}, {{15}}, link);
  std::printf("[ negative islands ] %zu of %zu taken out\n", cut.removed, s.size());
  EXPECT_EQ(cut.removed, 10u);
  EXPECT_EQ(cut.cut, 1);
  EXPECT_EQ(cut.joined, 0);
  for (size_t i = 0; i < s.size(); ++i) EXPECT_EQ(selection[i], i < 10) << i;
  // The same click again changes nothing: its pixel shows nothing selected now.
  std::vector<bool> again = selection;
  EXPECT_EQ(cut_negative_islands(again, s, index, {2}, {{}}, link).removed, 0u);
  EXPECT_EQ(again, selection);
}

TEST(NegativeIslands, NothingLeavesWhereTheIslandHoldsAPositiveClick) {
  // Joined by touching Gaussians: the negative click is on the object's own island.
  const GaussianScene s = row(true);
  const CentreIndex index(s);
  std::vector<bool> selection(s.size(), true);
  const NegativeCut cut = cut_negative_islands(selection, s, index, {2}, {{15}}, IslandOptions{});
  EXPECT_EQ(cut.removed, 0u);
  EXPECT_EQ(cut.joined, 1);
  EXPECT_EQ(std::count(selection.begin(), selection.end(), true), 40);
  // Gaussians that are not selected join nothing: without the bridge selected, the box goes.
  for (size_t i = 20; i < 40; ++i) selection[i] = false;
  EXPECT_EQ(cut_negative_islands(selection, s, index, {2}, {{15}}, IslandOptions{}).removed, 10u);
  // A click on the object itself (its Gaussians also a positive click's) takes out nothing.
  std::vector<bool> all(s.size(), true);
  EXPECT_EQ(cut_negative_islands(all, s, index, {2}, {{2}}, IslandOptions{}).removed, 0u);
}

TEST(NegativeIslands, APixelShowsTheSelectedGaussiansThatBlendMostThere) {
  // Two Gaussians on the camera's axis, the front one more transparent; a third beside them.
  GaussianScene s;
  auto add = [&](Vec3 p, float opacity_logit) {
    s.positions.insert(s.positions.end(), {float(p.x), float(p.y), float(p.z)});
    s.scales.insert(s.scales.end(), {std::log(0.05f), std::log(0.05f), std::log(0.05f)});
    s.rotations.insert(s.rotations.end(), {1, 0, 0, 0});
    s.opacity.push_back(opacity_logit);
    s.sh.insert(s.sh.end(), {0.5f, 0.5f, 0.5f});
  };
  add({0, 0, 0}, 0.f);     // front, opacity 0.5
  add({0, 0.5, 0}, 4.f);   // behind it, nearly opaque
  add({0.4, 0, 0}, 4.f);   // off the axis
  const Camera cam = Camera::look_at({0, -2, 0}, {0, 0, 0}, {0, 0, 1}, 64, 48, 60);
  const PreparedFrame frame = prepare_frame(s, cam);
  const int cx = 32, cy = 24;
  std::vector<bool> all(3, true), back_only = {false, true, false}, none(3, false);
  // The front blends 0.5, the back 0.5 x 0.98: both at least half the largest.
  EXPECT_EQ(selected_at_pixel(frame, all, cx, cy), (std::vector<uint32_t>{0, 1}));
  EXPECT_EQ(selected_at_pixel(frame, back_only, cx, cy), (std::vector<uint32_t>{1}));
  EXPECT_TRUE(selected_at_pixel(frame, none, cx, cy).empty());
  EXPECT_TRUE(selected_at_pixel(frame, all, -1, cy).empty());  // off the image
}

}  // namespace
}  // namespace isegman::segment
