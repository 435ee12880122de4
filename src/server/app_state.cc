#include "server/app_state.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "io/image_io.h"
#include "io/scene_loader.h"
#include "server/app_error.h"
#include "server/input_paths.h"
#include "server/output_paths.h"
#include "server/scene_binary.h"
#include "server/scene_name.h"

namespace fs = std::filesystem;

namespace isegman::server {

namespace {

SegmentationOptions segmentation_options(const AppOptions& o) {
  SegmentationOptions s;
  s.enabled = o.segmentation;
  s.sam_dir = o.sam_dir;
  s.session = o.session;
  s.views = o.views;
  s.settings = o.settings;
  s.threads = o.threads;
  s.kept_bytes = o.kept_segmentation_bytes;
  return s;
}

SceneBundle without_gaussians(const SceneBundle& bundle) {
  SceneBundle b;
  b.cameras = bundle.cameras;
  b.ply_path = bundle.ply_path;
  b.cameras_path = bundle.cameras_path;
  b.images_dir = bundle.images_dir;
  return b;
}

GaussianScene checked(GaussianScene scene, const std::string& path) {
  if (scene.size() == 0) throw Error(path, "the scene has no Gaussians");
  return scene;
}

}  // namespace

AppState::AppState(SceneBundle bundle, AppOptions options)
    : bundle_(without_gaussians(bundle)),
      options_(std::move(options)),
      data_dir_(options_.data_dir.empty() ? default_data_dir(bundle_) : options_.data_dir),
      scene_(checked(std::move(bundle.gaussians), bundle_.ply_path)),
      files_(data_dir_, options_.max_upload_bytes),
      segmentation_(bundle_, segmentation_options(options_), scene_, jobs_, log_) {}

AppState::~AppState() { stop(); }

void AppState::stop() {
  segmentation_.stop_building_ahead();
  jobs_.stop();
}

void AppState::start() { segmentation_.start(); }

SceneInfo AppState::scene_info() const {
  SceneInfo s;
  s.name = scene_name(bundle_.ply_path);
  s.ply = bundle_.ply_path;
  const EditStatus e = scene_.status();
  s.gaussians = e.gaussians;
  scene_.bounds(s.lo, s.hi, s.sh_degree);
  s.robust = scene_.robust_bounds();
  s.orbit_distance = s.robust.radius / std::tan(M_PI / 6) / 0.8;
  s.cameras = bundle_.cameras;
  s.preview_side = options_.preview_side;
  s.out_dir = fs::absolute(options_.out_dir).lexically_normal().string();
  s.data_dir = data_folder();
  for (int k = 0; k < 3; ++k) s.background[k] = options_.background[k];
  return s;
}

std::string AppState::data_folder() const {
  return data_dir_.empty() ? "" : fs::absolute(data_dir_).lexically_normal().string();
}

AppStatus AppState::status() const {
  AppStatus s;
  s.job = jobs_.current();
  s.busy = jobs_.busy();
  s.queued = jobs_.queued();
  s.edit = scene_.status();
  s.segmentation = segmentation_.status(s.edit.fingerprint);
  s.log = log_.entries();
  s.version = log_.version() + s.edit.revision;
  return s;
}

Camera AppState::camera_for(const RenderRequest& r) const {
  Camera cam;
  if (r.free) {
    cam = make_free_camera(*r.free);
  } else {
    if (r.camera_index < 0 || r.camera_index >= int(bundle_.cameras.size()))
      invalid("view: no camera " + std::to_string(r.camera_index) + " (there are " +
              std::to_string(bundle_.cameras.size()) + ")");
    cam = bundle_.cameras[size_t(r.camera_index)];
  }
  if (r.max_side > 0 && std::max(cam.width, cam.height) != r.max_side) {
    const double s = double(r.max_side) / std::max(cam.width, cam.height);
    cam = cam.resized(std::max(1, int(std::lround(cam.width * s))), std::max(1, int(std::lround(cam.height * s))));
  }
  if (size_t(cam.width) * cam.height > size_t(4096) * 4096) invalid("size: the render would be too large");
  return cam;
}

std::vector<uint8_t> AppState::render(const RenderRequest& r) const {
  const Camera cam = camera_for(r);
  RenderSettings rs;
  rs.threads = options_.threads;
  rs.depth = false;
  for (int k = 0; k < 3; ++k) rs.background[k] = options_.background[k];
  if (r.background) {
    rs.background[0] = float(r.background->r);
    rs.background[1] = float(r.background->g);
    rs.background[2] = float(r.background->b);
  }
  const std::vector<bool> hidden = display_.hidden(scene_.status().gaussians);
  const Image color = scene_.render(cam, rs, r.highlight ? r.tint : 0.f, &hidden);
  return r.png ? encode_png(color) : encode_jpeg(color, 88);
}

std::vector<uint8_t> AppState::splats() const {
  return scene_.read([](const GaussianScene& g, const std::vector<bool>&, uint64_t, uint64_t fingerprint) {
    return pack_splats(g, fingerprint);
  });
}

std::vector<uint8_t> AppState::selection_mask() const {
  return scene_.read([this](const GaussianScene& g, const std::vector<bool>& mask, uint64_t revision,
                            uint64_t fingerprint) {
    const std::vector<bool> hidden = display_.hidden(g.size());  // may forget flags: read it first
    return pack_selection(mask, hidden, fingerprint, revision + display_.revision());
  });
}

uint64_t AppState::click(ClickRecord click) {
  click.hidden = display_.hidden(scene_.status().gaussians);
  return segmentation_.click(click);
}

DisplayResult AppState::display(DisplayOp op) {
  DisplayResult r = scene_.read([this, op](const GaussianScene&, const std::vector<bool>& mask, uint64_t, uint64_t) {
    return display_.apply(op, mask);
  });
  log_.note(r.label);
  return r;
}

PickResult AppState::pick(const RenderRequest& view, double x, double y) const {
  RenderRequest full = view;
  full.max_side = 0;  // x, y are pixels of the full-size image
  const Camera cam = camera_for(full);
  RenderSettings rs;
  rs.threads = options_.threads;
  return scene_.read([&](const GaussianScene& g, const std::vector<bool>&, uint64_t, uint64_t) {
    std::vector<bool> hidden = display_.hidden(g.size());
    if (hidden.empty()) return pick_surface(g, cam, x, y, rs);
    for (size_t i = 0; i < hidden.size(); ++i) hidden[i] = !hidden[i];
    return pick_surface(g.subset(hidden), cam, x, y, rs);
  });
}

EditResult AppState::select(const SelectRequest& request) {
  edit::SelectOp op = request.op;
  if (request.free) {
    op.camera = make_free_camera(*request.free);
  } else if (request.camera_index >= 0) {
    if (request.camera_index >= int(bundle_.cameras.size()))
      invalid("view: no camera " + std::to_string(request.camera_index) + " (there are " +
              std::to_string(bundle_.cameras.size()) + ")");
    op.camera = bundle_.cameras[size_t(request.camera_index)];
  }
  op.screen.render.threads = options_.threads;
  EditResult r = scene_.select(op);
  log_.note(r.label);
  return r;
}

EditResult AppState::edit(const edit::EditOp& op, SceneSource source) {
  // Load the other scene of a combine before taking the scene lock; only from inside
  // the data folder or the uploads.
  GaussianScene other;
  if (op.kind == edit::EditKind::kCombine) {
    const std::string path = source == SceneSource::kUpload ? files_.upload_path(op.other_path)
                                                            : resolve_input_path(data_dir_, op.other_path);
    try {
      std::error_code ec;
      if (fs::is_directory(path, ec)) {
        SceneLoadOptions lo;
        lo.require_cameras = false;
        other = load_scene(path, lo).gaussians;
      } else {
        other = edit::read_scene_file(path);
      }
    } catch (const Error& e) {
      // The message names the file inside the data folder only.
      invalid(std::string("path: ") + e.what());
    }
  }
  EditResult r = scene_.edit(op, op.kind == edit::EditKind::kCombine ? &other : nullptr);
  log_.note(r.label);
  segmentation_.scene_changed();
  return r;
}

SceneFileEntry AppState::upload(const std::string& name, const std::string& bytes) {
  SceneFileEntry e = files_.upload(name, bytes);
  log_.note("uploaded " + e.name + ": " + std::to_string(e.gaussians) + " Gaussians (" + std::to_string(e.bytes) +
            " bytes)");
  return e;
}

EditResult AppState::undo(StepFilter filter) {
  EditResult r = scene_.undo(filter);
  log_.note("undo: " + r.label);
  if (r.kind == StepKind::kClick) r.job = segmentation_.follow_undo(r.fingerprint);
  else segmentation_.scene_changed();
  return r;
}

EditResult AppState::redo(StepFilter filter) {
  EditResult r = scene_.redo(filter);
  log_.note("redo: " + r.label);
  if (r.kind == StepKind::kClick) r.job = segmentation_.follow_redo(r.fingerprint);
  else segmentation_.scene_changed();
  return r;
}

ExportResult AppState::export_to(const std::string& relative_path) {
  ExportResult r;
  r.path = resolve_output_path(options_.out_dir, relative_path, {".ply", ".splat", ".spz", ".sog"});
  r.gaussians = scene_.write(r.path, {bundle_.ply_path, bundle_.cameras_path}, &r.notes);
  log_.note("exported " + std::to_string(r.gaussians) + " Gaussians to " + r.path);
  return r;
}

}  // namespace isegman::server
