#include "server/display_state.h"

#include <algorithm>

#include "server/app_error.h"

namespace isegman::server {

namespace {
size_t count_true(const std::vector<bool>& v) { return size_t(std::count(v.begin(), v.end(), true)); }
}  // namespace

DisplayResult DisplayState::apply(DisplayOp op, const std::vector<bool>& selection) {
  std::lock_guard<std::mutex> lock(mu_);
  const size_t n = selection.size();
  if (hidden_.size() != n) hidden_.assign(n, false);
  const size_t selected = count_true(selection);
  if (op != DisplayOp::kShowAll && selected == 0)
    conflict("nothing is selected: select what to hide or isolate first");
  std::string label;
  switch (op) {
    case DisplayOp::kHide:
      for (size_t i = 0; i < n; ++i) hidden_[i] = hidden_[i] || selection[i];
      label = "hid " + std::to_string(selected) + " selected Gaussians";
      break;
    case DisplayOp::kIsolate:
      for (size_t i = 0; i < n; ++i) hidden_[i] = hidden_[i] || !selection[i];
      label = "isolated " + std::to_string(selected) + " selected Gaussians";
      break;
    case DisplayOp::kShowAll:
      hidden_.assign(n, false);
      label = "showing every Gaussian";
      break;
  }
  ++revision_;
  return {label, count_true(hidden_), revision_};
}

std::vector<bool> DisplayState::hidden(size_t count) {
  std::lock_guard<std::mutex> lock(mu_);
  if (hidden_.size() != count) {
    if (!hidden_.empty()) ++revision_;  // forgotten: the page must redraw everything
    hidden_.clear();
  }
  if (std::find(hidden_.begin(), hidden_.end(), true) == hidden_.end()) return {};
  return hidden_;
}

uint64_t DisplayState::revision() const {
  std::lock_guard<std::mutex> lock(mu_);
  return revision_;
}

}  // namespace isegman::server
