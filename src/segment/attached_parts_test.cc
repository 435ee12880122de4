#include "segment/attached_parts.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace isegman::segment {
namespace {

// Gaussians of scale 6 mm on a line along x (neighbours 1 cm apart touch, 2 cm apart do
// not), one per entry of `x_cm`, each seen with total weight 1. `share[i]` of it is
// positive, `open[i]` left open between part and whole (W).
struct Line {
  GaussianScene scene;
  VoteAccumulator votes;
  std::vector<bool> selection;
  std::vector<uint32_t> candidates;  // every Gaussian with a positive vote
  Line(const std::vector<float>& x_cm, const std::vector<double>& share, const std::vector<double>& open)
      : votes(x_cm.size()), selection(x_cm.size(), false) {
    ViewVotes positive, total, whole;
    const int64_t a = int64_t(1) << 24;
    for (uint32_t i = 0; i < x_cm.size(); ++i) {
      scene.positions.insert(scene.positions.end(), {0.01f * x_cm[i], 0.f, 0.f});
      scene.scales.insert(scene.scales.end(), {std::log(0.006f), std::log(0.006f), std::log(0.002f)});
      scene.rotations.insert(scene.rotations.end(), {1, 0, 0, 0});
      scene.opacity.push_back(0);
      total.index.push_back(i);
      total.weight.push_back(a);
      if (share[i] > 0) {
        positive.index.push_back(i);
        positive.weight.push_back(int64_t(share[i] * double(a)));
        candidates.push_back(i);
      }
      if (open[i] > 0) {
        whole.index.push_back(i);
        whole.weight.push_back(int64_t(open[i] * double(a)));
      }
      selection[i] = share[i] > 0.8;
    }
    votes.add(positive, total, +1, nullptr, nullptr, &whole);
  }
};

AttachedPartsOptions on() {
  AttachedPartsOptions o;
  o.enabled = true;
  return o;
}

size_t count(const std::vector<bool>& s) {
  size_t n = 0;
  for (bool b : s) n += b;
  return n;
}

// The selected part (x = 0..9 cm); a part 7 of 20 views mask, touching it (10..14); a part
// with as many votes standing 15 cm away (15..19); one the minority masks less (20..24,
// 15 %, touching the first); and one whose share counts only once the views that leave it
// open are left out (25..29: P/A 0.25, P/(A - W) 0.5), touching the second.
Line parts() {
  std::vector<float> x;
  std::vector<double> share, open;
  for (int i = 0; i < 10; ++i) x.push_back(float(i)), share.push_back(1.0), open.push_back(0);
  for (int i = 0; i < 5; ++i) x.push_back(float(10 + i)), share.push_back(0.35 + 0.01), open.push_back(0);
  for (int i = 0; i < 5; ++i) x.push_back(float(30 + i)), share.push_back(0.4), open.push_back(0);
  for (int i = 0; i < 5; ++i) x.push_back(float(-1 - i)), share.push_back(0.15), open.push_back(0);
  for (int i = 0; i < 5; ++i) x.push_back(float(15 + i)), share.push_back(0.25), open.push_back(0.5);
  return Line(x, share, open);
}

TEST(AttachedParts, APartAMinorityMasksJoinsWhereItAttaches) {
  Line l = parts();
  const CentreIndex index(l.scene);
  const size_t added = add_attached_parts(l.selection, l.votes, 0.0, l.candidates, {}, {}, {}, l.scene, index, on());
  std::printf("[ attached ] %zu of 30 added, %zu selected\n", added, count(l.selection));
  EXPECT_EQ(added, 10u);
  for (uint32_t i = 0; i < 30; ++i) EXPECT_EQ(l.selection[i], i < 15 || i >= 25) << i;
  // Off: nothing changes.
  Line off = parts();
  EXPECT_EQ(add_attached_parts(off.selection, off.votes, 0.0, off.candidates, {}, {}, {}, off.scene, index, {}), 0u);
  EXPECT_EQ(count(off.selection), 10u);
}

TEST(AttachedParts, WhatSeveralViewsSetAsideOrTheUserExcludedBreaksTheChain) {
  const AttachedPartsOptions o = on();
  ASSERT_GT(o.min_set_aside_views, 1);
  Line l = parts();
  const CentreIndex index(l.scene);
  std::vector<uint8_t> aside(30, 0);
  // Behind the target in enough views: 12 stays out, and 13, 14 no longer attach.
  aside[12] = uint8_t(o.min_set_aside_views);
  EXPECT_EQ(add_attached_parts(l.selection, l.votes, 0.0, l.candidates, aside, {}, {}, l.scene, index, o), 2u);
  for (uint32_t i = 10; i < 15; ++i) EXPECT_EQ(l.selection[i], i < 12) << i;
  // Set aside by one view fewer: that view's gate alone does not keep the part out.
  Line fewer = parts();
  aside[12] = uint8_t(o.min_set_aside_views - 1);
  EXPECT_EQ(add_attached_parts(fewer.selection, fewer.votes, 0.0, fewer.candidates, aside, {}, {}, fewer.scene, index, o), 10u);  // as with nothing set aside
  for (uint32_t i = 10; i < 15; ++i) EXPECT_TRUE(fewer.selection[i]) << i;
  Line ex = parts();
  std::vector<bool> excluded(30, false);
  excluded[10] = true;  // the first link
  add_attached_parts(ex.selection, ex.votes, 0.0, ex.candidates, {}, {}, excluded, ex.scene, index, on());
  for (uint32_t i = 10; i < 15; ++i) EXPECT_FALSE(ex.selection[i]) << i;
}

TEST(AttachedParts, ANeighbourSetApartClaimsWhatAttachesToIt) {
  // The part (0..39), a bridge of minority votes (40..44) and, touching the bridge, a
  // neighbour whole islands dropped (45..49): the bridge goes with the neighbour.
  std::vector<float> x;
  std::vector<double> share, open;
  for (int i = 0; i < 50; ++i) x.push_back(float(i)), share.push_back(i < 40 ? 1.0 : (i < 45 ? 0.5 : 0.6)), open.push_back(0);
  Line l(x, share, open);
  const CentreIndex index(l.scene);
  const std::vector<uint32_t> apart = {45, 46, 47, 48, 49};
  EXPECT_EQ(add_attached_parts(l.selection, l.votes, 0.0, l.candidates, {}, apart, {}, l.scene, index, on()), 0u);
  EXPECT_EQ(count(l.selection), 40u);
  // One speck dropped (under 5 % of the selection) is no neighbour: the bridge joins.
  Line specks(x, share, open);
  const size_t added = add_attached_parts(specks.selection, specks.votes, 0.0, specks.candidates, {}, {49}, {},
                                          specks.scene, index, on());
  EXPECT_EQ(added, 9u);  // 40..48; 49 itself was dropped and stays out
  EXPECT_FALSE(specks.selection[49]);
}

TEST(AttachedParts, WhatOnlyViewsFarLargerThanTheObjectMaskDoesNotJoin) {
  // The parts above, where the votes for the touching part (10..14) came from views whose
  // masks lie mostly off the selection (a shelf of books masked with the clicked globe):
  // without their votes it holds none, and it stays out; so does what joined through it
  // (25..29, still a candidate on its own shares but attached only through 10..14).
  Line l = parts();
  const CentreIndex index(l.scene);
  ViewVotes shelf;
  for (uint32_t i = 10; i < 15; ++i) {
    shelf.index.push_back(i);
    shelf.weight.push_back(int64_t(0.36 * double(int64_t(1) << 24)));
  }
  const std::vector<ViewVotes> wide{shelf};
  const size_t added =
      add_attached_parts(l.selection, l.votes, 0.0, l.candidates, {}, {}, {}, l.scene, index, on(), 1, &wide);
  std::printf("[ attached ] with the wide views' votes taken out: %zu added\n", added);
  EXPECT_EQ(added, 0u);
  EXPECT_EQ(count(l.selection), 10u);
  // Without wide views (or an empty list) the part joins as before.
  Line same = parts();
  const std::vector<ViewVotes> none;
  EXPECT_EQ(add_attached_parts(same.selection, same.votes, 0.0, same.candidates, {}, {}, {}, same.scene, index, on(), 1,
                               &none),
            10u);
}

}  // namespace
}  // namespace isegman::segment
