#include "server/app_state.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>

#include "core/error.h"
#include "core/selection.h"
#include "edit/combine.h"
#include "edit/remove.h"
#include "edit/selection_tools.h"
#include "io/gaussian_file.h"
#include "edit/transform.h"
#include "io/image_io.h"
#include "io/ply.h"
#include "io/scene_loader.h"
#include "models/sam.h"
#include "render/rasterizer.h"
#include "server/http_error.h"
#include "server/output_paths.h"
#include "server/validation.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace isegman::server {

namespace {

constexpr int kThumbSide = 240;
constexpr size_t kLogKept = 60;
constexpr double kCoordLimit = 1e7;

json vec_json(const Vec3& v) { return json::array({v.x, v.y, v.z}); }

std::string scene_name(const SceneBundle& b) {
  fs::path p(b.ply_path);
  // .../<scene>/point_cloud/iteration_N/point_cloud.ply -> <scene>
  if (p.filename() == "point_cloud.ply" && p.parent_path().parent_path().filename() == "point_cloud")
    return p.parent_path().parent_path().parent_path().filename().string();
  return p.stem().string();
}

// Tints the selection's coverage magenta (it stands out on any object colour) and draws
// its outline.
void highlight(Image& color, const Image& coverage) {
  const float orange[3] = {1.f, 0.2f, 0.8f};
  const int w = color.width, h = color.height;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float c = std::clamp(coverage.at(x, y), 0.f, 1.f);
      if (c <= 0.f) continue;
      const float a = 0.5f * c;
      for (int k = 0; k < 3; ++k) color.at(x, y, k) = color.at(x, y, k) * (1 - a) + orange[k] * a;
    }
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      const bool in = coverage.at(x, y) > 0.5f;
      if (!in) continue;
      if (coverage.at(x - 1, y) <= 0.5f || coverage.at(x + 1, y) <= 0.5f || coverage.at(x, y - 1) <= 0.5f ||
          coverage.at(x, y + 1) <= 0.5f)
        for (int k = 0; k < 3; ++k) color.at(x, y, k) = orange[k];
    }
}

edit::Similarity similarity_from(const json& body) {
  edit::Similarity t;
  t.translation = json_vec3(body, "translate", kCoordLimit, Vec3{0, 0, 0});
  const Vec3 r = json_vec3(body, "rotate", 3600, Vec3{0, 0, 0});
  t.rotation = edit::rotation_from_euler_deg(r.x, r.y, r.z);
  t.scale = json_number(body, "scale", 0.01, 100, 1.0);
  return t;
}

Selection combine_selection(const Selection& current, const Selection& shape, const std::string& mode) {
  if (mode == "replace") return shape;
  if (mode == "add") return edit::unite(current, shape);
  if (mode == "subtract") return edit::subtract(current, shape);
  if (mode == "intersect") return edit::intersect(current, shape);
  bad_request("mode: expected replace, add, subtract or intersect, got '" + mode + "'");
}

const char* mode_text(segment::PropagationMode m) { return segment::mode_name(m); }

}  // namespace

AppState::AppState(SceneBundle bundle, AppOptions options)
    : bundle_([&] {
        SceneBundle b = bundle;
        b.gaussians = GaussianScene();
        return b;
      }()),
      options_(std::move(options)),
      edit_(std::move(bundle.gaussians)) {
  if (edit_.scene().size() == 0) throw Error(bundle_.ply_path, "the scene has no Gaussians");
  edit_fingerprint_ = edit_.scene().fingerprint();
  seg_settings_ = options_.settings;
  if (!options_.segmentation) {
    seg_state_ = "off";
    seg_message_ = "segmentation is disabled (--no-segmentation); selection tools and edits work";
  }
}

AppState::~AppState() { stop(); }

void AppState::stop() { jobs_.stop(); }

void AppState::start() {
  if (!options_.segmentation) return;
  jobs_.submit("prepare segmentation", [this](const JobRunner::Report& report) { prepare_job(report); });
}

