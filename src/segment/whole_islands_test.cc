#include "segment/whole_islands.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace isegman::segment {
namespace {

// Gaussians of scale 1 cm (flat along z) in a row along x: the part the votes select
// (0..9, x = 0..9 cm), the rest of the whole touching it (10..19, x = 10..19 cm), and a
// neighbour of `neighbour` Gaussians standing 10 cm apart (from x = 30 cm on). The whole
// rule selects everything after the part; `own` of the neighbour's Gaussians (from the far
// end) also pass on their own votes: a few of a neighbour's Gaussians seen mostly by the
// views whose masks took it in.
struct Row {
  GaussianScene scene;
  VoteAccumulator votes;
  std::vector<bool> selection;
  explicit Row(uint32_t neighbour = 10, uint32_t own = 0)
      : votes(20 + neighbour), selection(20 + neighbour, true) {
    const uint32_t n = 20 + neighbour;
    ViewVotes positive, total;
    for (uint32_t i = 0; i < n; ++i) {
      const float x = 0.01f * float(i < 20 ? i : i + 10);
      scene.positions.insert(scene.positions.end(), {x, 0.f, 0.f});
      scene.scales.insert(scene.scales.end(), {std::log(0.01f), std::log(0.01f), std::log(0.002f)});
      scene.rotations.insert(scene.rotations.end(), {1, 0, 0, 0});
      scene.opacity.push_back(0);
      const int64_t a = int64_t(1) << 24;
      total.index.push_back(i);
      total.weight.push_back(a);
      positive.index.push_back(i);
      positive.weight.push_back(i < 10 || i >= n - own ? a : a * 4 / 10);
    }
    votes.add(positive, total);
  }
};

TEST(WholeIslands, WhatTheWholeRuleAloneSelectsMustTouchThePartTheVotesChose) {
  Row r;
  const CentreIndex index(r.scene);
  IslandOptions o;
  o.enabled = true;
  o.link_sigmas = 1;
  const size_t dropped = drop_whole_islands(r.selection, r.votes, r.scene, index, 0.8, 0.0, {}, o);
  std::printf("[ islands ] %zu of 30 dropped\n", dropped);
  EXPECT_EQ(dropped, 10u);
  for (uint32_t i = 0; i < 30; ++i) EXPECT_EQ(r.selection[i], i < 20) << i;
}

TEST(WholeIslands, ALinkFarEnoughJoinsTheNeighbourAndOffDropsNothing) {
  Row joined;
  const CentreIndex index(joined.scene);
  IslandOptions wide;
  wide.enabled = true;
  wide.link_sigmas = 6;  // 6 x (1 + 1) cm reaches across the 11 cm gap between centres
  EXPECT_EQ(drop_whole_islands(joined.selection, joined.votes, joined.scene, index, 0.8, 0.0, {}, wide), 0u);
  Row off;
  EXPECT_EQ(drop_whole_islands(off.selection, off.votes, off.scene, index, 0.8, 0.0, {}, IslandOptions{}), 0u);
  EXPECT_EQ(std::count(off.selection.begin(), off.selection.end(), true), 30);
  // Nothing the votes select on their own: no part to grow from, nothing is dropped.
  Row none;
  none.selection = std::vector<bool>(30, false);
  for (uint32_t i = 10; i < 30; ++i) none.selection[i] = true;
  IslandOptions on;
  on.enabled = true;
  on.link_sigmas = 1;
  EXPECT_EQ(drop_whole_islands(none.selection, none.votes, none.scene, index, 0.8, 0.0, {}, on), 0u);
}

TEST(WholeIslands, AnIslandIsKeptOnlyWhenWhatItsOwnVotesSelectIsARealShareOfIt) {
  IslandOptions o;
  o.enabled = true;
  o.link_sigmas = 1;
  o.min_own_share = 0.02;
  for (uint32_t own : {0u, 1u, 2u, 10u}) {
    Row p(100, own);
    const CentreIndex index(p.scene);
    const size_t dropped = drop_whole_islands(p.selection, p.votes, p.scene, index, 0.8, 0.0, {}, o);
    // Under 2 of its 100 Gaussians: the neighbour's dependent ones go; the part and the
    // rest of its whole (20 Gaussians, 10 on their own votes) always stay.
    const bool kept = own >= 2;
    std::printf("[ islands ] neighbour with %u of 100 on its own votes: %zu dropped\n", own, dropped);
    EXPECT_EQ(dropped, kept ? 0u : 100u - own) << own;
    for (uint32_t i = 0; i < 20; ++i) EXPECT_TRUE(p.selection[i]) << own << " " << i;
    for (uint32_t i = 20; i < 120; ++i) EXPECT_EQ(p.selection[i], kept || i >= 120 - own) << own << " " << i;
  }
  // Without the share, one Gaussian on its own votes anchors the whole neighbour.
  Row one(100, 1);
  const CentreIndex index(one.scene);
  o.min_own_share = 0;
  EXPECT_EQ(drop_whole_islands(one.selection, one.votes, one.scene, index, 0.8, 0.0, {}, o), 0u);
}

}  // namespace
}  // namespace isegman::segment
