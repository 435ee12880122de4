// Everything the web app shows and changes: the scene being edited (an EditSession with
// undo/redo), the interactive segmentation (clicks -> 3D selection, with per-view
// evidence), background jobs, renders and exports. HTTP-independent and thread-safe:
// the API layer (api.h) only parses requests and calls these methods.
//
// Consistency of indices: the segmentation runs on a snapshot of the edited scene and
// remembers its fingerprint. A click result becomes the edit selection only while the
// edited scene still has that fingerprint; after an edit that changes the scene the
// segmentation is "stale" and the next click re-opens it on the edited scene (fresh
// views, clicks start over). Undoing the edit makes it current again.
//
// Locks: seg_mu_ (segmentation, held by jobs) before edit_mu_ (scene; renders share it)
// before status_mu_ (published status, thumbnails). HTTP handlers never wait on seg_mu_.
#pragma once

#include <atomic>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <shared_mutex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/scene.h"
#include "edit/colorize.h"
#include "edit/history.h"
#include "edit/scene_format.h"
#include "segment/session.h"
#include "segment/views.h"
#include "server/free_camera.h"
#include "server/jobs.h"
#include "server/segmentation.h"

namespace isegman::server {

struct AppOptions {
  std::string out_dir = "isegman-out";  // exports are written only below this folder
  std::string sam_dir;                  // encoder.onnx + sam.onnx; "" = models::default_sam_dir()
  bool segmentation = true;             // false: selection tools and edits only
  segment::SessionOptions session;
  segment::ViewOptions views;           // working resolution, embedding cache, threads
  SegmentSettings settings;             // tau, view sampling, propagation, inspection
  int preview_side = 640;               // default longest side of navigation renders
  float background[3] = {0.f, 0.f, 0.f};
  int threads = 0;
  AppOptions() { views.max_side = 512; }
};

struct RenderRequest {
  int camera_index = -1;                // a training camera, or
  std::optional<FreeCameraSpec> free;   // a free camera
  int max_side = 0;                     // longest side; 0 = the camera's full resolution
  bool highlight = true;                // tint the current selection
  bool png = false;                     // else JPEG
  std::optional<edit::Rgb> background;
};

class AppState {
 public:
  AppState(SceneBundle bundle, AppOptions options);
  ~AppState();

  // Loads SAM and prepares the segmentation views in the background.
  void start();
  // Stops the job runner (drops queued work, waits for the running job).
  void stop();
  JobRunner& jobs() { return jobs_; }
  const AppOptions& options() const { return options_; }

  nlohmann::json scene_info() const;
  nlohmann::json status() const;
  std::vector<uint8_t> render(const RenderRequest& request) const;
  // Evidence thumbnail of segmentation view `index` (JPEG); 404 when absent.
  std::vector<uint8_t> thumbnail(int index) const;

  // Segmentation work runs as jobs; these return the job id.
  uint64_t click(const ClickRecord& click);
  uint64_t undo_click();
  uint64_t redo_click();
  uint64_t set_settings(const SegmentSettings& settings);

  // Selection helpers: "box", "sphere", "invert", "clear", "all" (body: shape, mode).
  nlohmann::json select(const std::string& tool, const nlohmann::json& body);
  // Bounds of the selection (or the scene when nothing is selected).
  nlohmann::json selection_bounds() const;
  // Edits: "remove", "colorize", "scale", "copy", "move", "combine".
  nlohmann::json edit(const std::string& op, const nlohmann::json& body);
  nlohmann::json undo_edit();
  nlohmann::json redo_edit();

  std::vector<uint8_t> export_bytes(edit::SceneFormat format) const;
  // Writes under the output directory; returns {path, gaussians, notes}.
  nlohmann::json export_to(const std::string& relative_path);

 private:
  using Progress = Segmentation::Progress;
  std::shared_ptr<const SceneBundle> snapshot() const;
  void prepare_job(const JobRunner::Report& report);
  // Opens the segmentation on the current scene when it is stale (seg_mu_ held).
  void ensure_current(const Progress& progress);
  // Pushes the segmentation's selection into the edit session and publishes the
  // segmentation status and thumbnails (seg_mu_ held).
  void publish_segmentation(bool apply_selection);
  void after_scene_change();  // edit_mu_ held exclusively
  nlohmann::json edit_result(const std::string& label, const std::vector<std::string>& notes) const;
  void note(const std::string& text, const std::string& level = "info");
  std::string require_segmentation() const;
  uint64_t submit_segmentation_job(const std::string& name, std::function<void(const Progress&)> work);

  const SceneBundle bundle_;  // cameras and paths (gaussians moved into edit_)
  const AppOptions options_;
  JobRunner jobs_;

  std::mutex seg_mu_;
  std::shared_ptr<const models::SamModel> sam_;
  std::unique_ptr<Segmentation> seg_;

  mutable std::shared_mutex edit_mu_;
  edit::EditSession edit_;
  uint64_t edit_fingerprint_ = 0;

  mutable std::mutex status_mu_;
  std::string seg_state_ = "starting";  // off, starting, preparing, ready, error
  std::string seg_message_;
  uint64_t seg_fingerprint_ = 0;
  nlohmann::json seg_views_ = nlohmann::json::array();
  size_t seg_clicks_ = 0, seg_selected_ = 0;
  bool seg_can_undo_ = false, seg_can_redo_ = false;
  SegmentSettings seg_settings_;
  std::vector<std::vector<uint8_t>> thumbs_;
  uint64_t thumb_version_ = 0;
  std::deque<nlohmann::json> log_;
  std::atomic<uint64_t> version_{1};
  std::atomic<uint64_t> edit_revision_{1};  // scene or selection changed: re-render
  uint64_t log_seq_ = 0;
};

}  // namespace isegman::server
