#include "segment/apart_islands.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace isegman::segment {
namespace {

// A flat Gaussian at (x, y, z), `scale` wide in x and y, 2 mm thin in z.
void add_gaussian(GaussianScene& s, float x, float y, float z, float scale) {
  s.positions.insert(s.positions.end(), {x, y, z});
  s.scales.insert(s.scales.end(), {std::log(scale), std::log(scale), std::log(0.002f)});
  s.rotations.insert(s.rotations.end(), {1, 0, 0, 0});
  s.opacity.push_back(0);
}

// Gaussians of scale 1 cm in a row along x: the clicked object (0..9, x = 0..9 cm) and,
// 20 cm apart, a neighbour (10..19, x = 30..39 cm); with `bridge`, selected Gaussians in the
// gap (20..39) join the two, of scale `bridge_scale`.
GaussianScene row(bool bridge, float bridge_scale = 0.01f) {
  GaussianScene s;
  auto add = [&](float x, float scale) { add_gaussian(s, x, 0.f, 0.f, scale); };
  for (int i = 0; i < 20; ++i) add(0.01f * float(i < 10 ? i : i + 20), 0.01f);
  if (bridge)
    for (int i = 0; i < 20; ++i) add(0.01f * float(10 + i), bridge_scale);
  return s;
}

// A clicked view's votes: every Gaussian in `seen` blends weight 1, those in `masked` wholly
// inside the mask.
struct View {
  ViewVotes inside, total;
  View(const std::vector<uint32_t>& seen, const std::vector<uint32_t>& masked) {
    for (uint32_t g : seen) {
      total.index.push_back(g);
      total.weight.push_back(int64_t(kVoteScale));
      if (std::count(masked.begin(), masked.end(), g)) {
        inside.index.push_back(g);
        inside.weight.push_back(int64_t(kVoteScale));
      }
    }
  }
  ClickedViewVotes votes() const { return {&inside, &total}; }
};

std::vector<uint32_t> range(uint32_t a, uint32_t b) {
  std::vector<uint32_t> out;
  for (uint32_t g = a; g < b; ++g) out.push_back(g);
  return out;
}

ApartOptions on() {
  ApartOptions o;
  o.enabled = true;
  return o;
}

TEST(ApartIslands, ANeighbourTheClickedViewLeavesOutLeavesWhenItStandsApart) {
  const GaussianScene s = row(false);
  // The clicked view sees both; its mask holds the object and, as a mask's edge may, two of
  // the neighbour's Gaussians.
  const View view(range(0, 20), {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11});
  std::vector<bool> selection(s.size(), true);
  const ApartReport r = drop_apart_islands(selection, s, {view.votes()}, {4}, 0.05, on(), IslandOptions{});
  std::printf("[ apart islands ] %zu of %zu left, in %d set(s)\n", r.removed, s.size(), r.islands);
  EXPECT_EQ(r.removed, 10u);
  EXPECT_EQ(r.islands, 1);
  for (size_t i = 0; i < s.size(); ++i) EXPECT_EQ(selection[i], i < 10) << i;
  // Switched off, or without a click's Gaussians to tell the object by, nothing leaves.
  std::vector<bool> all(s.size(), true);
  EXPECT_EQ(drop_apart_islands(all, s, {view.votes()}, {4}, 0.05, ApartOptions{}, IslandOptions{}).removed, 0u);
  EXPECT_EQ(drop_apart_islands(all, s, {view.votes()}, {}, 0.05, on(), IslandOptions{}).removed, 0u);
  EXPECT_EQ(std::count(all.begin(), all.end(), true), 20);
}

TEST(ApartIslands, WhatTouchesTheClickedObjectStays) {
  // The rest of an object (a chair's seat below its clicked back) joins it through touching
  // Gaussians: the clicked view's mask leaving it out says nothing then.
  const GaussianScene s = row(true);
  const View view(range(0, 40), range(0, 10));
  std::vector<bool> selection(s.size(), true);
  EXPECT_EQ(drop_apart_islands(selection, s, {view.votes()}, {4}, 0.05, on(), IslandOptions{}).removed, 0u);
  EXPECT_EQ(std::count(selection.begin(), selection.end(), true), 40);
}

TEST(ApartIslands, ASmallSetApartMayBeAPartOfTheObject) {
  // Three Gaussians apart from the object (a lamp's stem below its shade, touching nothing
  // selected): under min_size_share of the ten the mask holds, they stay. The neighbour of
  // ten leaves.
  GaussianScene s = row(false);
  for (int i = 0; i < 3; ++i) add_gaussian(s, 0.05f, 0.f, -0.3f - 0.01f * float(i), 0.01f);
  const View view(range(0, 23), range(0, 10));
  std::vector<bool> selection(s.size(), true);
  EXPECT_EQ(drop_apart_islands(selection, s, {view.votes()}, {4}, 0.05, on(), IslandOptions{}).removed, 10u);
  for (size_t i = 0; i < s.size(); ++i) EXPECT_EQ(selection[i], i < 10 || i >= 20) << i;
}

TEST(ApartIslands, BroadGaussiansDoNotJoin) {
  // The gap filled by broad flat Gaussians, 5 cm to the others' 1 cm (a floor the selection
  // took): they link nothing; the neighbour leaves, and with it the broad one that touches it
  // and nothing that stays. The others stay.
  GaussianScene s = row(false);
  for (float x : {0.12f, 0.17f, 0.22f, 0.27f}) add_gaussian(s, x, 0.f, -0.01f, 0.05f);
  const View view(range(0, 24), range(0, 10));
  std::vector<bool> selection(s.size(), true);
  EXPECT_EQ(drop_apart_islands(selection, s, {view.votes()}, {4}, 0.05, on(), IslandOptions{}).removed, 11u);
  for (size_t i = 0; i < s.size(); ++i) EXPECT_EQ(selection[i], i < 10 || (i >= 20 && i < 23)) << i;
  // Not followed, the broad one under the neighbour stays.
  ApartOptions stay = on();
  stay.broad_follow = false;
  std::vector<bool> all(s.size(), true);
  EXPECT_EQ(drop_apart_islands(all, s, {view.votes()}, {4}, 0.05, stay, IslandOptions{}).removed, 10u);
  // As broad as the rest, they join the two, and nothing leaves.
  ApartOptions any_size = on();
  any_size.max_link_scale = 100;
  all.assign(s.size(), true);
  EXPECT_EQ(drop_apart_islands(all, s, {view.votes()}, {4}, 0.05, any_size, IslandOptions{}).removed, 0u);
}

TEST(ApartIslands, ASetTheClickedViewsBarelySeeIsNotTheirsToJudge) {
  // The clicked view sees 2 of the neighbour's 10 Gaussians (a part the other views show):
  // under min_seen_share, it stays. A second clicked view that sees it all takes it out.
  const GaussianScene s = row(false);
  const View glimpse(range(0, 12), range(0, 10));
  std::vector<bool> selection(s.size(), true);
  EXPECT_EQ(drop_apart_islands(selection, s, {glimpse.votes()}, {4}, 0.05, on(), IslandOptions{}).removed, 0u);
  // Too faint to count as seen: weights under min_weight.
  EXPECT_EQ(drop_apart_islands(selection, s, {View(range(0, 20), range(0, 10)).votes()}, {4}, 2.0, on(),
                               IslandOptions{})
                .removed,
            0u);
  const View whole(range(0, 20), range(0, 10));
  EXPECT_EQ(drop_apart_islands(selection, s, {glimpse.votes(), whole.votes()}, {4}, 0.05, on(), IslandOptions{})
                .removed,
            10u);
}

// A clicked trellis 1 m in front of a camera at the origin (bars of touching 1 cm Gaussians
// every 5 cm, x and y from -20 to 20 cm) and, `behind` m farther, a square block of Gaussians
// `half` m across each way from the axis (a vase seen through the bars). With `joined`, a
// chain of Gaussians along the axis joins the block to the trellis.
struct Trellis {
  GaussianScene scene;
  size_t bars = 0;  // the trellis's Gaussians come first
  Camera camera;
  Trellis(double behind, double half, bool joined) {
    for (int bar = -4; bar <= 4; ++bar)
      for (int k = -20; k <= 20; ++k) {
        add_gaussian(scene, 0.05f * float(bar), 0.01f * float(k), 1.f, 0.01f);  // a column
        add_gaussian(scene, 0.01f * float(k), 0.05f * float(bar), 1.f, 0.01f);  // a row
      }
    bars = scene.size();
    const int n = int(std::lround(half / 0.01));
    for (int i = -n; i <= n; ++i)
      for (int j = -n; j <= n; ++j) add_gaussian(scene, 0.01f * float(i), 0.01f * float(j), float(1 + behind), 0.01f);
    if (joined)
      for (int k = 1; k < int(std::lround(behind / 0.01)); ++k) add_gaussian(scene, 0.f, 0.f, 1.f + 0.01f * float(k), 0.01f);
    camera.width = camera.height = 400;
    camera.fx = camera.fy = 400;
    camera.cx = camera.cy = 200;
  }
  // The clicked view sees every Gaussian, and its mask (SAM's, of the trellis) holds them all.
  ClickedViewVotes votes(View& view) const {
    view = View(range(0, uint32_t(scene.size())), range(0, uint32_t(scene.size())));
    ClickedViewVotes v = view.votes();
    v.camera = &camera;
    return v;
  }
};

TEST(ApartIslands, AnObjectSeenBehindTheClickedObjectsGapsLeaves) {
  // The block 30 cm behind the bars: every view's mask of the lattice holds it, so only 3D
  // and the clicked view's depths tell it is not the lattice.
  const Trellis t(0.3, 0.1, false);
  View view({}, {});
  std::vector<bool> selection(t.scene.size(), true);
  const ApartReport r = drop_apart_islands(selection, t.scene, {t.votes(view)}, {0}, 0.05, on(), IslandOptions{});
  std::printf("[ apart islands ] the block behind the trellis: %zu of %zu Gaussians left, in %d set(s)\n", r.removed,
              t.scene.size() - t.bars, r.islands);
  EXPECT_EQ(r.removed, t.scene.size() - t.bars);
  for (size_t i = 0; i < t.scene.size(); ++i) EXPECT_EQ(selection[i], i < t.bars) << i;
  // Without the rule nothing leaves: the clicked view's mask holds the block.
  ApartOptions off = on();
  off.behind = false;
  std::vector<bool> kept(t.scene.size(), true);
  EXPECT_EQ(drop_apart_islands(kept, t.scene, {t.votes(view)}, {0}, 0.05, off, IslandOptions{}).removed, 0u);
}

TEST(ApartIslands, WhatIsSeenBehindTheGapsStaysWhenItIsAPartOrJoined) {
  View view({}, {});
  // Joined to the lattice by a chain (a plant's back leaves on their stem): it stays.
  const Trellis joined(0.3, 0.1, true);
  std::vector<bool> all(joined.scene.size(), true);
  EXPECT_EQ(drop_apart_islands(all, joined.scene, {joined.votes(view)}, {0}, 0.05, on(), IslandOptions{}).removed, 0u);
  // A small block (9 Gaussians against the lattice's 738: a leaf cluster behind the others)
  // stays, and so does a block 2.5 cm behind (within behind_gap of the lattice's depth).
  const Trellis small(0.3, 0.01, false);
  std::vector<bool> some(small.scene.size(), true);
  EXPECT_EQ(drop_apart_islands(some, small.scene, {small.votes(view)}, {0}, 0.05, on(), IslandOptions{}).removed, 0u);
  const Trellis close(0.025, 0.1, false);
  std::vector<bool> near(close.scene.size(), true);
  EXPECT_EQ(drop_apart_islands(near, close.scene, {close.votes(view)}, {0}, 0.05, on(), IslandOptions{}).removed, 0u);
  // Without the camera nothing is seen behind.
  const Trellis far(0.3, 0.1, false);
  std::vector<bool> blind(far.scene.size(), true);
  ClickedViewVotes no_camera = far.votes(view);
  no_camera.camera = nullptr;
  EXPECT_EQ(drop_apart_islands(blind, far.scene, {no_camera}, {0}, 0.05, on(), IslandOptions{}).removed, 0u);
}

// A clicked object `half` m across each way from the axis, 1 m in front of a camera at the
// origin, and 30 cm behind it a larger board (60 cm each way) that the clicked view sees mostly
// around the object, not between its parts: a bookcase SAM merges with the plant before it.
// With `pieces`, the board has a hole (x and y 30-50 cm) holding a piece of it apart from the
// rest (3 x 3 Gaussians at 38-42 cm: books the leaves part from the others), and the object a
// leaf 12 cm behind its plane, apart from it just beyond its edge (x 24-28 cm); both last.
struct PlantBeforeBookcase {
  GaussianScene scene;
  size_t plant = 0;  // the clicked object's Gaussians come first
  size_t board = 0;  // then the board's, up to here
  Camera camera;
  explicit PlantBeforeBookcase(double half, bool pieces = false) {
    const int n = int(std::lround(half / 0.01));
    for (int i = -n; i <= n; ++i)
      for (int j = -n; j <= n; ++j) add_gaussian(scene, 0.01f * float(i), 0.01f * float(j), 1.f, 0.01f);
    plant = scene.size();
    for (int i = -30; i <= 30; ++i)
      for (int j = -30; j <= 30; ++j)
        if (!pieces || i < 15 || i > 25 || j < 15 || j > 25)
          add_gaussian(scene, 0.02f * float(i), 0.02f * float(j), 1.3f, 0.02f);
    board = scene.size();
    if (pieces)
      for (int i = -1; i <= 1; ++i)
        for (int j = -1; j <= 1; ++j) {
          add_gaussian(scene, 0.40f + 0.02f * float(i), 0.40f + 0.02f * float(j), 1.3f, 0.02f);
          add_gaussian(scene, 0.26f + 0.02f * float(i), 0.02f * float(j), 1.12f, 0.01f);
        }
    camera.width = camera.height = 400;
    camera.fx = camera.fy = 400;
    camera.cx = camera.cy = 200;
  }
  ClickedViewVotes votes(View& view) const {  // seen whole, and all in the clicked view's mask
    view = View(range(0, uint32_t(scene.size())), range(0, uint32_t(scene.size())));
    ClickedViewVotes v = view.votes();
    v.camera = &camera;
    return v;
  }
};

TEST(ApartIslands, WhatStandsApartBehindTheClickedSurfaceLeaves) {
  // The object (1,681 Gaussians, 31 % of what the clicked mask holds) is the set joined to the
  // click; the board, apart from it and 30 % deeper than the clicked surface, leaves. No
  // nearer Gaussians flank most of it (it shows around the object), so the gaps alone do not
  // take it out.
  const PlantBeforeBookcase p(0.2);
  View view({}, {});
  std::vector<bool> selection(p.scene.size(), true);
  const ApartReport r = drop_apart_islands(selection, p.scene, {p.votes(view)}, {0}, 0.05, on(), IslandOptions{});
  std::printf("[ apart islands ] the board behind the clicked object: %zu of %zu Gaussians left\n", r.removed,
              p.scene.size() - p.plant);
  EXPECT_EQ(r.removed, p.scene.size() - p.plant);
  for (size_t i = 0; i < p.scene.size(); ++i) EXPECT_EQ(selection[i], i < p.plant) << i;
  ApartOptions gaps_only = on();
  gaps_only.behind_click_gap = 0;
  std::vector<bool> kept(p.scene.size(), true);
  EXPECT_EQ(drop_apart_islands(kept, p.scene, {p.votes(view)}, {0}, 0.05, gaps_only, IslandOptions{}).removed, 0u);
}

TEST(ApartIslands, WhatLiesBehindAClickedPieceStays) {
  // The clicked set is 25 Gaussians against the board's 3,721 (a skeleton's rib among bones
  // that are sets of their own): it does not stand for the object, and the board stays.
  const PlantBeforeBookcase piece(0.02);
  View view({}, {});
  std::vector<bool> selection(piece.scene.size(), true);
  EXPECT_EQ(drop_apart_islands(selection, piece.scene, {piece.votes(view)}, {0}, 0.05, on(), IslandOptions{}).removed,
            0u);
  // It is that guard that keeps it: without it the board would leave.
  ApartOptions unguarded = on();
  unguarded.min_click_set_share = 0;
  EXPECT_EQ(drop_apart_islands(selection, piece.scene, {piece.votes(view)}, {0}, 0.05, unguarded, IslandOptions{}).removed,
            piece.scene.size() - piece.plant);
}

TEST(ApartIslands, PiecesOfWhatLeftThatLieNearerToItLeaveWithIt) {
  // The board leaves as above. Its piece in the hole (9 Gaussians, far under a quarter of the
  // rest) lies 10 cm from the board and 20 cm from the object: it leaves with the board. The
  // object's leaf behind its plane lies nearer the object (12 cm, against 18 cm to the board)
  // and stays.
  const PlantBeforeBookcase p(0.2, true);
  View view({}, {});
  std::vector<bool> selection(p.scene.size(), true);
  const ApartReport r = drop_apart_islands(selection, p.scene, {p.votes(view)}, {0}, 0.05, on(), IslandOptions{});
  std::printf("[ apart islands ] the board and its piece: %zu Gaussians left in %d sets\n", r.removed, r.islands);
  for (size_t i = 0; i < p.scene.size(); ++i) {
    const bool leaf = i >= p.board && (i - p.board) % 2 == 1;  // the pieces alternate: the board's, the leaf's
    EXPECT_EQ(selection[i], i < p.plant || leaf) << i;
  }
  EXPECT_EQ(r.islands, 2);
  // Without following the nearest, the board's piece stays too small to leave on its own.
  ApartOptions alone = on();
  alone.nearest_follow = false;
  std::vector<bool> kept(p.scene.size(), true);
  EXPECT_EQ(drop_apart_islands(kept, p.scene, {p.votes(view)}, {0}, 0.05, alone, IslandOptions{}).removed,
            p.board - p.plant);
}

}  // namespace
}  // namespace isegman::segment
