#include "segment/live_selection.h"

#include <algorithm>
#include <iterator>

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
  support_.clear();
  rule_ = rule;
  min_fixed_ = VoteAccumulator::min_fixed(rule.min_total);
  // P > tau * A with A > 0 needs P > 0 when tau >= 0; so does the centre rule's P > tau_low * A.
  everyone_ = !(rule.tau >= 0) || (rule.centre.enabled && !(rule.centre.tau_low >= 0));
  excluded_ = excluded && excluded->size() == n ? excluded : nullptr;
}

void LiveSelection::add_support(const std::vector<uint32_t>& positive) {
  scratch_.clear();
  scratch_.reserve(support_.size() + positive.size());
  std::set_union(support_.begin(), support_.end(), positive.begin(), positive.end(), std::back_inserter(scratch_));
  support_.swap(scratch_);
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
    for (uint32_t i : support_) visit(i);
  for (uint32_t i : members_) set(i, true);
}

}  // namespace isegman::segment
