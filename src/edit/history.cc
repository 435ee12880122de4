#include "edit/history.h"

#include <cstdio>

#include "core/error.h"

namespace isegman::edit {
namespace {

std::string mib(size_t bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f MiB", double(bytes) / double(1 << 20));
  return buf;
}

}  // namespace

void History::clear() {
  undo_.clear();
  redo_.clear();
  bytes_ = 0;
}

std::string History::push(Delta delta) {
  for (const Delta& d : redo_) bytes_ -= d.bytes();
  redo_.clear();
  const size_t b = delta.bytes();
  if (b > limits_.max_bytes || limits_.max_steps == 0) {
    const size_t dropped = undo_.size();
    clear();
    return "undo history: step '" + delta.label + "' needs " + mib(b) + ", more than the whole cap of " +
           mib(limits_.max_bytes) + "; it was applied but cannot be undone" +
           (dropped ? " and the " + std::to_string(dropped) + " earlier steps were dropped" : std::string()) +
           " (raise the history cap to keep them)";
  }
  size_t dropped = 0;
  while (!undo_.empty() && (bytes_ + b > limits_.max_bytes || undo_.size() + 1 > limits_.max_steps)) {
    bytes_ -= undo_.front().bytes();
    undo_.pop_front();
    ++dropped;
  }
  bytes_ += b;
  undo_.push_back(std::move(delta));
  if (dropped == 0) return "";
  return "undo history full (cap " + mib(limits_.max_bytes) + ", " + std::to_string(limits_.max_steps) +
         " steps): dropped the " + std::to_string(dropped) + " oldest step" + (dropped > 1 ? "s" : "") +
         "; those can no longer be undone";
}

const Delta& History::pop_undo() {
  if (undo_.empty()) throw Error("undo", "nothing to undo");
  redo_.push_back(std::move(undo_.back()));
  undo_.pop_back();
  return redo_.back();
}

const Delta& History::pop_redo() {
  if (redo_.empty()) throw Error("redo", "nothing to redo");
  undo_.push_back(std::move(redo_.back()));
  redo_.pop_back();
  return undo_.back();
}

EditSession::EditSession(GaussianScene scene, HistoryLimits limits)
    : scene_(std::move(scene)), fingerprint_(scene_.fingerprint()), mask_(scene_.size(), false), history_(limits) {}

void EditSession::step_done(const Delta& d) {
  if (!d.modified.empty() || !d.removed.empty() || d.appended.size() > 0) fingerprint_ = scene_.fingerprint();
}

void EditSession::select(const Selection& sel, const std::string& label) {
  sel.check_matches(scene_, fingerprint_, label);
  Delta d;
  d.label = label;
  for (size_t i = 0; i < mask_.size(); ++i)
    if (mask_[i] != sel.mask[i]) d.flipped.push_back(uint32_t(i));
  apply(std::move(d));
}

void EditSession::apply(Delta delta) {
  notice_.clear();
  apply_delta(delta, scene_, mask_);
  step_done(delta);
  notice_ = history_.push(std::move(delta));
}

std::string EditSession::undo() {
  notice_.clear();
  if (!history_.can_undo()) throw Error("undo", "nothing to undo");
  const Delta& d = history_.pop_undo();
  revert_delta(d, scene_, mask_);
  step_done(d);
  return d.label;
}

std::string EditSession::redo() {
  notice_.clear();
  if (!history_.can_redo()) throw Error("redo", "nothing to redo");
  const Delta& d = history_.pop_redo();
  apply_delta(d, scene_, mask_);
  step_done(d);
  return d.label;
}

}  // namespace isegman::edit
