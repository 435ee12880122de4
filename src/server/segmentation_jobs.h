// The interactive segmentation of the web app as background jobs: loading SAM and
// preparing the views, clicks, click undo/redo and new settings, each a job on the
// JobRunner. A click's selection is handed to the EditState only while the edited scene
// still matches the scene the segmentation runs on (edit_state.h); otherwise the next
// click re-opens the segmentation on the edited scene.
//
// Locks: seg_mu_ (the Segmentation, held by jobs) before the EditState's lock before
// status_mu_ (the published status and thumbnails). Request threads never wait on seg_mu_.
#pragma once

#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "core/scene.h"
#include "segment/propagation.h"
#include "segment/session.h"
#include "segment/views.h"
#include "server/activity_log.h"
#include "server/edit_state.h"
#include "server/jobs.h"
#include "server/segmentation.h"

namespace isegman::models {
class SamModel;
}

namespace isegman::server {

struct SegmentationOptions {
  bool enabled = true;
  std::string sam_dir;              // encoder.onnx + sam.onnx; "" = models::default_sam_dir()
  segment::SessionOptions session;
  segment::ViewOptions views;
  SegmentSettings settings;
  int threads = 0;
  uint64_t kept_bytes = uint64_t(2) << 30;  // Segmentation::set_kept_budget
};

// New settings; unset fields keep their current value.
struct SettingsRequest {
  std::optional<double> tau;
  std::optional<std::string> views;
  std::optional<segment::PropagationMode> mode;
  std::optional<bool> inspection;
};

struct SegmentationStatus {
  std::string state;    // off, starting, preparing, ready, error
  std::string message;
  bool stale = false;   // the scene was edited since: the next click segments the edited scene
  size_t clicks = 0, selected = 0;  // clicks: the log's entries, Larger / Smaller steps included
  size_t steps = 0;                   // ... of them Larger / Smaller steps
  bool can_undo = false, can_redo = false;
  bool can_grow = false, can_shrink = false;  // SAM has a larger / smaller mask at the last click
  std::vector<ViewEvidence> views;
  uint64_t thumb_version = 0;
  SegmentSettings settings;
};

class SegmentationJobs {
 public:
  // `bundle`: the cameras and paths (its Gaussians are not used; snapshots come from `scene`).
  SegmentationJobs(const SceneBundle& bundle, SegmentationOptions options, EditState& scene, JobRunner& jobs,
                   ActivityLog& log);

  ~SegmentationJobs();  // stop_building_ahead()

  void start();  // loads SAM and prepares the views (a job)

  // The camera the user looks at (the page sends the shown training camera, or the one
  // nearest its free camera). While no job runs, a background thread builds the views a
  // first click there would use (Segmentation::prefetch_one), one at a time, so that click
  // finds them built; a job waits at most for the view being built. Never throws.
  void focus(int camera);
  // Blocks until the views for the focused camera are built (tests); false on timeout.
  bool wait_built_ahead(double timeout_seconds);
  void stop_building_ahead();  // joins the thread; idempotent

  uint64_t click(const ClickRecord& click);
  // The last click's mask one step larger (+1) or smaller (-1) among SAM's candidates
  // (Segmentation::step_granularity), as a job a click's history step records.
  uint64_t granularity(int step);
  // The one history (EditState's timeline) walked back or forward over a click made on
  // the scene with `fingerprint`; the history already restored the selection exactly. A
  // job brings the segmentation's click log and evidence in line. Returns its id (0 when
  // none could be queued); never throws.
  uint64_t follow_undo(uint64_t fingerprint) { return follow(true, fingerprint); }
  uint64_t follow_redo(uint64_t fingerprint) { return follow(false, fingerprint); }
  uint64_t set_settings(const SettingsRequest& request);
  // The edited scene changed (edit, undo, redo): when it is back to a scene an earlier
  // segmentation ran on, a quick job makes that segmentation (its clicks, evidence and
  // click undo) current again. Never throws; a full queue just skips it.
  void scene_changed();

  SegmentationStatus status(uint64_t edit_fingerprint) const;
  // Evidence thumbnail of view `index` (JPEG); AppError(kNotFound) when absent.
  std::vector<uint8_t> thumbnail(int index) const;

 private:
  using Progress = Segmentation::Progress;
  // A copy of the scene as it is now, with its fingerprint (read together).
  std::shared_ptr<const SceneBundle> snapshot(uint64_t& fingerprint) const;
  void prepare_job(const JobRunner::Report& report);
  void ensure_current(const Progress& progress);       // seg_mu_ held
  // Returns false when the selection should have been applied but the scene had changed.
  // `what` and `kind` name the history step the applied selection becomes.
  bool publish(bool apply_selection, const std::string& what = "click",
               StepKind kind = StepKind::kClick);   // seg_mu_ held
  uint64_t follow(bool undo, uint64_t fingerprint);
  void set_state(const std::string& state, const std::string& message);
  void require_available() const;
  uint64_t submit(const std::string& name, std::function<void(const Progress&)> work);

  const SceneBundle& bundle_;
  const SegmentationOptions options_;
  EditState& scene_;
  JobRunner& jobs_;
  ActivityLog& log_;

  std::mutex seg_mu_;
  std::shared_ptr<const models::SamModel> sam_;
  std::unique_ptr<Segmentation> seg_;

  void build_ahead_loop();
  void rearm_building_ahead();  // after a job: the focused camera may want views again

  // The builder's own state (never held while taking seg_mu_).
  std::mutex ahead_mu_;
  std::condition_variable ahead_cv_;
  int focus_ = -1;
  bool ahead_done_ = true;   // nothing left to build for focus_
  bool ahead_stop_ = false;
  std::thread ahead_thread_;  // started by the first focus()

  mutable std::mutex status_mu_;
  SegmentationStatus published_;
  uint64_t seg_fingerprint_ = 0;
  std::vector<uint64_t> kept_;  // fingerprints Segmentation::restore can bring back
  std::vector<std::vector<uint8_t>> thumbs_;
};

}  // namespace isegman::server
