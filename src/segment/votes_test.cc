#include "segment/votes.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/sh.h"
#include "segment/test_masks.h"

namespace isegman::segment {
namespace {

void add_gaussian(GaussianScene& g, Vec3 p, double s, double o) {
  g.positions.insert(g.positions.end(), {float(p.x), float(p.y), float(p.z)});
  g.scales.insert(g.scales.end(), 3, float(std::log(s)));
  g.rotations.insert(g.rotations.end(), {1, 0, 0, 0});
  g.opacity.push_back(float(std::log(o / (1 - o))));
  g.sh.insert(g.sh.end(), {0.f, 0.f, 0.f});
}

using testing::box_mask;

Camera axis_camera() {
  Camera c;
  c.width = 64;
  c.height = 32;
  c.fx = c.fy = 100;
  c.cx = 32;
  c.cy = 16;
  return c;
}

TEST(Votes, FlaggedWeightSumsTheFlaggedGaussiansVotesOnAnyThreadCount) {
  // A list long enough for several chunks (list_grain), weights near the fixed-point
  // scale's size: the chunked sums are whole numbers and equal the sum in order.
  ViewVotes votes;
  std::vector<bool> flags(900000, false);
  int64_t expected = 0;
  for (uint32_t g = 0; g < flags.size(); g += 3) {
    votes.index.push_back(g);
    votes.weight.push_back(int64_t(g % 977) << 20);
    flags[g] = g % 7 < 3;
    if (flags[g]) expected += votes.weight.back();
  }
  for (int threads : {1, 2, 3}) EXPECT_EQ(flagged_weight(votes, flags, threads), expected) << threads;
  EXPECT_EQ(flagged_weight(ViewVotes{}, flags, 2), 0);
}

TEST(Votes, HandBuiltScene) {
  // Gaussian 0 on the left half, 1 on the right half, 2 behind 0 (partly hidden).
  GaussianScene g;
  g.sh_degree = 0;
  add_gaussian(g, {-0.4, 0, 3}, 0.05, 0.9);
  add_gaussian(g, {0.4, 0, 3}, 0.05, 0.9);
  add_gaussian(g, {-0.4, 0, 5}, 0.08, 0.9);
  PreparedFrame f = prepare_frame(g, axis_camera());
  ViewVotes all = total_votes(f, 1);
  const Image left = box_mask(64, 32, 0, 32, 0, 32);
  ViewVotes pos = masked_votes(f, left, 2);
  VoteAccumulator acc(3);
  acc.add(pos, all);
  auto ratios = acc.ratios();
  EXPECT_NEAR(ratios[0], 1.0, 1e-6);  // entirely inside the mask
  EXPECT_EQ(ratios[1], 0.f);          // entirely outside
  EXPECT_GT(ratios[2], 0.99);         // hidden part does not vote at all
  EXPECT_GT(acc.total()[2], 0);
  EXPECT_LT(acc.total()[2], acc.total()[0]);  // occluded: less visible weight
  auto sel = acc.select(0.8, 0.0);
  EXPECT_EQ(sel, (std::vector<bool>{true, false, true}));
  // min_total removes Gaussians with negligible weight.
  const double w2 = double(acc.total()[2]) / kVoteScale;
  EXPECT_FALSE(acc.select(0.8, w2 * 1.01)[2]);
  // The total votes equal the rendered alpha summed over the image.
  RenderOutput r = render(g, axis_camera());
  double alpha_sum = 0, vote_sum = 0;
  for (float a : r.alpha.data) alpha_sum += a;
  for (int64_t w : all.weight) vote_sum += double(w) / kVoteScale;
  EXPECT_NEAR(vote_sum, alpha_sum, 1e-3);
}

TEST(Votes, AddingAndRemovingAViewIsExact) {
  GaussianScene g;
  g.sh_degree = 0;
  for (int i = 0; i < 40; ++i) add_gaussian(g, {-0.8 + 0.04 * i, 0.1 * std::sin(i), 3 + 0.05 * i}, 0.04, 0.6);
  const Camera c = axis_camera();
  PreparedFrame f = prepare_frame(g, c);
  const Image mask = box_mask(64, 32, 10, 50, 4, 20);
  ViewVotes all = total_votes(f), pos = masked_votes(f, mask);
  VoteAccumulator base(g.size());
  base.add(pos, all);
  VoteAccumulator acc = base;
  const Image mask2 = box_mask(64, 32, 0, 20, 0, 32);
  ViewVotes pos2 = masked_votes(f, mask2);
  acc.add(pos2, all);
  EXPECT_FALSE(acc == base);
  acc.add(pos2, all, -1);
  EXPECT_TRUE(acc == base);
  // Thread count does not change a single vote.
  EXPECT_EQ(masked_votes(f, mask, 1).weight, masked_votes(f, mask, 3).weight);
}

TEST(Votes, CentreHiddenOutsideTheMaskCountsByWhereTheGaussianShows) {
  // A pillar's top (0): a large Gaussian whose centre lies behind a nearer ceiling (outside
  // the mask); only its lower part shows, below the ceiling, inside the mask.
  GaussianScene g;
  g.sh_degree = 0;
  add_gaussian(g, {0, -0.72, 6}, 0.36, 0.9);  // centre at row 4, sd 6 pixels: hidden
  for (double y : {-0.26, -0.32, -0.40})       // the ceiling: opaque down to row 6, gone by row 10
    for (double x = -0.64; x <= 0.64; x += 0.04) add_gaussian(g, {x, y, 2}, 0.06, 0.99);
  const Camera c = axis_camera();
  PreparedFrame f = prepare_frame(g, c);
  RenderOutput r = render(g, c);
  const Image mask = box_mask(64, 32, 22, 42, 9, 32);
  ViewVotes all = total_votes(f), pos = masked_votes(f, mask);
  double share = 0;
  for (size_t k = 0, t = 0; k < pos.index.size(); ++k)
    if (pos.index[k] == 0) {
      while (all.index[t] != 0) ++t;
      share = double(pos.weight[k]) / double(all.weight[t]);
    }
  std::printf("[ hidden centre ] share of the pillar's Gaussian in the mask %.2f\n", share);
  ASSERT_GT(share, 0.5);
  EXPECT_EQ(centred_votes(g, c, mask, r.depth, pos, all, 2).index, (std::vector<uint32_t>{0}));
  // Within the margin of the mask the centre may be hidden by the object's own edge: no count.
  EXPECT_TRUE(centred_votes(g, c, mask, r.depth, pos, all, 6).index.empty());
  // Mask the Gaussian's visible part only partly: the majority is outside and it does not count.
  const Image narrow = box_mask(64, 32, 31, 33, 9, 32);
  ViewVotes pos_narrow = masked_votes(f, narrow);
  EXPECT_TRUE(centred_votes(g, c, narrow, r.depth, pos_narrow, all, 2).index.empty());
}

TEST(Votes, CentreOutsideTheFrameCountsByWhereTheGaussianShows) {
  // A Gaussian centred just beyond the right edge shows its left half; the mask holds most of it.
  GaussianScene g;
  g.sh_degree = 0;
  add_gaussian(g, {0.35, 0, 3}, 0.09, 0.9);  // centre at x = 43.7, sd 3 pixels
  Camera c = axis_camera();
  c.width = 40;  // the centre is outside the frame
  PreparedFrame f = prepare_frame(g, c);
  RenderOutput r = render(g, c);
  const Image mask = box_mask(40, 32, 30, 40, 0, 32), left = box_mask(40, 32, 0, 30, 0, 32);
  ViewVotes all = total_votes(f);
  EXPECT_EQ(centred_votes(g, c, mask, r.depth, masked_votes(f, mask), all).index, (std::vector<uint32_t>{0}));
  EXPECT_TRUE(centred_votes(g, c, left, r.depth, masked_votes(f, left), all).index.empty());
}

TEST(Votes, CentreRuleTellsAnOutlineGaussianFromASpillingNeighbour) {
  // A thin object (a mask 3 pixels wide) drawn by one coarse Gaussian (0, sd 2 pixels,
  // centre inside the mask) that spills over both edges: share 0.5-0.8. A neighbour's
  // Gaussian (1) beside the strip. Gaussian 2 is larger and sits behind 0: its centre is
  // hidden, only its rim shows, and most of that rim falls inside the mask.
  GaussianScene g;
  g.sh_degree = 0;
  add_gaussian(g, {-0.015, 0, 3}, 0.06, 0.9);  // centre at x = 31.5
  add_gaussian(g, {0.1, 0, 3}, 0.06, 0.9);     // centre at x = 35.3
  add_gaussian(g, {-0.03, 0, 6}, 0.1, 0.9);
  const Camera c = axis_camera();
  PreparedFrame f = prepare_frame(g, c);
  RenderOutput r = render(g, c);
  const Image mask = box_mask(64, 32, 30, 33, 0, 32);
  ViewVotes all = total_votes(f), pos = masked_votes(f, mask);
  const ViewVotes centred = centred_votes(g, c, mask, r.depth, pos, all);
  ASSERT_EQ(centred.index, (std::vector<uint32_t>{0}));  // 1: centre outside; 2: centre hidden
  // Without a depth image the hidden centre cannot be told apart, and it counts.
  EXPECT_EQ(centred_votes(g, c, mask, Image(), pos, all).index, (std::vector<uint32_t>{0, 2}));
  for (size_t k = 0; k < all.index.size(); ++k) {
    if (all.index[k] == 0) {
      EXPECT_EQ(centred.weight[0], all.weight[k]);  // its whole view total
    }
  }
  VoteAccumulator acc(3);
  acc.add(pos, all, 1, nullptr, &centred);
  const auto share = acc.ratios();
  std::printf("[ shares ] outline %.2f, neighbour %.2f, hidden %.2f\n", share[0], share[1], share[2]);
  ASSERT_GT(share[0], 0.5);
  ASSERT_LT(share[0], 0.8);
  ASSERT_GT(share[2], 0.5);
  EXPECT_FALSE(acc.select(0.8, 0.0)[0]);  // tau alone drops the outline Gaussian
  CentreRule rule{true};
  const auto sel = acc.select(0.8, 0.0, rule);
  EXPECT_TRUE(sel[0]);
  EXPECT_FALSE(sel[1]);
  EXPECT_FALSE(sel[2]);
  EXPECT_TRUE(acc.select(0.5, 0.0)[2]);  // a plain majority would take the hidden one in
  // Removing the view again is exact, centre evidence included.
  VoteAccumulator copy = acc;
  copy.add(pos, all, -1, nullptr, &centred);
  EXPECT_TRUE(copy == VoteAccumulator(3));
}

TEST(Votes, WholeRuleLetsTheViewsThatSegmentTheWholeDecide) {
  // Four views see Gaussian 0 (the seat of a chair) with weight 1 each. One segments the whole
  // chair (P = 1); the others' masks are the chair's back, and in two of them the seat lies
  // in a larger candidate of their own (left open, W = 1 each); the last votes against it.
  const int64_t one = kVoteScale;
  auto votes = [](int64_t w) {
    ViewVotes v;
    v.index = {0};
    v.weight = {w};
    return v;
  };
  VoteAccumulator acc(1);
  const ViewVotes none, w1 = votes(one);
  acc.add(w1, w1);                      // segments the whole
  acc.add(none, w1, 1, nullptr, nullptr, &w1);  // back only, the whole a candidate
  acc.add(none, w1, 1, nullptr, nullptr, &w1);
  acc.add(none, w1);                    // back only, no candidate holds the seat
  const int64_t min_fixed = VoteAccumulator::min_fixed(0.05);
  EXPECT_FALSE(acc.selects(0, 0.8, min_fixed));  // P/A = 0.25: the intersection of the views
  WholeRule whole{true, 0.2};
  // P/(A - W) = 1/2: the view that votes against still outweighs.
  EXPECT_FALSE(acc.selects(0, 0.8, min_fixed, {}, whole));
  VoteAccumulator two(1);  // two views segment the whole, two leave it open
  two.add(w1, w1);
  two.add(w1, w1);
  two.add(none, w1, 1, nullptr, nullptr, &w1);
  two.add(none, w1, 1, nullptr, nullptr, &w1);
  EXPECT_FALSE(two.selects(0, 0.8, min_fixed));     // P/A = 0.5
  EXPECT_TRUE(two.selects(0, 0.8, min_fixed, {}, whole));  // P/(A - W) = 1, P/A = 0.5 > 0.2
  EXPECT_FALSE(two.selects(0, 0.8, min_fixed, {}, {true, 0.6}));  // not a sizeable enough share
  // Removing a view again is exact, W included.
  two.add(none, w1, -1, nullptr, nullptr, &w1);
  two.add(none, w1, 1, nullptr, nullptr, &w1);
  EXPECT_EQ(two.whole()[0], 2 * one);
}

}  // namespace
}  // namespace isegman::segment