void AppState::note(const std::string& text, const std::string& level) {
  std::lock_guard<std::mutex> lock(status_mu_);
  log_.push_front({{"seq", ++log_seq_}, {"time", double(std::time(nullptr))}, {"level", level}, {"text", text}});
  if (log_.size() > kLogKept) log_.pop_back();
  ++version_;
}

std::shared_ptr<const SceneBundle> AppState::snapshot() const {
  auto b = std::make_shared<SceneBundle>(bundle_);
  std::shared_lock<std::shared_mutex> lock(edit_mu_);
  b->gaussians = edit_.scene();
  return b;
}

void AppState::prepare_job(const JobRunner::Report& report) {
  std::lock_guard<std::mutex> seg_lock(seg_mu_);
  auto set_state = [&](const std::string& state, const std::string& message) {
    std::lock_guard<std::mutex> lock(status_mu_);
    seg_state_ = state;
    seg_message_ = message;
    ++version_;
  };
  try {
    const std::string dir = options_.sam_dir.empty() ? models::default_sam_dir() : options_.sam_dir;
    const fs::path enc = fs::path(dir) / "encoder.onnx", dec = fs::path(dir) / "sam.onnx";
    if (!fs::exists(enc) || !fs::exists(dec)) {
      set_state("off", "SAM model files missing in " + dir +
                           " (run scripts/setup.sh or pass --sam DIR); selection tools and edits still work");
      note("segmentation unavailable: SAM model files missing in " + dir, "warn");
      return;
    }
    set_state("preparing", "loading SAM");
    report(0, 0, "loading SAM from " + dir);
    if (!options_.views.cache_dir.empty()) {
      std::error_code ec;
      fs::create_directories(options_.views.cache_dir, ec);
    }
    sam_ = std::make_shared<const models::SamModel>(enc.string(), dec.string(), options_.threads);
    seg_ = std::make_unique<Segmentation>(sam_, options_.session, options_.views, options_.settings);
    std::shared_ptr<const SceneBundle> snap = snapshot();
    const uint64_t fp = snap->gaussians.fingerprint();
    set_state("preparing", "rendering views and computing SAM embeddings");
    seg_->open(snap, fp, [&](int done, int total, const std::string& line) {
      report(done, total, line);
      std::lock_guard<std::mutex> lock(status_mu_);
      seg_message_ = "preparing views: " + line;
      ++version_;
    });
    set_state("ready", "click an object: left = add, right or shift = remove");
    publish_segmentation(false);
    note("segmentation ready: " + std::to_string(seg_->view_count()) + " views");
  } catch (const std::exception& e) {
    set_state("error", std::string("segmentation could not start: ") + e.what());
    note(std::string("segmentation could not start: ") + e.what(), "error");
    throw;
  }
}

void AppState::ensure_current(const Progress& progress) {
  if (!seg_ || !seg_->is_open()) throw HttpError(409, "segmentation is not ready");
  uint64_t current;
  {
    std::shared_lock<std::shared_mutex> lock(edit_mu_);
    current = edit_fingerprint_;
  }
  if (seg_->fingerprint() == current) return;
  note("the scene was edited: segmenting the edited scene (views re-rendered, clicks start over)");
  {
    std::lock_guard<std::mutex> lock(status_mu_);
    seg_state_ = "preparing";
    seg_message_ = "re-rendering the views of the edited scene";
    ++version_;
  }
  std::shared_ptr<const SceneBundle> snap = snapshot();
  seg_->open(snap, snap->gaussians.fingerprint(), progress);
  std::lock_guard<std::mutex> lock(status_mu_);
  seg_state_ = "ready";
  seg_message_ = "click an object: left = add, right or shift = remove";
}

