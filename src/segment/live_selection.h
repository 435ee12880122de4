// The selection a round's votes make so far (session.cc). Inspecting a view needs the
// selection of the views before it; deciding it afresh meant a pass over every
// Gaussian's vote sums and building a bit and a float per Gaussian, for every view
// inspected: O(N) each time, 10-20 times a click (~0.4 s at 6M Gaussians). A Gaussian
// can only be selected when its positive sum P is above 0 (for tau, tau_low >= 0), so
// only the Gaussians that ever got a positive vote are decided, with the same test as
// VoteAccumulator::select, and the per-Gaussian forms are updated where they change.
#pragma once

#include <cstdint>
#include <vector>

#include "segment/votes.h"

namespace isegman::segment {

struct SelectionRule {
  double tau = 0.8;
  double min_total = 0.05;
  CentreRule centre;
  WholeRule whole;
};

class LiveSelection {
 public:
  // Nothing selected among n Gaussians (buffers of the same size are reused: only what was
  // selected is cleared). `excluded` (null, empty or one flag per Gaussian) are never
  // eligible; it must outlive the round.
  void reset(size_t n, const SelectionRule& rule, const std::vector<bool>* excluded);
  // After votes.add(positive, ...): the Gaussians `positive` votes for.
  void add_support(const std::vector<uint32_t>& positive);
  // Decides the selection from `votes` (which add_support has followed since reset), on
  // `threads` workers (0 = all cores).
  void decide(const VoteAccumulator& votes, int threads = 1);

  // votes.select(rule) as of the last decide: excluded Gaussians included (coherence counts them).
  const std::vector<bool>& strong() const { return strong_; }
  // strong() without the excluded Gaussians: what the session selects.
  const std::vector<bool>& eligible() const { return eligible_; }
  // eligible() as 1 / 0 per Gaussian, for coverage renders.
  const std::vector<float>& values() const { return values_; }
  // The Gaussians strong() holds, ascending.
  const std::vector<uint32_t>& members() const { return members_; }
  // Every Gaussian with a positive vote since reset, ascending: outside it P = 0. Listed
  // from the bits on the first call after a change (not for concurrent callers).
  const std::vector<uint32_t>& support() const;

 private:
  void set(uint32_t i, bool s);
  // f(i) for every Gaussian i of the support in words [w0, w1) of its bits, ascending.
  template <class F>
  void for_each_supported(size_t w0, size_t w1, F&& f) const {
    for (size_t w = w0; w < w1; ++w)
      for (uint64_t bits = support_bits_[w]; bits != 0; bits &= bits - 1)
        f(uint32_t(w * 64 + size_t(__builtin_ctzll(bits))));
  }
  SelectionRule rule_;
  int64_t min_fixed_ = 0;
  bool everyone_ = false;  // a rule that can select P = 0 (tau < 0): decide every Gaussian
  const std::vector<bool>* excluded_ = nullptr;
  std::vector<bool> strong_, eligible_;
  std::vector<float> values_;
  std::vector<uint32_t> members_;
  std::vector<uint32_t> next_members_;  // decide's new list, kept for its capacity
  // The support as one bit per Gaussian: a view's votes set their bits in O(their count);
  // merging sorted lists instead cost O(support) a view (~1M entries at 6M Gaussians).
  std::vector<uint64_t> support_bits_;
  mutable std::vector<uint32_t> support_list_;  // support(), built when asked
  mutable bool support_listed_ = false;
};

}  // namespace isegman::segment
