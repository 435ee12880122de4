// The app's segmentation: a segment::Session over a snapshot of the scene, the log of
// the user's clicks (for redo and for re-running them under new settings) and the
// free-camera views added by clicks outside the training cameras.
//
// The session works on the snapshot it was opened on; the app re-opens it when the
// edited scene no longer matches (its fingerprint differs), so the selection indices
// always refer to the scene being edited. Not thread-safe: the app serialises access.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/centre_index.h"
#include "core/click.h"
#include "core/scene.h"
#include "models/sam.h"
#include "segment/session.h"

namespace isegman::server {

struct SegmentSettings {
  double tau = 0.8;
  std::string views_spec = "50%";
  segment::PropagationMode mode = segment::PropagationMode::Hybrid;
  bool inspection = true;
};

// A user click: in a training camera (camera_index >= 0) or a free camera, at continuous
// pixel coordinates of that camera's full-size image (core/click.h), as the page sends it.
// `hidden`: the Gaussians hidden from display when it was made (one flag per Gaussian, or
// empty): the click segments what the user saw, and none of them can be selected.
// `granularity` (+1 / -1): not a new click but the last click's mask one step larger or
// smaller (Session::change_granularity); the other fields repeat that click's.
struct ClickRecord {
  int camera_index = -1;
  std::optional<Camera> free_camera;
  Click click;
  std::vector<bool> hidden;
  int granularity = 0;
};

// What the evidence strip shows of one segmentation view.
struct ViewEvidence {
  size_t index = 0;
  std::string name;
  int camera = -1;             // -1: a free camera
  std::string status;          // accepted, dropped, no-clicks, empty-mask, skipped, idle
  std::string status_text;
  int positive = 0, negative = 0;
  size_t not_sent = 0;
  std::string not_sent_reason;
  int mask_pixels = 0;
  double sam_score = 0;
  double overlap = 0;
  bool inspected = false;      // false: accepted without inspection (the clicked view, or inspection off)
};

class Segmentation {
 public:
  using Progress = std::function<void(int done, int total, const std::string& message)>;

  Segmentation(std::shared_ptr<const models::SamModel> sam, segment::SessionOptions session_options,
               segment::ViewOptions view_options, SegmentSettings settings);

  // Builds the sampled views of `snapshot` (embeddings from the cache when present)
  // and opens an empty session; the click log is cleared. Views the edit since the
  // previous scene cannot have changed are taken from it (view_reuse.h), and views
  // prepared ahead for this scene (prepare) are used as they are. The segmentation of the scene
  // it replaces is kept (the last few), so undoing edits back to that scene brings its
  // clicks back (restore); a kept one for `fingerprint` is reopened as it was.
  void open(std::shared_ptr<const SceneBundle> snapshot, uint64_t fingerprint, const Progress& progress);
  // Builds ahead the views of an edited scene (`snapshot`, not yet current), reusing
  // the current session's views the edit does not reach; the next open() of that
  // scene takes them. Cameras clicked in that are not sampled views are prepared too
  // (the next click is likely there). Reports per view whether it was reused or rebuilt.
  void prepare(std::shared_ptr<const SceneBundle> snapshot, uint64_t fingerprint, const Progress& progress);
  bool prepared_for(uint64_t fingerprint) const { return prepared_ && prepared_->fingerprint == fingerprint; }
  // Of the last views built: how many were reused from the previous scene / rebuilt.
  int last_reused() const { return last_reused_; }
  int last_rebuilt() const { return last_rebuilt_; }
  // Fingerprints of the kept segmentations of earlier scenes (oldest first).
  std::vector<uint64_t> kept() const;
  // The kept segmentations and the spare views (built, not in the current session) together
  // hold at most this many bytes of views and scene copies: the oldest kept segmentations go
  // first, then the oldest spare views (a large scene's views are ~0.1-0.2 GB each, and
  // every kept segmentation holds a full set). The current session is never touched.
  void set_kept_budget(size_t bytes);
  size_t kept_bytes() const;   // of the kept segmentations
  size_t spare_bytes() const;  // of the spare views
  // Cameras of the current session's views, in its order.
  std::vector<int> view_cameras() const;
  // Builds ahead (render + SAM embedding) one view a first click in camera `camera` is
  // likely to use, in order: the camera's own view, then the views choose_views_for would
  // pick for a click at its image centre. Built views wait as spares. A view it builds, or
  // finds built without them, also gets the SAM decoder's values for its image (one decode:
  // every later decode there without a previous mask, the first click's included, skips
  // ~a fifth of its work). True when it built a view or made a view's decoder values; false
  // when there is nothing to do: the views are not "auto", the segmentation has clicks (its
  // views are chosen), all are built and ready, or the kept budget has no room.
  bool prefetch_one(int camera, const Progress& progress);
  // Cameras with a built view: the session's and the spares.
  bool has_view_of(int camera) const;
  // Whether the built view of `camera` holds the SAM decoder's values for its image.
  bool decoder_ready(int camera) const;
  // Makes the kept segmentation of `fingerprint` current (the current one is kept);
  // false when there is none.
  bool restore(uint64_t fingerprint);
  bool is_open() const { return session_ != nullptr; }
  uint64_t fingerprint() const { return fingerprint_; }

