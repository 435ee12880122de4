#include "segment/coherence.h"

#include <gtest/gtest.h>

namespace isegman::segment {
namespace {

// Gaussians on a line x = 0..n-1 (unit spacing) with the given vote shares (all observed).
struct Line {
  GaussianScene scene;
  VoteAccumulator votes;
  explicit Line(const std::vector<double>& shares) : votes(shares.size()) {
    for (size_t i = 0; i < shares.size(); ++i) scene.positions.insert(scene.positions.end(), {float(i), 0.f, 0.f});
    scene.opacity.assign(shares.size(), 0.f);
    ViewVotes total, positive;
    for (size_t i = 0; i < shares.size(); ++i) {
      total.index.push_back(uint32_t(i));
      total.weight.push_back(int64_t(kVoteScale));
      positive.index.push_back(uint32_t(i));
      positive.weight.push_back(int64_t(shares[i] * kVoteScale));
    }
    votes.add(positive, total);
  }
};

TEST(Coherence, UndecidedSharesFollowTheirNeighbours) {
  // An object (shares 0.9) with undecided Gaussians (0.6) inside it, then a neighbour
  // (0.1) with undecided Gaussians (0.6) inside it: the same share, opposite company.
  std::vector<double> shares;
  for (int i = 0; i < 20; ++i) shares.push_back(i % 4 == 2 ? 0.6 : 0.9);
  for (int i = 0; i < 20; ++i) shares.push_back(i % 4 == 2 ? 0.6 : 0.1);
  Line l(shares);
  const CentreIndex index(l.scene);
  CoherenceOptions o;
  o.neighbours = 4;
  const std::vector<bool> plain = l.votes.select(0.8, 0.05);
  const std::vector<bool> sel = coherent_selection(l.votes, l.scene, index, 0.8, 0.05, o);
  for (int i = 0; i < 40; ++i) {
    const bool object = i < 20;
    if (shares[size_t(i)] == 0.6) {
      EXPECT_FALSE(plain[size_t(i)]) << i;
    }
    // The boundary (i = 18..21) mixes both sides; away from it the company decides.
    if (i >= 17 && i <= 22) continue;
    EXPECT_EQ(bool(sel[size_t(i)]), object) << i;
  }
}

}  // namespace
}  // namespace isegman::segment