void AppState::publish_segmentation(bool apply_selection) {
  if (!seg_) return;
  if (apply_selection && seg_->is_open()) {
    std::unique_lock<std::shared_mutex> lock(edit_mu_);
    if (edit_fingerprint_ == seg_->fingerprint()) {
      edit_.select(Selection::from_mask(edit_.scene(), seg_->selection()),
                   "click selection (" + std::to_string(seg_->selected_count()) + " Gaussians)");
      ++edit_revision_;
    } else {
      lock.unlock();
      note("the scene changed while segmenting; the click's selection was not applied", "warn");
    }
  }
  std::vector<std::vector<uint8_t>> thumbs = seg_->thumbnails(kThumbSide);
  json views = seg_->views_json();
  std::lock_guard<std::mutex> lock(status_mu_);
  thumbs_ = std::move(thumbs);
  seg_views_ = std::move(views);
  seg_fingerprint_ = seg_->fingerprint();
  seg_clicks_ = seg_->clicks().size();
  seg_selected_ = seg_->selected_count();
  seg_can_undo_ = seg_->can_undo();
  seg_can_redo_ = seg_->can_redo();
  seg_settings_ = seg_->settings();
  ++thumb_version_;
  ++version_;
}

std::string AppState::require_segmentation() const {
  std::lock_guard<std::mutex> lock(status_mu_);
  if (seg_state_ == "off" || seg_state_ == "error") throw HttpError(409, "segmentation unavailable: " + seg_message_);
  return seg_state_;
}

uint64_t AppState::submit_segmentation_job(const std::string& name, std::function<void(const Progress&)> work) {
  require_segmentation();
  return jobs_.submit(name, [this, work, name](const JobRunner::Report& report) {
    std::lock_guard<std::mutex> seg_lock(seg_mu_);
    try {
      work(report);
    } catch (const std::exception& e) {
      note(name + " failed: " + e.what(), "error");
      // Whatever happened, show the segmentation as it now is.
      if (seg_ && seg_->is_open()) publish_segmentation(false);
      {
        std::lock_guard<std::mutex> lock(status_mu_);
        if (seg_state_ == "preparing") seg_state_ = seg_ && seg_->is_open() ? "ready" : "error";
      }
      throw;
    }
  });
}

uint64_t AppState::click(const ClickRecord& c) {
  if (c.camera_index >= int(bundle_.cameras.size()) || (c.camera_index < 0 && !c.free_camera))
    bad_request("view: no camera " + std::to_string(c.camera_index));
  if (!(c.x >= 0 && c.x <= 1 && c.y >= 0 && c.y <= 1)) bad_request("x, y: must be in [0, 1]");
  if (c.label != 0 && c.label != 1) bad_request("label: must be 1 (positive) or 0 (negative)");
  return submit_segmentation_job("click", [this, c](const Progress& progress) {
    ensure_current(progress);
    const auto t0 = std::chrono::steady_clock::now();
    segment::RoundReport r = seg_->click(c, progress);
    publish_segmentation(true);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    char line[256];
    std::snprintf(line, sizeof line, "%s click: %zu Gaussians selected; %d views segmented, %d accepted, %d dropped (%.1f s)",
                  c.label ? "positive" : "negative", r.selected, r.views_segmented, r.accepted, r.dropped, ms / 1000);
    note(line);
  });
}

uint64_t AppState::undo_click() {
  uint64_t edit_fp;
  {
    std::shared_lock<std::shared_mutex> lock(edit_mu_);
    edit_fp = edit_fingerprint_;
  }
  {
    std::lock_guard<std::mutex> lock(status_mu_);
    if (!seg_can_undo_) throw HttpError(409, "no click to undo");
    if (seg_fingerprint_ != edit_fp)
      throw HttpError(409, "the scene was edited after these clicks; undo the edit or click again");
  }
  return submit_segmentation_job("undo click", [this](const Progress&) {
    {
      std::shared_lock<std::shared_mutex> lock(edit_mu_);
      if (!seg_ || seg_->fingerprint() != edit_fingerprint_)
        throw HttpError(409, "the scene was edited after these clicks; undo the edit or click again");
    }
    seg_->undo();
    publish_segmentation(true);
    note("undid a click: " + std::to_string(seg_->selected_count()) + " Gaussians selected");
  });
}

