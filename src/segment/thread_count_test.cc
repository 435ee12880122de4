// The per-Gaussian steps of a vote split long lists over threads (a large scene's mask
// holds ~10^6 Gaussians a view): their results must not depend on the thread count.
// Lists here are long enough (> 2^16 entries) to take the parallel paths.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/random.h"
#include "segment/background_gate.h"
#include "segment/depth_layers.h"
#include "segment/votes.h"

namespace isegman::segment {
namespace {

constexpr size_t kGaussians = 400000;

// A 320x240 view of a far wall (z ~ 6) and, in front of it, a patch of small Gaussians with
// holes (z ~ 3) that the mask covers with some wall around it: the wall shows through the
// patch's holes, and around it.
// With the rendered depth and alpha, the view's votes, and most of the patch as selection.
struct BigView {
  GaussianScene scene;
  Camera cam = Camera::look_at({0, 0, 0}, {0, 0, 1}, {0, -1, 0}, 320, 240, 60);
  Image mask{320, 240, 1}, depth, alpha;
  ViewVotes positive, total;
  std::vector<bool> selection;
  static bool in_patch(size_t i) { return i % 8 == 0; }

  BigView() {
    SplitMix64 rng(11);
    auto uniform = [&]() { return double(rng.next() >> 11) * 0x1.0p-53; };
    for (size_t i = 0; i < kGaussians; ++i) {
      const bool near = in_patch(i);
      const double x = near ? uniform() * 2 - 1 : uniform() * 7 - 3.5, y = near ? uniform() * 1.5 - 0.75 : uniform() * 5 - 2.5;
      const double z = near ? 3.0 + 0.1 * uniform() : 6.0 + 0.1 * x + 0.05 * uniform();
      scene.positions.insert(scene.positions.end(), {float(x), float(y), float(z)});
      const float s = float(std::log(near ? 0.002 : 0.015));
      scene.scales.insert(scene.scales.end(), {s, float(s + std::log(1 + 2 * uniform())), float(s - 1.0)});
      const double a = uniform() * 3.14159;
      scene.rotations.insert(scene.rotations.end(), {float(std::cos(a)), float(std::sin(a)), 0.f, 0.f});
      scene.opacity.push_back(near ? 1.f : 3.f);
      scene.sh.insert(scene.sh.end(), {0.f, 0.f, 0.f});
    }
    scene.sh_degree = 0;
    const RenderOutput r = render(scene, cam);
    depth = r.depth;
    alpha = r.alpha;
    for (int y = 35; y < 205; ++y)  // the patch and some wall around it, with a ragged left edge
      for (int x = 50 + (y % 7); x < 270; ++x) mask.at(x, y) = 1.f;
    const PreparedFrame f = prepare_frame(scene, cam);
    total = total_votes(f);
    positive = masked_votes(f, mask);
    selection.assign(kGaussians, false);
    for (uint32_t g : positive.index) selection[g] = in_patch(g) && g % 5 != 0;
  }
};

const BigView& big_view() {
  static const BigView v;
  return v;
}

TEST(ThreadCount, VoteSumsAndCentreEvidence) {
  const BigView& v = big_view();
  ASSERT_GT(v.positive.index.size(), size_t(1) << 16);
  const ViewVotes c1 = centred_votes(v.scene, v.cam, v.mask, v.depth, v.positive, v.total, 4, 1);
  const ViewVotes c3 = centred_votes(v.scene, v.cam, v.mask, v.depth, v.positive, v.total, 4, 3);
  EXPECT_GT(c1.index.size(), v.positive.index.size() / 4);
  EXPECT_EQ(c1.index, c3.index);
  EXPECT_EQ(c1.weight, c3.weight);
  VoteAccumulator a1(kGaussians), a3(kGaussians);
  a1.add(v.positive, v.total, +1, &c1, &c1, &c1, 1);
  a3.add(v.positive, v.total, +1, &c1, &c1, &c1, 3);
  EXPECT_EQ(a1, a3);
  a3.add(v.positive, v.total, -1, &c1, &c1, &c1, 3);
  EXPECT_EQ(a3, VoteAccumulator(kGaussians));
  std::printf("[ threads ] %zu in the mask, %zu with centre evidence\n", v.positive.index.size(), c1.index.size());
}

TEST(ThreadCount, DepthLayerGate) {
  const BigView& v = big_view();
  for (const bool with_selection : {false, true}) {
    ViewVotes p1 = v.positive, n1, p3 = v.positive, n3;
    const std::vector<bool>* sel = with_selection ? &v.selection : nullptr;
    const GateReport r1 = gate_by_depth(v.scene, v.cam, p1, n1, {3.0}, sel, {}, 1);
    const GateReport r3 = gate_by_depth(v.scene, v.cam, p3, n3, {3.0}, sel, {}, 3);
    EXPECT_FALSE(n1.index.empty()) << "the far sheet is gated";
    EXPECT_EQ(r1.local, with_selection);
    EXPECT_EQ(p1.index, p3.index);
    EXPECT_EQ(p1.weight, p3.weight);
    EXPECT_EQ(n1.index, n3.index);
    EXPECT_EQ(r1.layers, r3.layers);
    EXPECT_EQ(r1.gated_share, r3.gated_share);
    std::printf("[ threads ] depth layers%s: %zu kept, %zu neutral\n", with_selection ? " (local)" : "",
                p1.index.size(), n1.index.size());
  }
}

TEST(ThreadCount, BackgroundEstimateAndGate) {
  const BigView& v = big_view();
  const double near = near_depth(v.scene, v.cam, v.positive, 0.05);
  const Image b1 = background_inverse_depth(v.mask, v.depth, v.alpha, near * 0.9, {}, 1);
  const Image b4 = background_inverse_depth(v.mask, v.depth, v.alpha, near * 0.9, {}, 4);
  EXPECT_EQ(b1.data, b4.data);
  EXPECT_GT(std::count_if(b1.data.begin(), b1.data.end(), [](float x) { return x > 0; }), 1000);
  BackgroundTarget target;
  target.seeds.push_back({160.5, 120.5});
  ViewVotes p1 = v.positive, n1, p3 = v.positive, n3;
  const size_t m1 = gate_background(v.scene, v.cam, b1, target, p1, n1, {}, 1);
  const size_t m3 = gate_background(v.scene, v.cam, b1, target, p3, n3, {}, 3);
  EXPECT_EQ(m1, m3);
  EXPECT_EQ(p1.index, p3.index);
  EXPECT_EQ(n1.index, n3.index);
  EXPECT_EQ(n1.weight, n3.weight);
  std::printf("[ threads ] background: %zu estimated pixels, %zu Gaussians moved\n",
              size_t(std::count_if(b1.data.begin(), b1.data.end(), [](float x) { return x > 0; })), m1);
}

}  // namespace
}  // namespace isegman::segment
