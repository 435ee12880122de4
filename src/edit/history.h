// Undo/redo for an edit session. Every operation and every selection change is one
// Delta (edit/delta.h), so the history costs memory in proportion to what changed. A
// cap on bytes and steps bounds it: when a new step would exceed the cap, the oldest
// steps are dropped and a notice says so; a single step larger than the whole cap is
// applied but cannot be undone (also with a notice).
#pragma once

#include <deque>
#include <string>
#include <vector>

#include "core/scene.h"
#include "core/selection.h"
#include "edit/delta.h"

namespace isegman::edit {

struct HistoryLimits {
  size_t max_bytes = size_t(512) << 20;  // 512 MiB
  size_t max_steps = 10000;
};

class History {
 public:
  explicit History(HistoryLimits limits = {}) : limits_(limits) {}

  // Records an applied delta; clears the redo steps. Returns a notice ("" when none)
  // when the cap forced old steps out or the step could not be recorded.
  std::string push(Delta delta);
  bool can_undo() const { return !undo_.empty(); }
  bool can_redo() const { return !redo_.empty(); }
  // Moves the newest step to the redo list and returns it (to be reverted).
  const Delta& pop_undo();
  // Moves the newest undone step back and returns it (to be re-applied).
  const Delta& pop_redo();

  size_t undo_steps() const { return undo_.size(); }
  size_t redo_steps() const { return redo_.size(); }
  size_t bytes() const { return bytes_; }
  const HistoryLimits& limits() const { return limits_; }
  void clear();

 private:
  HistoryLimits limits_;
  std::deque<Delta> undo_;
  std::vector<Delta> redo_;
  size_t bytes_ = 0;
};

// A scene, its current selection and the undo history: what the CLI, the demo and an
// interactive front end drive. Operations always act on the current selection.
class EditSession {
 public:
  explicit EditSession(GaussianScene scene, HistoryLimits limits = {});

  const GaussianScene& scene() const { return scene_; }
  // scene().fingerprint(), kept current by every step that changes the scene: hashing it
  // reads every parameter (94 ms at 6M Gaussians), and every selection needs it.
  uint64_t fingerprint() const { return fingerprint_; }
  const std::vector<bool>& mask() const { return mask_; }
  // The current selection tied to the current scene.
  Selection selection() const { return Selection::from_mask(scene_, mask_, fingerprint_); }

  // Replaces the selection (undoable). Throws when it belongs to another scene.
  void select(const Selection& selection, const std::string& label = "select");
  // Applies a planned delta (from plan_* on scene() and selection()) and records it.
  void apply(Delta delta);

  // Undo / redo one step; return the step's label. Throw Error when there is none.
  std::string undo();
  std::string redo();

  const History& history() const { return history_; }
  // The notice of the last apply/select ("" when none): history cap messages.
  const std::string& notice() const { return notice_; }

 private:
  // After a step: a new fingerprint when it changed the scene (not for a selection alone).
  void step_done(const Delta& delta);

  GaussianScene scene_;
  uint64_t fingerprint_ = 0;
  std::vector<bool> mask_;
  History history_;
  std::string notice_;
};

}  // namespace isegman::edit
