#include "segment/live_selection.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <set>

#include "core/random.h"

namespace isegman::segment {
namespace {

// A view's sparse votes over n Gaussians: each Gaussian with probability `density`,
// ascending, with weights of up to a pixel (fixed point).
ViewVotes random_votes(SplitMix64& rng, size_t n, double density) {
  ViewVotes v;
  for (uint32_t i = 0; i < uint32_t(n); ++i)
    if (double(rng.next() % 1000000) < density * 1e6) {
      v.index.push_back(i);
      v.weight.push_back(int64_t(1 + rng.next() % (uint64_t(1) << 24)));
    }
  return v;
}

TEST(LiveSelection, DecidesAsTheWholeAccumulatorAndKeepsItsSupport) {
  // Views vote one after another (positive votes a subset of each view's total); after each,
  // the live selection must equal VoteAccumulator::select over every Gaussian (excluded ones
  // kept in strong() and left out of eligible()), and support() must be the sorted union of
  // the positive lists so far, across the 64-Gaussian words of its bit set.
  SplitMix64 rng(11);
  for (size_t n : {size_t(1), size_t(63), size_t(64), size_t(65), size_t(5000), size_t(600000)}) {
    std::vector<bool> excluded(n, false);
    for (size_t i = 0; i < n; ++i) excluded[i] = rng.next() % 7 == 0;
    SelectionRule rule;
    rule.tau = 0.6;
    rule.min_total = 0.01;
    rule.centre.enabled = true;
    rule.whole.enabled = true;
    VoteAccumulator votes(n);
    LiveSelection live;
    live.reset(n, rule, &excluded);
    std::set<uint32_t> support;
    for (int view = 0; view < 6; ++view) {
      const ViewVotes total = random_votes(rng, n, 0.5);
      ViewVotes positive, centred, whole;
      for (size_t k = 0; k < total.index.size(); ++k) {
        const uint64_t r = rng.next() % 4;
        if (r != 0) {
          positive.index.push_back(total.index[k]);
          positive.weight.push_back(total.weight[k] / int64_t(r));
        }
        if (r == 1) {
          centred.index.push_back(total.index[k]);
          centred.weight.push_back(total.weight[k]);
        }
        if (r == 0) {
          whole.index.push_back(total.index[k]);
          whole.weight.push_back(total.weight[k] / 2);
        }
      }
      votes.add(positive, total, +1, nullptr, &centred, &whole);
      live.add_support(positive.index);
      support.insert(positive.index.begin(), positive.index.end());
      live.decide(votes, view % 2 ? 2 : 1);  // 600,000 Gaussians: three chunks decided in parallel
      const std::vector<bool> want = votes.select(rule.tau, rule.min_total, rule.centre, rule.whole);
      ASSERT_EQ(live.strong(), want) << "n " << n << " view " << view;
      size_t selected = 0;
      for (size_t i = 0; i < n; ++i) {
        ASSERT_EQ(live.eligible()[i], want[i] && !excluded[i]) << "n " << n << " Gaussian " << i;
        ASSERT_EQ(live.values()[i], live.eligible()[i] ? 1.f : 0.f);
        selected += want[i];
      }
      ASSERT_EQ(live.members().size(), selected);
      ASSERT_TRUE(std::is_sorted(live.members().begin(), live.members().end()));
      ASSERT_EQ(live.support(), std::vector<uint32_t>(support.begin(), support.end())) << "n " << n << " view " << view;
      if (n == 5000 && view == 5)
        std::printf("[ live ] 5000 Gaussians, 6 views: %zu selected, support %zu\n", selected, support.size());
    }
    // A new round starts empty.
    live.reset(n, rule, &excluded);
    EXPECT_TRUE(live.support().empty());
    EXPECT_TRUE(live.members().empty());
    EXPECT_EQ(std::count(live.strong().begin(), live.strong().end(), true), 0);
  }
}

}  // namespace
}  // namespace isegman::segment
