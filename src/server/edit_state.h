// The scene being edited: an EditSession (scene + selection + undo history) behind a
// reader/writer lock, with the fingerprint the segmentation compares against and a
// revision the page re-renders on. Typed in, typed out: no JSON, no HTTP.
#pragma once

#include <atomic>
#include <cstdint>
#include <optional>
#include <shared_mutex>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/math.h"
#include "core/virtual_views.h"
#include "core/scene.h"
#include "edit/edit_op.h"
#include "edit/select_op.h"
#include "edit/history.h"
#include "edit/scene_format.h"
#include "render/rasterizer.h"
#include "server/free_camera.h"

namespace isegman::server {

// A selection tool's request: the edit vocabulary's SelectOp (edit/select_op.h, what
// `isegman edit`'s selection flags mean too). The screen-space tools and the eyedropper
// name the camera they were drawn in: a training camera or a free one, which the app
// resolves into `op.camera`.
struct SelectRequest {
  edit::SelectOp op;
  int camera_index = -1;
  std::optional<FreeCameraSpec> free;
};

// The kinds of step in the one history: a segmentation click (its selection applied to
// the scene), an edit of the scene, or a selection tool (box, sphere, invert, ...).
enum class StepKind { kClick, kEdit, kSelect };
const char* step_kind_name(StepKind kind);

struct TimelineEntry {
  StepKind kind = StepKind::kEdit;
  std::string label;
  uint64_t fingerprint = 0;  // the scene's fingerprint while this step is applied
};

// The one history of clicks, selections and edits: `entries[0, cursor)` are applied,
// `entries[cursor, end)` can be redone.
struct Timeline {
  std::vector<TimelineEntry> entries;
  size_t cursor = 0;
};

// Which steps an undo/redo may take: any, or only a click (the old click endpoints), or
// only a non-click (the old edit endpoints).
enum class StepFilter { kAny, kClick, kNotClick };

// What an edit, a selection change or an undo/redo did.
struct EditResult {
  std::string label;
  std::vector<std::string> notes;
  std::string notice;    // history cap messages
  size_t gaussians = 0;
  size_t selected = 0;
  StepKind kind = StepKind::kEdit;  // the step made, or undone/redone
  uint64_t fingerprint = 0;         // undo/redo of a click: the scene it was made on
  uint64_t job = 0;      // undo/redo of a click: the job that brings the segmentation's clicks in line
};

struct EditStatus {
  size_t gaussians = 0, selected = 0;
  bool can_undo = false, can_redo = false;
  size_t undo_steps = 0, redo_steps = 0;
  std::string notice;
  uint64_t revision = 0;
  uint64_t fingerprint = 0;
  // The one history of clicks, selections and edits, read under the same lock as the
  // counts: a page that saw the scene after a redo must also see the redo's position.
  Timeline history;
};

struct SelectionBounds {
  bool of_selection = false;  // false: of the whole scene (nothing selected)
  size_t count = 0;
  Vec3 lo, hi, center;
  double radius = 0;
};

class EditState {
 public:
  explicit EditState(GaussianScene scene);

  // The scene and its fingerprint, read under one lock: an edit landing between two
  // separate reads would pair one scene with another's fingerprint.
  GaussianScene scene_copy(uint64_t& fingerprint) const;
  uint64_t fingerprint() const;
  uint64_t revision() const { return revision_.load(); }
  void bounds(Vec3& lo, Vec3& hi, int& sh_degree) const;
  // Percentile bounds of the opacity-weighted centres (core/virtual_views.h): far,
  // faint outliers do not move them.
  RobustBounds robust_bounds() const;
  EditStatus status() const;

  // Runs a selection tool (its camera already resolved); AppError(kInvalid) for
  // parameters the tool refuses.
  EditResult select(const edit::SelectOp& op);
  // Makes a click's selection current when the scene still has `fingerprint`; false
  // (nothing changed) when the scene was edited meanwhile.
  // Recorded in the history as one step of `kind` (a click, or kSelect for a re-run
  // under new settings).
  bool select_from_segmentation(const std::vector<bool>& mask, uint64_t fingerprint, const std::string& label,
                                StepKind kind = StepKind::kClick);
  // `other`: the loaded scene of a combine. Throws AppError(kConflict) when nothing is
  // selected, AppError(kInvalid) for parameters the toolbox refuses.
  EditResult edit(const edit::EditOp& op, const GaussianScene* other = nullptr);
  // Walk the one history; AppError(kConflict) when there is no step (of that filter).
  EditResult undo(StepFilter filter = StepFilter::kAny);
  EditResult redo(StepFilter filter = StepFilter::kAny);
  SelectionBounds selection_bounds() const;

  // Renders the edited scene, the selection tinted at opacity `tint` (0: not highlighted),
  // without the Gaussians flagged in `hidden` (the page's display state; null: all drawn).
  Image render(const Camera& camera, const RenderSettings& settings, float tint,
               const std::vector<bool>* hidden = nullptr) const;
  // Runs `fn(scene, selection mask, revision, fingerprint)` under the read lock, for views of the
  // scene that need the Gaussians and the selection together (the page's splat data).
  template <typename Fn>
  auto read(Fn&& fn) const {
    std::shared_lock<std::shared_mutex> lock(mu_);
    return fn(session_.scene(), session_.mask(), revision_.load(), session_.fingerprint());
  }
  std::vector<uint8_t> serialize(edit::SceneFormat format) const;
  // Writes the scene to `path` (never one of `inputs`); returns the Gaussian count.
  size_t write(const std::string& path, const std::vector<std::string>& inputs, std::vector<std::string>* notes) const;

 private:
  EditResult result(const std::string& label, const std::vector<std::string>& notes) const;
  void changed() { ++revision_; }  // the scene changed; lock held exclusively
  void record(StepKind kind, const std::string& label);  // after a step was pushed; lock held

  Timeline timeline_;
  mutable std::shared_mutex mu_;
  edit::EditSession session_;
  std::atomic<uint64_t> revision_{1};  // scene or selection changed: re-render
};

}  // namespace isegman::server
