#include "segment/live_selection.h"

#include <algorithm>

#include "core/parallel.h"

namespace isegman::segment {

void LiveSelection::set(uint32_t i, bool s) {
  const bool e = s && !(excluded_ && (*excluded_)[i]);
  strong_[i] = s;
  eligible_[i] = e;
  values_[i] = e ? 1.f : 0.f;
}

void LiveSelection::reset(size_t n, const SelectionRule& rule, const std::vector<bool>* excluded) {
  if (strong_.size() != n) {
    strong_.assign(n, false);
    eligible_.assign(n, false);
    values_.assign(n, 0.f);
    members_.clear();
  }
  for (uint32_t i : members_) set(i, false);
  members_.clear();
  support_bits_.assign((n + 63) / 64, 0);
  support_list_.clear();
  support_listed_ = true;
  rule_ = rule;
  min_fixed_ = VoteAccumulator::min_fixed(rule.min_total);
  // P > tau * A with A > 0 needs P > 0 when tau >= 0; so does the centre rule's P > tau_low * A.
  everyone_ = !(rule.tau >= 0) || (rule.centre.enabled && !(rule.centre.tau_low >= 0));
  excluded_ = excluded && excluded->size() == n ? excluded : nullptr;
}

void LiveSelection::add_support(const std::vector<uint32_t>& positive) {
  for (uint32_t i : positive) support_bits_[i >> 6] |= uint64_t(1) << (i & 63);
  support_listed_ = support_listed_ && positive.empty();
}

const std::vector<uint32_t>& LiveSelection::support() const {
  if (!support_listed_) {
    support_list_.clear();
    for_each_supported(0, support_bits_.size(), [&](uint32_t i) { support_list_.push_back(i); });
    support_listed_ = true;
  }
  return support_list_;
}

void LiveSelection::decide(const VoteAccumulator& votes, int threads) {
  // Chunks of 2^18 Gaussians tested in parallel, each listing its members ascending, joined
  // in order.
  constexpr size_t kWordsPerChunk = size_t(1) << 12;  // 64 Gaussians a word
  const size_t words = everyone_ ? (votes.size() + 63) / 64 : support_bits_.size();
  const size_t chunks = (words + kWordsPerChunk - 1) / kWordsPerChunk;
  std::vector<std::vector<uint32_t>> found(chunks);
  parallel_for(chunks, threads, [&](int, size_t c) {
    std::vector<uint32_t> out;  // a local, moved in at the end: the chunks' lists share cache lines
    auto visit = [&](uint32_t i) {
      if (votes.selects(i, rule_.tau, min_fixed_, rule_.centre, rule_.whole)) out.push_back(i);
    };
    const size_t w0 = c * kWordsPerChunk, w1 = std::min(words, w0 + kWordsPerChunk);
    if (everyone_)
      for (size_t i = w0 * 64, e = std::min(votes.size(), w1 * 64); i < e; ++i) visit(uint32_t(i));
    else
      for_each_supported(w0, w1, visit);
    found[c] = std::move(out);
  });
  std::vector<uint32_t>& now = next_members_;
  now.clear();
  for (const std::vector<uint32_t>& f : found) now.insert(now.end(), f.begin(), f.end());
  // Both lists ascending: only the Gaussians that left or joined change their forms (a view
  // changes a few of the ~10^6 members of a large scene's selection).
  size_t a = 0, b = 0;
  while (a < members_.size() || b < now.size()) {
    if (b == now.size() || (a < members_.size() && members_[a] < now[b])) {
      set(members_[a++], false);
    } else if (a == members_.size() || now[b] < members_[a]) {
      set(now[b++], true);
    } else {
      ++a;
      ++b;
    }
  }
  members_.swap(now);
}

}  // namespace isegman::segment