uint64_t AppState::redo_click() {
  uint64_t edit_fp;
  {
    std::shared_lock<std::shared_mutex> lock(edit_mu_);
    edit_fp = edit_fingerprint_;
  }
  {
    std::lock_guard<std::mutex> lock(status_mu_);
    if (!seg_can_redo_) throw HttpError(409, "no click to redo");
    if (seg_fingerprint_ != edit_fp)
      throw HttpError(409, "the scene was edited after these clicks; undo the edit or click again");
  }
  return submit_segmentation_job("redo click", [this](const Progress& progress) {
    {
      std::shared_lock<std::shared_mutex> lock(edit_mu_);
      if (!seg_ || seg_->fingerprint() != edit_fingerprint_)
        throw HttpError(409, "the scene was edited after these clicks; undo the edit or click again");
    }
    seg_->redo(progress);
    publish_segmentation(true);
    note("redid a click: " + std::to_string(seg_->selected_count()) + " Gaussians selected");
  });
}

uint64_t AppState::set_settings(const SegmentSettings& s) {
  if (!(s.tau >= 0 && s.tau < 1)) bad_request("tau: must be in [0, 1)");
  try {
    segment::sample_views(bundle_.cameras, s.views_spec);
  } catch (const Error& e) {
    bad_request(std::string("views: ") + e.what());
  }
  return submit_segmentation_job("apply settings", [this, s](const Progress& progress) {
    ensure_current(progress);
    {
      std::lock_guard<std::mutex> lock(status_mu_);
      seg_state_ = "preparing";
      seg_message_ = "applying settings: rebuilding views and replaying clicks";
      ++version_;
    }
    seg_->reconfigure(s, progress);
    {
      std::lock_guard<std::mutex> lock(status_mu_);
      seg_state_ = "ready";
      seg_message_ = "click an object: left = add, right or shift = remove";
    }
    publish_segmentation(seg_->can_undo());
    char line[200];
    std::snprintf(line, sizeof line, "settings: tau %.2f, views %s (%zu), %s propagation, inspection %s", s.tau,
                  s.views_spec.c_str(), seg_->view_count(), mode_text(s.mode), s.inspection ? "on" : "off");
    note(line);
  });
}

json AppState::scene_info() const {
  json cams = json::array();
  Vec3 up_sum{0, 0, 0};
  for (size_t i = 0; i < bundle_.cameras.size(); ++i) {
    const Camera& c = bundle_.cameras[i];
    const Vec3 forward = c.R.row(2), up = -c.R.row(1);
    up_sum += up;
    cams.push_back({{"index", i},
                    {"id", c.id},
                    {"name", c.name},
                    {"width", c.width},
                    {"height", c.height},
                    {"fov", 2 * std::atan(0.5 * c.width / c.fx) * 180 / M_PI},
                    {"center", vec_json(c.center())},
                    {"forward", vec_json(forward)},
                    {"up", vec_json(up)}});
  }
  std::shared_lock<std::shared_mutex> lock(edit_mu_);
  const GaussianScene& g = edit_.scene();
  Vec3 lo, hi;
  g.bounds(lo, hi);
  const double n = std::sqrt(up_sum.x * up_sum.x + up_sum.y * up_sum.y + up_sum.z * up_sum.z);
  return {{"name", scene_name(bundle_)},
          {"ply", bundle_.ply_path},
          {"gaussians", g.size()},
          {"sh_degree", g.sh_degree},
          {"bounds", {{"lo", vec_json(lo)}, {"hi", vec_json(hi)}}},
          {"up", n > 1e-9 ? vec_json(up_sum / n) : vec_json({0, 0, 1})},
          {"cameras", cams},
          {"preview_side", options_.preview_side},
          {"out_dir", fs::absolute(options_.out_dir).lexically_normal().string()},
          {"background", json::array({options_.background[0], options_.background[1], options_.background[2]})}};
}