  // One round for a click; adds the free camera's view first when needed. Clears redo.
  segment::RoundReport click(const ClickRecord& click, const Progress& progress);
  // The last click's mask one step larger (step > 0) or smaller among SAM's candidates: a
  // round like a click's, logged, undone and redone as one. Throws AppError(kConflict) when
  // there is no click, the last one is negative, or SAM has no such candidate there.
  segment::RoundReport step_granularity(int step, const Progress& progress);
  // Whether SAM has a larger (step > 0) / smaller mask at the last click.
  bool can_step_granularity(int step) const { return session_ && session_->can_change_granularity(step); }
  bool can_undo() const { return !log_.empty(); }
  bool can_redo() const { return !redo_.empty(); }
  void undo();                              // throws AppError(kConflict) when nothing to undo
  void redo(const Progress& progress);      // re-runs the undone click
  // New settings: rebuilds the views and replays the clicks (embeddings cached).
  void reconfigure(const SegmentSettings& settings, const Progress& progress);
  const SegmentSettings& settings() const { return settings_; }

  const std::vector<bool>& selection() const;
  size_t selected_count() const;
  const std::vector<ClickRecord>& clicks() const { return log_; }
  // Per view: name, camera, clicks, mask size, inspection verdict.
  std::vector<ViewEvidence> evidence() const;
  // Evidence thumbnail of every view (JPEG, longest side `side`).
  std::vector<std::vector<uint8_t>> thumbnails(int side) const;
  size_t view_count() const;

 private:
  int view_for(const ClickRecord& click, const Progress& progress);
  // With an "auto" / "auto:K" view spec and more cameras than K, the first click of a
  // segmentation chooses its views as `segment` does: the K cameras that best see the
  // clicked surface point, spread around it (view_selection.h), so a click's cost does not
  // grow with the number of cameras and every view sees the target. A free camera's click
  // chooses them from the training camera nearest it and keeps its own view after them.
  // Built views are reused (the others wait as spares); true when the views changed.
  bool choose_views_for(const ClickRecord& click, const Progress& progress);
  // K of an "auto" / "auto:K" spec when the scene has more cameras than K (the views are
  // then chosen per segmentation), else 0.
  int chosen_view_count() const;
  // The clicked camera rendered without the hidden Gaussians (their opacity zeroed, so the
  // indices stay), added as a view of its own once per camera and hidden set.
  int shown_view_for(const ClickRecord& click, const Progress& progress);
  // The click's hidden flags when they fit the scene and hide something, else null.
  const std::vector<bool>* hidden_of(const ClickRecord& click) const;
  // `donor` / `donor_scene`: a session of another scene (or of this one) whose views the
  // scene change does not reach are reused; nullptr: build every view.
  void rebuild(const Progress& progress, const segment::Session* donor = nullptr,
               const GaussianScene* donor_scene = nullptr);
  std::vector<segment::SegmentView> build_views(const SceneBundle& snapshot, const std::vector<int>& chosen,
                                                const segment::Session* donor, const GaussianScene* donor_scene,
                                                const Progress& progress, int total);
  segment::SessionOptions session_options() const;

  // A view added for a click: a free camera, or any camera rendered without hidden Gaussians.
  struct AddedView {
    std::optional<Camera> camera;
    std::vector<bool> hidden;  // empty: the whole scene
  };
  struct Kept {
    std::shared_ptr<const SceneBundle> snapshot;
    uint64_t fingerprint = 0;
    std::unique_ptr<segment::Session> session;
    std::vector<ClickRecord> log, redo;
    std::vector<AddedView> free_views;
  };
  static constexpr size_t kKept = 3;  // each holds its views' renders and embeddings
  size_t kept_budget_ = size_t(2) << 30;
  static size_t bytes_of(const Kept& k);
  void trim_cache();
  void keep_current();

  std::vector<Kept> kept_;  // newest last
  struct Prepared {
    std::shared_ptr<const SceneBundle> snapshot;
    uint64_t fingerprint = 0;
    std::vector<int> chosen;
    std::vector<segment::SegmentView> views;  // of `chosen`
    std::vector<segment::SegmentView> extra;  // of the other cameras clicked in before
  };
  std::optional<Prepared> prepared_;
  // The built view of `camera` (the session's, else a spare of this scene), or null.
  const segment::SegmentView* built_view(int camera) const;
  // Cameras whose view prefetch_one has decoded once to make its decoder values (this scene).
  std::set<int> decoder_tried_;
  uint64_t decoder_tried_fingerprint_ = 0;
  // Prepared views of cameras outside the sampled ones, for a click there (scene `spare_fingerprint_`).
  std::vector<segment::SegmentView> spare_;
  uint64_t spare_fingerprint_ = 0;
  int last_reused_ = 0, last_rebuilt_ = 0;
  std::shared_ptr<const models::SamModel> sam_;
  segment::SessionOptions base_session_;
  segment::ViewOptions view_options_;
  SegmentSettings settings_;
  std::shared_ptr<const SceneBundle> snapshot_;
  uint64_t fingerprint_ = 0;
  // The snapshot's neighbour index (voting-view selection, then the sessions' decisions),
  // built at the first click that chooses views; rebuilt when the snapshot changes.
  std::shared_ptr<const CentreIndex> neighbours_;
  std::weak_ptr<const SceneBundle> neighbours_of_;
  const std::shared_ptr<const CentreIndex>& neighbours();
  // The views a click at the centre of camera `ahead_camera_` would choose (prefetch_one).
  int ahead_camera_ = -1;
  uint64_t ahead_fingerprint_ = 0;
  std::vector<int> ahead_views_;
  std::unique_ptr<segment::Session> session_;
  std::vector<ClickRecord> log_, redo_;
  std::vector<AddedView> free_views_;  // per session view: the camera it was added for, if any
};

}  // namespace isegman::server
