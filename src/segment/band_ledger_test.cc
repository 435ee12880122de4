#include "segment/band_ledger.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "render/visibility.h"
#include "segment/test_masks.h"

namespace isegman::segment {
namespace {

// 4000 small Gaussians scattered over a wall 3-5 units in front of the camera, so every tile
// lists many at different depths.
GaussianScene scattered_scene() {
  GaussianScene g;
  g.sh_degree = 0;
  uint64_t state = 12345;
  auto uniform = [&]() {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return double(state >> 11) / double(1ull << 53);
  };
  for (int i = 0; i < 4000; ++i) {
    const double x = -1.6 + 3.2 * uniform(), y = -1.0 + 2.0 * uniform(), z = 3 + 2 * uniform();
    g.positions.insert(g.positions.end(), {float(x), float(y), float(z)});
    g.scales.insert(g.scales.end(), 3, float(std::log(0.02 + 0.04 * uniform())));
    g.rotations.insert(g.rotations.end(), {1, 0, 0, 0});
    const double o = 0.3 + 0.6 * uniform();
    g.opacity.push_back(float(std::log(o / (1 - o))));
    g.sh.insert(g.sh.end(), {0.f, 0.f, 0.f});
  }
  return g;
}

Camera wall_camera() {
  Camera c;
  c.width = 160;
  c.height = 96;
  c.fx = c.fy = 150;
  c.cx = 80;
  c.cy = 48;
  return c;
}

// A mask of the camera's size over columns [x0, x1) and rows [y0, y1).
Image box(int x0, int x1, int y0, int y1) { return testing::box_mask(160, 96, x0, x1, y0, y1); }

struct Case {
  GaussianScene scene = scattered_scene();
  PreparedFrame frame;
  Image band;
  std::vector<uint32_t> shown;        // the mask's Gaussians
  std::map<uint32_t, int64_t> truth;  // the band's votes in one pass, the mask's Gaussians left out
  explicit Case(bool compact) {
    frame = prepare_frame(scene, wall_camera());
    if (compact) compact_frame(frame, RenderSettings{}, false);
    // The mask a block in the middle, the band a wide frame around it (4x its area).
    const Image mask = box(60, 100, 30, 66);
    band = box(20, 140, 6, 90);
    for (size_t i = 0; i < band.data.size(); ++i)
      if (mask.data[i] > 0.5f) band.data[i] = 0.f;
    shown = masked_votes(frame, mask, 2).index;
    std::vector<bool> in_mask(scene.size(), false);
    for (uint32_t j : shown) in_mask[j] = true;
    const ViewVotes all = masked_votes(frame, band, 2);
    for (size_t i = 0; i < all.index.size(); ++i)
      if (!in_mask[all.index[i]]) truth[all.index[i]] = all.weight[i];
  }
};

void add(std::map<uint32_t, int64_t>& sums, const ViewVotes& v) {
  for (size_t i = 0; i < v.index.size(); ++i) sums[v.index[i]] += v.weight[i];
}

TEST(BandLedger, ASupportedGaussianHasItsWholeBandWeightWhateverWaits) {
  Case c(true);
  ASSERT_GT(c.truth.size(), 200u);
  BandLedger ledger(c.scene);
  auto frame_of = [&](size_t) -> const PreparedFrame& { return c.frame; };
  std::map<uint32_t, int64_t> sums;
  std::vector<bool> supported(c.scene.size(), false);
  // Checks that every supported Gaussian outside the mask holds exactly its one-pass weight.
  auto check = [&](const char* when) {
    size_t checked = 0;
    for (uint32_t j = 0; j < c.scene.size(); ++j) {
      if (!supported[j]) continue;
      auto t = c.truth.find(j);
      const int64_t want = t == c.truth.end() ? 0 : t->second;
      auto s = sums.find(j);
      const int64_t got = s == sums.end() ? 0 : s->second;
      EXPECT_EQ(got, want) << when << ": Gaussian " << j;
      checked += t != c.truth.end();
    }
    return checked;
  };
  // First a vote of the mask's Gaussians alone: no band tile lists a Gaussian with a positive
  // vote outside the mask, so every one waits.
  std::vector<uint32_t> first = c.shown;
  for (uint32_t j : first) supported[j] = true;
  for (const ViewVotes& v : ledger.add_positive(first, frame_of, 2)) add(sums, v);
  add(sums, ledger.add_view(0, c.frame, c.band, c.shown, 2));
  const size_t waited = ledger.waiting_tiles();
  check("after the view");
  // Then one band Gaussian alone, the one of largest weight (its splat reaches several
  // tiles): only the tiles it reaches may have been blended for it.
  uint32_t heaviest = 0;
  int64_t heaviest_weight = -1;
  for (const auto& [j, w] : c.truth)
    if (!supported[j] && w > heaviest_weight) {
      heaviest = j;
      heaviest_weight = w;
    }
  ASSERT_GE(heaviest_weight, 0);
  supported[heaviest] = true;
  for (const ViewVotes& v : ledger.add_positive({heaviest}, frame_of, 2)) add(sums, v);
  EXPECT_EQ(check("after one Gaussian's vote"), 1u);
  const size_t after_one = ledger.waiting_tiles();
  EXPECT_GT(after_one, 0u);
  EXPECT_LT(after_one, waited);
  // Then every band Gaussian.
  std::vector<uint32_t> third;
  for (const auto& [j, w] : c.truth) third.push_back(j);
  for (uint32_t j : third) supported[j] = true;
  for (const ViewVotes& v : ledger.add_positive(third, frame_of, 2)) add(sums, v);
  const size_t all_checked = check("after every band Gaussian's vote");
  std::printf("band of %zu Gaussians: %zu tiles waited, %zu after one Gaussian's vote, %zu at the end; %zu blended\n",
              c.truth.size(), waited, after_one, ledger.waiting_tiles(), ledger.blended_tiles());
  EXPECT_EQ(all_checked, c.truth.size());
  EXPECT_EQ(sums.size(), c.truth.size());  // every band Gaussian counted, none twice
}

TEST(BandLedger, AFrameNotCompactedWaitsForNothing) {
  Case c(false);
  BandLedger ledger(c.scene);
  std::map<uint32_t, int64_t> sums;
  add(sums, ledger.add_view(0, c.frame, c.band, c.shown, 2));
  EXPECT_EQ(ledger.waiting_tiles(), 0u);
  EXPECT_EQ(sums, c.truth);
}

}  // namespace
}  // namespace isegman::segment