json AppState::status() const {
  const JobStatus job = jobs_.current();
  json j;
  j["job"] = {{"id", job.id},          {"name", job.name},   {"state", job.state},     {"done", job.done},
              {"total", job.total},    {"message", job.message}, {"error", job.error}, {"seconds", job.seconds}};
  j["busy"] = jobs_.busy();
  j["queued"] = jobs_.queued();
  uint64_t edit_fp;
  {
    std::shared_lock<std::shared_mutex> lock(edit_mu_);
    const auto& mask = edit_.mask();
    edit_fp = edit_fingerprint_;
    j["edit"] = {{"gaussians", edit_.scene().size()},
                 {"selected", size_t(std::count(mask.begin(), mask.end(), true))},
                 {"can_undo", edit_.history().can_undo()},
                 {"can_redo", edit_.history().can_redo()},
                 {"undo_steps", edit_.history().undo_steps()},
                 {"redo_steps", edit_.history().redo_steps()},
                 {"notice", edit_.notice()},
                 {"revision", edit_revision_.load()}};
  }
  std::lock_guard<std::mutex> lock(status_mu_);
  const bool stale = seg_state_ == "ready" && seg_fingerprint_ != edit_fp;
  j["segmentation"] = {{"state", seg_state_},
                       {"message", stale ? "the scene was edited: the next click segments the edited scene"
                                         : seg_message_},
                       {"stale", stale},
                       {"clicks", seg_clicks_},
                       {"selected", seg_selected_},
                       {"can_undo", seg_can_undo_ && !stale},
                       {"can_redo", seg_can_redo_ && !stale},
                       {"views", seg_views_},
                       {"thumb_version", thumb_version_},
                       {"settings",
                        {{"tau", seg_settings_.tau},
                         {"views", seg_settings_.views_spec},
                         {"mode", mode_text(seg_settings_.mode)},
                         {"inspection", seg_settings_.inspection}}}};
  j["log"] = json::array();
  for (const json& e : log_) j["log"].push_back(e);
  j["version"] = version_.load();
  return j;
}

std::vector<uint8_t> AppState::thumbnail(int index) const {
  std::lock_guard<std::mutex> lock(status_mu_);
  if (index < 0 || index >= int(thumbs_.size()))
    throw HttpError(404, "no thumbnail " + std::to_string(index) + " (there are " + std::to_string(thumbs_.size()) + ")");
  return thumbs_[size_t(index)];
}

std::vector<uint8_t> AppState::render(const RenderRequest& r) const {
  Camera cam;
  if (r.free) {
    cam = make_free_camera(*r.free);
  } else {
    if (r.camera_index < 0 || r.camera_index >= int(bundle_.cameras.size()))
      bad_request("view: no camera " + std::to_string(r.camera_index) + " (there are " +
                  std::to_string(bundle_.cameras.size()) + ")");
    cam = bundle_.cameras[size_t(r.camera_index)];
  }
  if (r.max_side > 0 && std::max(cam.width, cam.height) != r.max_side) {
    const double s = double(r.max_side) / std::max(cam.width, cam.height);
    cam = cam.resized(std::max(1, int(std::lround(cam.width * s))), std::max(1, int(std::lround(cam.height * s))));
  }
  if (size_t(cam.width) * cam.height > size_t(4096) * 4096) bad_request("size: the render would be too large");
  RenderSettings rs;
  rs.threads = options_.threads;
  rs.depth = false;
  for (int k = 0; k < 3; ++k) rs.background[k] = options_.background[k];
  if (r.background) {
    rs.background[0] = float(r.background->r);
    rs.background[1] = float(r.background->g);
    rs.background[2] = float(r.background->b);
  }
  RenderOutput out;
  {
    std::shared_lock<std::shared_mutex> lock(edit_mu_);
    const auto& mask = edit_.mask();
    std::vector<float> values;
    if (r.highlight && std::find(mask.begin(), mask.end(), true) != mask.end()) {
      values.resize(mask.size());
      for (size_t i = 0; i < mask.size(); ++i) values[i] = mask[i] ? 1.f : 0.f;
    }
    out = isegman::render(edit_.scene(), cam, rs, values.empty() ? nullptr : &values);
  }
  if (!out.value.empty()) highlight(out.color, out.value);
  return r.png ? encode_png(out.color) : encode_jpeg(out.color, 88);
}

