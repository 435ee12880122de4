#include "segment/whole_islands.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace isegman::segment {
namespace {

// Gaussians of scale 1 cm in rows along x: the part the votes select (0..9, x = 0..9 cm),
// the rest of the whole touching it (10..19, x = 10..19 cm), and a neighbour standing
// 10 cm apart (20..29, x = 30..39 cm).
struct Row {
  GaussianScene scene;
  VoteAccumulator votes{30};
  std::vector<bool> selection = std::vector<bool>(30, true);
  Row() {
    ViewVotes positive, total;
    for (uint32_t i = 0; i < 30; ++i) {
      const float x = 0.01f * float(i < 20 ? i : i + 10);
      scene.positions.insert(scene.positions.end(), {x, 0.f, 0.f});
      scene.scales.insert(scene.scales.end(), {std::log(0.01f), std::log(0.01f), std::log(0.002f)});
      scene.rotations.insert(scene.rotations.end(), {1, 0, 0, 0});
      scene.opacity.push_back(0);
      const int64_t a = int64_t(1) << 24;
      total.index.push_back(i);
      total.weight.push_back(a);
      positive.index.push_back(i);
      positive.weight.push_back(i < 10 ? a : a * 4 / 10);  // the whole rule selects 10..29
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

}  // namespace
}  // namespace isegman::segment
