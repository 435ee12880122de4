// The web app, composed: the scene being edited (EditState), the interactive
// segmentation as background jobs (SegmentationJobs), the activity log, renders and
// exports. Requests and answers are typed structs; JSON and HTTP status codes live only
// in the API layer (api.cc, api_json.h), which maps AppError kinds to codes.
//
// Consistency of indices: the segmentation runs on a snapshot of the edited scene and
// remembers its fingerprint. A click result becomes the edit selection only while the
// edited scene still has that fingerprint (segmentation_jobs.h).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/scene.h"
#include "edit/colorize.h"
#include "edit/edit_op.h"
#include "edit/scene_format.h"
#include "segment/session.h"
#include "segment/views.h"
#include "server/activity_log.h"
#include "server/display_state.h"
#include "server/edit_state.h"
#include "server/free_camera.h"
#include "server/jobs.h"
#include "server/scene_files.h"
#include "server/pick.h"
#include "server/segmentation.h"
#include "server/segmentation_jobs.h"

namespace isegman::server {

struct AppOptions {
  std::string out_dir = "isegman-out";  // exports are written only below this folder
  std::string data_dir;                 // inputs (combine) are read only below this folder; "" = the scene's parent
  std::string sam_dir;                  // encoder.onnx + sam.onnx; "" = models::default_sam_dir()
  bool segmentation = true;             // false: selection tools and edits only
  segment::SessionOptions session;
  segment::ViewOptions views;           // working resolution, embedding cache, threads
  SegmentSettings settings;             // tau, view sampling, propagation, inspection
  int preview_side = 640;               // default longest side of navigation renders
  float background[3] = {0.f, 0.f, 0.f};
  int threads = 0;
  uint64_t max_upload_bytes = uint64_t(256) << 20;  // scenes uploaded to combine
  // Views and scene copies of earlier scenes' segmentations kept for undo (segmentation.h).
  uint64_t kept_segmentation_bytes = uint64_t(2) << 30;
  AppOptions() { views.max_side = 512; }
};

struct RenderRequest {
  int camera_index = -1;                // a training camera, or
  std::optional<FreeCameraSpec> free;   // a free camera
  int max_side = 0;                     // longest side; 0 = the camera's full resolution
  bool highlight = true;                // tint the current selection
  float tint = 0.5f;                    // its opacity (the page's highlight slider)
  bool png = false;                     // else JPEG
  std::optional<edit::Rgb> background;
};

struct SceneInfo {
  std::string name, ply;
  size_t gaussians = 0;
  int sh_degree = 0;
  Vec3 lo, hi;             // the bounding box of the centres (outliers included)
  RobustBounds robust{};   // percentile box: the free camera's pivot is its centre
  double orbit_distance = 0;  // where the robust box fills ~80% of a 60-degree view
  std::vector<Camera> cameras;
  int preview_side = 0;
  std::string out_dir, data_dir;
  float background[3] = {0.f, 0.f, 0.f};
};

struct AppStatus {
  JobStatus job;
  bool busy = false;
  size_t queued = 0;
  EditStatus edit;
  SegmentationStatus segmentation;
  std::vector<LogEntry> log;
  uint64_t version = 0;
};

// Where a combine's other scene comes from.
enum class SceneSource { kDataFolder, kUpload };

struct ExportResult {
  std::string path;
  size_t gaussians = 0;
  std::vector<std::string> notes;
};

class AppState {
  Camera camera_for(const RenderRequest& request) const;

 public:
  AppState(SceneBundle bundle, AppOptions options);
  ~AppState();

  // Loads SAM and prepares the segmentation views in the background.
  void start();
  // Stops the job runner (drops queued work, waits for the running job).
  void stop();
  JobRunner& jobs() { return jobs_; }
  const AppOptions& options() const { return options_; }

  SceneInfo scene_info() const;
  AppStatus status() const;
  std::vector<uint8_t> render(const RenderRequest& request) const;
  std::vector<uint8_t> thumbnail(int index) const { return segmentation_.thumbnail(index); }
  // For the page's WebGL renderer (scene_binary.h): the Gaussians, and the selection with
  // the display state's hidden flags.
  std::vector<uint8_t> splats() const;
  std::vector<uint8_t> selection_mask() const;
  // Hide / isolate the selection, show all: drawn by the page and by render(), nothing else.
  DisplayResult display(DisplayOp op);
  // The surface point under (x, y), pixels of the view's full-size image (pick-to-focus).
  PickResult pick(const RenderRequest& view, double x, double y) const;

  // Segmentation work runs as jobs; these return the job id.
  // The click segments what the page shows: the display state's hidden Gaussians are
  // neither in its view nor selectable.
  uint64_t click(ClickRecord click);
  // The last click's mask one step larger (+1) or smaller (-1): a job, as a click is.
  uint64_t granularity(int step) { return segmentation_.granularity(step); }
  // The old click endpoints: walk the history when its step is a click (the job id).
  uint64_t undo_click() { return undo(StepFilter::kClick).job; }
  uint64_t redo_click() { return redo(StepFilter::kClick).job; }
  uint64_t set_settings(const SettingsRequest& request) { return segmentation_.set_settings(request); }
  // The camera the user looks at: views a click there would use are built in the background.
  void focus(int camera) { segmentation_.focus(camera); }
  size_t camera_count() const { return bundle_.cameras.size(); }
  bool wait_built_ahead(double timeout_seconds) { return segmentation_.wait_built_ahead(timeout_seconds); }

  EditResult select(const SelectRequest& request);
  SelectionBounds selection_bounds() const { return scene_.selection_bounds(); }
  // Runs an edit (edit/edit_op.h, the CLI's vocabulary); a combine's other scene is
  // `op.other_path` inside the data folder, or the upload of that name.
  EditResult edit(const edit::EditOp& op, SceneSource source = SceneSource::kDataFolder);
  // Scenes to combine: the data folder's and the uploaded ones (scene_files.h).
  std::vector<SceneFileEntry> data_files() const { return files_.list_data(); }
  std::string data_folder() const;  // absolute; "" when none
  std::vector<SceneFileEntry> uploads() const { return files_.list_uploads(); }
  SceneFileEntry upload(const std::string& name, const std::string& bytes);
  // One history of clicks, selections and edits (EditState's timeline): the scene and
  // selection are restored at once; walking over a click also queues a job that brings
  // the segmentation's clicks in line (EditResult::job).
  EditResult undo(StepFilter filter = StepFilter::kAny);
  EditResult redo(StepFilter filter = StepFilter::kAny);
  // The old edit endpoints: walk the history when its step is not a click.
  EditResult undo_edit() { return undo(StepFilter::kNotClick); }
  EditResult redo_edit() { return redo(StepFilter::kNotClick); }

  std::vector<uint8_t> export_bytes(edit::SceneFormat format) const { return scene_.serialize(format); }
  // Writes under the output directory.
  ExportResult export_to(const std::string& relative_path);

 private:
  const SceneBundle bundle_;  // cameras and paths (the Gaussians live in scene_)
  const AppOptions options_;
  const std::string data_dir_;
  ActivityLog log_;
  EditState scene_;
  SceneFiles files_;
  mutable DisplayState display_;  // forgets its flags when the Gaussian count changes
  JobRunner jobs_;
  SegmentationJobs segmentation_;
};

}  // namespace isegman::server
