#include "segment/live_selection.h"

#include <algorithm>

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
    for_each_supported([&](uint32_t i) { support_list_.push_back(i); });
    support_listed_ = true;
  }
  return support_list_;
}

void LiveSelection::decide(const VoteAccumulator& votes) {
  for (uint32_t i : members_) set(i, false);
  members_.clear();
  auto visit = [&](uint32_t i) {
    if (votes.selects(i, rule_.tau, min_fixed_, rule_.centre, rule_.whole)) members_.push_back(i);
  };
  if (everyone_)
    for (uint32_t i = 0; i < uint32_t(votes.size()); ++i) visit(i);
  else
    for_each_supported(visit);
  for (uint32_t i : members_) set(i, true);
}

}  // namespace isegman::segment