json AppState::edit_result(const std::string& label, const std::vector<std::string>& notes) const {
  const auto& mask = edit_.mask();
  return {{"label", label},
          {"notes", notes},
          {"notice", edit_.notice()},
          {"gaussians", edit_.scene().size()},
          {"selected", size_t(std::count(mask.begin(), mask.end(), true))}};
}

void AppState::after_scene_change() {
  edit_fingerprint_ = edit_.scene().fingerprint();
  ++edit_revision_;
  ++version_;
}

json AppState::select(const std::string& tool, const json& body) {
  const std::string mode = json_string(body, "mode", 16, std::string("replace"));
  json result;
  std::string label;
  {
    std::unique_lock<std::shared_mutex> lock(edit_mu_);
    const GaussianScene& scene = edit_.scene();
    const Selection current = edit_.selection();
    Selection next;
    if (tool == "box") {
      const Vec3 lo = json_vec3(body, "lo", kCoordLimit), hi = json_vec3(body, "hi", kCoordLimit);
      if (lo.x > hi.x || lo.y > hi.y || lo.z > hi.z) bad_request("box: lo must not exceed hi on any axis");
      next = combine_selection(current, edit::select_box(scene, lo, hi), mode);
      label = "box selection (" + mode + ")";
    } else if (tool == "sphere") {
      const Vec3 c = json_vec3(body, "center", kCoordLimit);
      const double radius = json_number(body, "radius", 0, kCoordLimit);
      if (!(radius > 0)) bad_request("radius: must be > 0");
      next = combine_selection(current, edit::select_sphere(scene, c, radius), mode);
      label = "sphere selection (" + mode + ")";
    } else if (tool == "invert") {
      next = edit::invert(current);
      label = "invert selection";
    } else if (tool == "clear") {
      next = Selection::none_of(scene);
      label = "clear selection";
    } else if (tool == "all") {
      next = Selection::all_of(scene);
      label = "select all";
    } else {
      throw HttpError(404, "no selection tool '" + tool + "' (box, sphere, invert, clear, all)");
    }
    label += ": " + std::to_string(next.count()) + " Gaussians";
    edit_.select(next, label);
    ++edit_revision_;
    ++version_;
    result = edit_result(label, {});
  }
  note(label);
  return result;
}

json AppState::selection_bounds() const {
  std::shared_lock<std::shared_mutex> lock(edit_mu_);
  const GaussianScene& g = edit_.scene();
  const auto& mask = edit_.mask();
  const bool any = std::find(mask.begin(), mask.end(), true) != mask.end();
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300}, sum{0, 0, 0};
  size_t n = 0;
  for (size_t i = 0; i < g.size(); ++i) {
    if (any && !mask[i]) continue;
    const Vec3 p = g.position(i);
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
    sum += p;
    ++n;
  }
  const Vec3 c = sum / double(std::max<size_t>(n, 1));
  double r = 0;
  for (size_t i = 0; i < g.size(); ++i) {
    if (any && !mask[i]) continue;
    const Vec3 d = g.position(i) - c;
    r = std::max(r, std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z));
  }
  return {{"of", any ? "selection" : "scene"}, {"count", n},        {"lo", vec_json(lo)},
          {"hi", vec_json(hi)},                {"center", vec_json(c)}, {"radius", r}};
}

