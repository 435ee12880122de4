#include "server/segmentation_jobs.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "models/sam.h"
#include "segment/trained_background.h"
#include "server/app_error.h"

namespace fs = std::filesystem;

namespace isegman::server {

namespace {

constexpr int kThumbSide = 240;
const char* kReady = "click an object: left = add, right or shift = remove";

}  // namespace

SegmentationJobs::SegmentationJobs(const SceneBundle& bundle, SegmentationOptions options, EditState& scene,
                                   JobRunner& jobs, ActivityLog& log)
    : bundle_(bundle), options_(std::move(options)), scene_(scene), jobs_(jobs), log_(log) {
  published_.state = "starting";
  published_.settings = options_.settings;
  if (!options_.enabled) {
    published_.state = "off";
    published_.message = "segmentation is disabled (--no-segmentation); selection tools and edits work";
  }
}

SegmentationJobs::~SegmentationJobs() { stop_building_ahead(); }

void SegmentationJobs::focus(int camera) {
  if (!options_.enabled || camera < 0 || camera >= int(bundle_.cameras.size())) return;
  std::lock_guard<std::mutex> lock(ahead_mu_);
  if (ahead_stop_) return;
  // The same camera again re-checks too: an edit or a cleared segmentation may want views.
  focus_ = camera;
  ahead_done_ = false;
  if (!ahead_thread_.joinable()) ahead_thread_ = std::thread([this] { build_ahead_loop(); });
  ahead_cv_.notify_all();
}

void SegmentationJobs::rearm_building_ahead() {
  std::lock_guard<std::mutex> lock(ahead_mu_);
  if (focus_ < 0 || ahead_stop_) return;
  ahead_done_ = false;
  ahead_cv_.notify_all();
}

bool SegmentationJobs::wait_built_ahead(double timeout_seconds) {
  std::unique_lock<std::mutex> lock(ahead_mu_);
  return ahead_cv_.wait_for(lock, std::chrono::duration<double>(timeout_seconds), [&] { return ahead_done_; });
}

void SegmentationJobs::stop_building_ahead() {
  {
    std::lock_guard<std::mutex> lock(ahead_mu_);
    ahead_stop_ = true;
    ahead_cv_.notify_all();
  }
  if (ahead_thread_.joinable()) ahead_thread_.join();
}

void SegmentationJobs::build_ahead_loop() {
  std::unique_lock<std::mutex> lock(ahead_mu_);
  int built = 0, built_for = -1;  // views built for camera built_for since t0
  auto t0 = std::chrono::steady_clock::now();
  for (;;) {
    ahead_cv_.wait(lock, [&] { return ahead_stop_ || !ahead_done_; });
    if (ahead_stop_) return;
    const int camera = focus_;
    if (camera != built_for || built == 0) {
      built = 0;
      built_for = camera;
      t0 = std::chrono::steady_clock::now();
    }
    lock.unlock();
    // The user's work first: wait while a job runs or is queued.
    if (jobs_.busy()) {
      lock.lock();
      ahead_cv_.wait_for(lock, std::chrono::milliseconds(100));
      continue;
    }
    bool more = false;
    {
      std::lock_guard<std::mutex> seg_lock(seg_mu_);
      bool ready = false;
      {
        std::lock_guard<std::mutex> status_lock(status_mu_);
        ready = published_.state == "ready";
      }
      try {
        if (ready && seg_ && seg_->is_open() && seg_->fingerprint() == scene_.fingerprint())
          more = seg_->prefetch_one(camera, nullptr);
      } catch (const std::exception& e) {
        log_.note(std::string("building views ahead stopped: ") + e.what(), "warn");
      }
    }
    built += more;
    lock.lock();
    if (!more && focus_ == camera) {
      ahead_done_ = true;
      ahead_cv_.notify_all();
      if (built > 0) {
        char line[200];
        std::snprintf(line, sizeof line, "built %d view(s) ahead for a click in camera %d (%.1f s)", built, camera,
                      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        log_.note(line);
      }
      built = 0;
    }
  }
}

void SegmentationJobs::start() {
  if (!options_.enabled) return;
  jobs_.submit("prepare segmentation", [this](const JobRunner::Report& report) { prepare_job(report); });
}

void SegmentationJobs::set_state(const std::string& state, const std::string& message) {
  std::lock_guard<std::mutex> lock(status_mu_);
  published_.state = state;
  published_.message = message;
  log_.bump();
}

std::shared_ptr<const SceneBundle> SegmentationJobs::snapshot(uint64_t& fingerprint) const {
  auto b = std::make_shared<SceneBundle>(bundle_);
  b->gaussians = scene_.scene_copy(fingerprint);
  return b;
}

void SegmentationJobs::prepare_job(const JobRunner::Report& report) {
  std::lock_guard<std::mutex> seg_lock(seg_mu_);
  try {
    const std::string dir = options_.sam_dir.empty() ? models::default_sam_dir() : options_.sam_dir;
    const fs::path enc = fs::path(dir) / "encoder.onnx", dec = fs::path(dir) / "sam.onnx";
    if (!fs::exists(enc) || !fs::exists(dec)) {
      set_state("off", "SAM model files missing in " + dir +
                           " (run scripts/setup.sh or pass --sam DIR); selection tools and edits still work");
      log_.note("segmentation unavailable: SAM model files missing in " + dir, "warn");
      return;
    }
    set_state("preparing", "loading SAM");
    report(0, 0, "loading SAM from " + dir);
    if (!options_.views.cache_dir.empty()) {
      std::error_code ec;
      fs::create_directories(options_.views.cache_dir, ec);
    }
    sam_ = std::make_shared<const models::SamModel>(enc.string(), dec.string(), options_.threads);
    uint64_t fingerprint = 0;
    std::shared_ptr<const SceneBundle> snap = snapshot(fingerprint);
    // SAM sees the views over the colour the scene was trained on (trained_background.h),
    // found once from the photos of the scene as loaded: an edited scene no longer matches them.
    segment::ViewOptions views = options_.views;
    segment::SessionOptions session = options_.session;
    const std::string background_line = segment::use_trained_background(*snap, views, session);
    if (!background_line.empty()) log_.note(background_line);
    seg_ = std::make_unique<Segmentation>(sam_, session, views, options_.settings);
    seg_->set_kept_budget(size_t(options_.kept_bytes));
    set_state("preparing", "rendering views and computing SAM embeddings");
    seg_->open(snap, fingerprint, [&](int done, int total, const std::string& line) {
      report(done, total, line);
      std::lock_guard<std::mutex> lock(status_mu_);
      published_.message = "preparing views: " + line;
      log_.bump();
    });
    set_state("ready", kReady);
    publish(false);
    log_.note("segmentation ready: " + std::to_string(seg_->view_count()) + " views");
    rearm_building_ahead();
  } catch (const std::exception& e) {
    set_state("error", std::string("segmentation could not start: ") + e.what());
    log_.note(std::string("segmentation could not start: ") + e.what(), "error");
    throw;
  }
}

void SegmentationJobs::ensure_current(const Progress& progress) {
  if (!seg_ || !seg_->is_open()) throw AppError(ErrorKind::kUnavailable, "segmentation is not ready");
  if (seg_->fingerprint() == scene_.fingerprint()) return;
  const uint64_t now = scene_.fingerprint();
  const bool prepared = seg_->prepared_for(now);
  log_.note(prepared ? "the scene was edited: segmenting the edited scene (its views were prepared; clicks start over)"
                     : "the scene was edited: segmenting the edited scene (changed views re-rendered, clicks start over)");
  set_state("preparing", "updating the views of the edited scene");
  uint64_t fingerprint = 0;
  std::shared_ptr<const SceneBundle> snap = snapshot(fingerprint);
  seg_->open(snap, fingerprint, progress);
  if (!prepared && seg_->last_reused() + seg_->last_rebuilt() > 0)
    log_.note("views: " + std::to_string(seg_->last_reused()) + " kept, " + std::to_string(seg_->last_rebuilt()) +
              " re-rendered");
  set_state("ready", kReady);
}

bool SegmentationJobs::publish(bool apply_selection, const std::string& what, StepKind kind) {
  if (!seg_) return true;
  const bool applied =
      !apply_selection || !seg_->is_open() ||
      scene_.select_from_segmentation(seg_->selection(), seg_->fingerprint(),
                                      what + ": " + std::to_string(seg_->selected_count()) + " Gaussians", kind);
  std::vector<std::vector<uint8_t>> thumbs = seg_->thumbnails(kThumbSide);
  std::vector<ViewEvidence> views = seg_->evidence();
  std::lock_guard<std::mutex> lock(status_mu_);
  thumbs_ = std::move(thumbs);
  published_.views = std::move(views);
  seg_fingerprint_ = seg_->fingerprint();
  published_.clicks = seg_->clicks().size();
  published_.steps = size_t(std::count_if(seg_->clicks().begin(), seg_->clicks().end(),
                                          [](const ClickRecord& c) { return c.granularity != 0; }));
  published_.selected = seg_->selected_count();
  published_.can_undo = seg_->can_undo();
  published_.can_redo = seg_->can_redo();
  published_.can_grow = seg_->can_step_granularity(1);
  published_.can_shrink = seg_->can_step_granularity(-1);
  published_.settings = seg_->settings();
  kept_ = seg_->kept();
  ++published_.thumb_version;
  log_.bump();
  return applied;
}

void SegmentationJobs::require_available() const {
  std::lock_guard<std::mutex> lock(status_mu_);
  if (published_.state == "off" || published_.state == "error")
    throw AppError(ErrorKind::kUnavailable, "segmentation unavailable: " + published_.message);
}

uint64_t SegmentationJobs::submit(const std::string& name, std::function<void(const Progress&)> work) {
  require_available();
  return jobs_.submit(name, [this, work, name](const JobRunner::Report& report) {
    std::lock_guard<std::mutex> seg_lock(seg_mu_);
    try {
      work(report);
      rearm_building_ahead();
    } catch (const std::exception& e) {
      log_.note(name + " failed: " + e.what(), "error");
      // Whatever happened, show the segmentation as it now is.
      if (seg_ && seg_->is_open()) publish(false);
      {
        std::lock_guard<std::mutex> lock(status_mu_);
        if (published_.state == "preparing") published_.state = seg_ && seg_->is_open() ? "ready" : "error";
      }
      throw;
    }
  });
}

uint64_t SegmentationJobs::click(const ClickRecord& c) {
  if (c.camera_index >= int(bundle_.cameras.size()) || (c.camera_index < 0 && !c.free_camera))
    invalid("view: no camera " + std::to_string(c.camera_index));
  const Camera& cam = c.free_camera ? *c.free_camera : bundle_.cameras[size_t(c.camera_index)];
  if (!(c.click.x >= 0 && c.click.x < cam.width && c.click.y >= 0 && c.click.y < cam.height))
    invalid("x, y: must lie in the camera's image, [0, " + std::to_string(cam.width) + ") x [0, " +
            std::to_string(cam.height) + ") pixels");
  if (c.click.label != 0 && c.click.label != 1) invalid("label: must be 1 (positive) or 0 (negative)");
  return submit("click", [this, c](const Progress& progress) {
    ensure_current(progress);
    const auto t0 = std::chrono::steady_clock::now();
    segment::RoundReport r = seg_->click(c, progress);
    if (r.duplicate) {  // a double click or a request sent twice: nothing changed, no history entry
      log_.note(std::string("the same ") + (c.click.label ? "positive" : "negative") +
                " click again: nothing changed (" + std::to_string(r.selected) + " Gaussians selected)");
      return;
    }
    const std::string what = std::string(c.click.label ? "positive" : "negative") + " click in " +
                             (c.free_camera ? std::string("the free camera")
                                            : "camera " + std::to_string(c.camera_index));
    // An edit landed while this click was segmented: its selection refers to the old
    // scene. Say so (the page shows the job's error) rather than drop it silently.
    if (!publish(true, what)) conflict("the scene was edited while this click was being segmented: click again");
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    char line[256];
    std::snprintf(line, sizeof line, "%s click: %zu Gaussians selected; %d views segmented, %d accepted, %d dropped (%.1f s)",
                  c.click.label ? "positive" : "negative", r.selected, r.views_segmented, r.accepted, r.dropped, ms / 1000);
    log_.note(line);
  });
}

uint64_t SegmentationJobs::granularity(int step) {
  if (step != 1 && step != -1) invalid("step: must be 1 (larger) or -1 (smaller)");
  const std::string what = step > 0 ? "larger mask at the last click" : "smaller mask at the last click";
  return submit(step > 0 ? "larger mask" : "smaller mask", [this, step, what](const Progress& progress) {
    ensure_current(progress);
    const auto t0 = std::chrono::steady_clock::now();
    segment::RoundReport r = seg_->step_granularity(step, progress);
    if (!publish(true, what)) conflict("the scene was edited while this mask was being segmented: try again");
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    char line[256];
    std::snprintf(line, sizeof line, "%s: %zu Gaussians selected; %d views accepted, %d dropped (%.1f s)", what.c_str(),
                  r.selected, r.accepted, r.dropped, ms / 1000);
    log_.note(line);
  });
}

uint64_t SegmentationJobs::follow(bool undo, uint64_t fingerprint) {
  try {
    return jobs_.submit(undo ? "undo click" : "redo click", [this, undo, fingerprint](const JobRunner::Report& report) {
      std::lock_guard<std::mutex> seg_lock(seg_mu_);
      if (!seg_ || !seg_->is_open()) return;
      // The click was made on the segmentation of `fingerprint`: make it current (it is
      // kept when later edits re-opened the segmentation), walk its click log, then show
      // the segmentation of the scene as it now is.
      if (seg_->fingerprint() != fingerprint && !seg_->restore(fingerprint)) return;
      try {
        if (undo && seg_->can_undo()) seg_->undo();
        else if (!undo && seg_->can_redo()) seg_->redo(report);
      } catch (const AppError& e) {
        log_.note(std::string(undo ? "undo" : "redo") + " click: the segmentation's clicks are out of step (" +
                      e.what() + ")",
                  "warn");
      }
      const uint64_t now = scene_.fingerprint();
      if (seg_->fingerprint() != now) seg_->restore(now);
      publish(false);
      log_.note(std::string(undo ? "undid" : "redid") + " a click: " + std::to_string(seg_->clicks().size()) +
                " click(s) in the segmentation");
    });
  } catch (const AppError&) {
    return 0;  // queue full or stopping: the selection is restored; the evidence lags
  }
}

uint64_t SegmentationJobs::set_settings(const SettingsRequest& request) {
  SegmentSettings s;
  {
    std::lock_guard<std::mutex> lock(status_mu_);
    s = published_.settings;
  }
  if (request.tau) s.tau = *request.tau;
  if (request.views) s.views_spec = *request.views;
  if (request.mode) s.mode = *request.mode;
  if (request.inspection) s.inspection = *request.inspection;
  if (!(s.tau >= 0 && s.tau < 1)) invalid("tau: must be in [0, 1)");
  if (s.views_spec.empty()) invalid("views: empty");
  try {
    segment::sample_views(bundle_.cameras, s.views_spec);
  } catch (const Error& e) {
    invalid(std::string("views: ") + e.what());
  }
  return submit("apply settings", [this, s](const Progress& progress) {
    ensure_current(progress);
    set_state("preparing", "applying settings: rebuilding views and replaying clicks");
    seg_->reconfigure(s, progress);
    set_state("ready", kReady);
    publish(seg_->can_undo(), "selection under new settings", StepKind::kSelect);
    char line[200];
    std::snprintf(line, sizeof line, "settings: tau %.2f, views %s (%zu), %s propagation, inspection %s", s.tau,
                  s.views_spec.c_str(), seg_->view_count(), segment::mode_name(s.mode), s.inspection ? "on" : "off");
    log_.note(line);
  });
}

void SegmentationJobs::scene_changed() {
  const uint64_t fp = scene_.fingerprint();
  bool restore = false;
  {
    std::lock_guard<std::mutex> lock(status_mu_);
    if (published_.state != "ready" || fp == seg_fingerprint_) return;
    restore = std::find(kept_.begin(), kept_.end(), fp) != kept_.end();
  }
  try {
    if (restore) {
      jobs_.submit("restore segmentation", [this](const JobRunner::Report&) {
        std::lock_guard<std::mutex> seg_lock(seg_mu_);
        const uint64_t now = scene_.fingerprint();
        if (!seg_ || seg_->fingerprint() == now || !seg_->restore(now)) return;
        publish(false);
        log_.note("the scene is back to an earlier state: its " + std::to_string(seg_->clicks().size()) +
                  " click(s) are current again");
      });
      return;
    }
    // A new scene: build its views now, in the background, so that the first click on
    // it does not wait for them; views the edit does not reach are kept as they are.
    // The evidence stays that of the scene before the edit until that click.
    jobs_.submit("update views after the edit", [this](const JobRunner::Report& report) {
      std::lock_guard<std::mutex> seg_lock(seg_mu_);
      const uint64_t now = scene_.fingerprint();
      if (!seg_ || !seg_->is_open() || seg_->fingerprint() == now || seg_->prepared_for(now)) return;
      for (uint64_t k : seg_->kept())
        if (k == now) return;  // restored instead, on the next click
      const auto t0 = std::chrono::steady_clock::now();
      // Left for another scene (undo, another edit) meanwhile: stop after this view.
      struct Left {};
      uint64_t copied = 0;
      std::shared_ptr<const SceneBundle> snap = snapshot(copied);
      if (copied != now) return;  // edited again meanwhile: that edit's own job prepares its views
      try {
        seg_->prepare(snap, copied, [&](int done, int total, const std::string& line) {
          report(done, total, line);
          if (scene_.fingerprint() != now) throw Left{};
        });
      } catch (const Left&) {
        log_.note("stopped preparing the views of an edited scene: the scene changed again");
        return;
      }
      char line[200];
      std::snprintf(line, sizeof line, "views of the edited scene: %d kept (the edit does not reach them), %d re-rendered (%.1f s)",
                    seg_->last_reused(), seg_->last_rebuilt(),
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      log_.note(line);
    });
  } catch (const AppError&) {
    // Queue full or stopping: the next click rebuilds the views instead.
  }
}

SegmentationStatus SegmentationJobs::status(uint64_t edit_fingerprint) const {
  std::lock_guard<std::mutex> lock(status_mu_);
  SegmentationStatus s = published_;
  s.stale = s.state == "ready" && seg_fingerprint_ != edit_fingerprint;
  if (s.stale) {
    s.message = "the scene was edited: the next click segments the edited scene";
    s.can_undo = s.can_redo = false;
  }
  return s;
}

std::vector<uint8_t> SegmentationJobs::thumbnail(int index) const {
  std::lock_guard<std::mutex> lock(status_mu_);
  if (index < 0 || index >= int(thumbs_.size()))
    throw AppError(ErrorKind::kNotFound,
                   "no thumbnail " + std::to_string(index) + " (there are " + std::to_string(thumbs_.size()) + ")");
  return thumbs_[size_t(index)];
}

}  // namespace isegman::server