json AppState::edit(const std::string& op, const json& body) {
  static const char* kOps[] = {"remove", "colorize", "scale", "copy", "move", "combine"};
  if (std::find_if(std::begin(kOps), std::end(kOps), [&](const char* o) { return op == o; }) == std::end(kOps))
    throw HttpError(404, "no edit '" + op + "' (remove, colorize, scale, copy, move, combine)");
  // Parse and load everything before taking the scene lock.
  edit::Rgb color;
  edit::ColorizeMode color_mode = edit::ColorizeMode::kReplace;
  double factor = 1;
  edit::Similarity t;
  GaussianScene source;
  if (op == "colorize") {
    color = parse_rgb(json_string(body, "color", 64), "color");
    const std::string m = json_string(body, "mode", 16, std::string("replace"));
    if (m != "replace" && m != "balanced") bad_request("mode: expected replace or balanced");
    color_mode = edit::parse_colorize_mode(m);
  } else if (op == "scale") {
    factor = json_number(body, "factor", 0.01, 100);
  } else if (op == "copy" || op == "move" || op == "combine") {
    t = similarity_from(body);
  }
  if (op == "combine") {
    const std::string path = json_string(body, "path", 4096);
    if (path.empty()) bad_request("path: empty");
    std::error_code ec;
    if (!fs::exists(path, ec)) bad_request("path: " + path + ": no such file or directory");
    try {
      if (fs::is_directory(path, ec)) {
        SceneLoadOptions lo;
        lo.require_cameras = false;
        source = load_scene(path, lo).gaussians;
      } else {
        source = edit::read_scene_file(path);
      }
    } catch (const std::exception& e) {
      bad_request(std::string("path: ") + e.what());
    }
  }
  json result;
  std::string label;
  {
    std::unique_lock<std::shared_mutex> lock(edit_mu_);
    const GaussianScene& scene = edit_.scene();
    const Selection sel = edit_.selection();
    if (op != "combine" && sel.empty())
      throw HttpError(409, "nothing is selected: click an object or use a selection tool first");
    edit::Delta d;
    try {
      if (op == "remove") d = edit::plan_remove(scene, sel);
      else if (op == "colorize") d = edit::plan_colorize(scene, sel, color, color_mode);
      else if (op == "scale") d = edit::plan_scale(scene, sel, factor);
      else if (op == "copy") d = edit::plan_copy(scene, sel, t);
      else if (op == "move") d = edit::plan_transform(scene, sel, t);
      else d = edit::plan_combine(scene, edit_.mask(), source, Selection::all_of(source), t);
    } catch (const HttpError&) {
      throw;
    } catch (const Error& e) {
      bad_request(e.what());
    }
    label = d.label.empty() ? op : d.label;
    const std::vector<std::string> notes = d.notes;
    edit_.apply(std::move(d));
    after_scene_change();
    result = edit_result(label, notes);
  }
  note(label);
  return result;
}

json AppState::undo_edit() {
  json result;
  std::string label;
  {
    std::unique_lock<std::shared_mutex> lock(edit_mu_);
    if (!edit_.history().can_undo()) throw HttpError(409, "no edit to undo");
    label = edit_.undo();
    after_scene_change();
    result = edit_result(label, {});
  }
  note("undo: " + label);
  return result;
}

json AppState::redo_edit() {
  json result;
  std::string label;
  {
    std::unique_lock<std::shared_mutex> lock(edit_mu_);
    if (!edit_.history().can_redo()) throw HttpError(409, "no edit to redo");
    label = edit_.redo();
    after_scene_change();
    result = edit_result(label, {});
  }
  note("redo: " + label);
  return result;
}

std::vector<uint8_t> AppState::export_bytes(edit::SceneFormat format) const {
  std::shared_lock<std::shared_mutex> lock(edit_mu_);
  try {
    return serialize_gaussians(edit_.scene(), format);
  } catch (const Error& e) {
    throw HttpError(409, e.what());
  }
}

json AppState::export_to(const std::string& relative_path) {
  const std::string path = resolve_output_path(options_.out_dir, relative_path, {".ply", ".splat", ".spz"});
  std::vector<std::string> notes;
  size_t count;
  try {
    std::shared_lock<std::shared_mutex> lock(edit_mu_);
    edit::write_scene_file(path, edit_.scene(), {bundle_.ply_path, bundle_.cameras_path}, &notes);
    count = edit_.scene().size();
  } catch (const Error& e) {
    bad_request(e.what());
  }
  note("exported " + std::to_string(count) + " Gaussians to " + path);
  return {{"path", path}, {"gaussians", count}, {"notes", notes}};
}

}  // namespace isegman::server
