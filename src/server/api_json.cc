#include "server/api_json.h"

#include <cmath>

#include "server/app_error.h"
#include "server/http_error.h"
#include "server/validation.h"

namespace isegman::server {

namespace {

constexpr double kCoordLimit = 1e7;

json vec_json(const Vec3& v) { return json::array({v.x, v.y, v.z}); }

edit::Similarity similarity_from(const json& body) {
  edit::Similarity t;
  t.translation = json_vec3(body, "translate", kCoordLimit, Vec3{0, 0, 0});
  const Vec3 r = json_vec3(body, "rotate", 3600, Vec3{0, 0, 0});
  t.rotation = edit::rotation_from_euler_deg(r.x, r.y, r.z);
  t.scale = json_number(body, "scale", 0.01, 100, 1.0);
  if (body.contains("pivot")) t.pivot = json_vec3(body, "pivot", kCoordLimit);
  return t;
}

}  // namespace

FreeCameraSpec free_camera_from_json(const json& j) {
  if (!j.is_object()) bad_request("camera: expected an object");
  FreeCameraSpec s;
  s.eye = json_vec3(j, "eye", kCoordLimit);
  s.target = json_vec3(j, "target", kCoordLimit);
  s.up = json_vec3(j, "up", kCoordLimit, Vec3{0, 0, 1});
  s.fov_x_deg = json_number(j, "fov", 5, 150, 60.0);
  s.width = json_integer(j, "width", 16, 4096, 640);
  s.height = json_integer(j, "height", 16, 4096, 480);
  return s;
}

ClickRecord click_from_json(const json& body) {
  json_only_keys(body, {"view", "camera", "x", "y", "label"});
  ClickRecord c;
  const bool has_view = body.contains("view") && !body["view"].is_null();
  const bool has_camera = body.contains("camera") && !body["camera"].is_null();
  if (has_view == has_camera) bad_request("give either 'view' (a camera index) or 'camera' (a free camera)");
  if (has_view) {
    c.camera_index = json_integer(body, "view", 0, 1 << 20);
  } else {
    c.free_camera = make_free_camera(free_camera_from_json(body["camera"]));
  }
  // Continuous pixel coordinates of the camera's image (core/click.h); the app checks
  // them against the camera's size.
  c.click.x = json_number(body, "x", 0, 1e5);
  c.click.y = json_number(body, "y", 0, 1e5);
  c.click.label = json_integer(body, "label", 0, 1, 1);
  return c;
}

SettingsRequest settings_from_json(const json& body) {
  json_only_keys(body, {"tau", "views", "mode", "inspection"});
  SettingsRequest s;
  if (body.contains("tau")) s.tau = json_number(body, "tau", 0, 0.999);
  if (body.contains("views")) {
    s.views = json_string(body, "views", 256);
    if (s.views->empty()) bad_request("views: empty");
  }
  if (body.contains("mode")) {
    const std::string mode = json_string(body, "mode", 16);
    if (mode != "hybrid" && mode != "epipolar" && mode != "depth") bad_request("mode: expected hybrid, epipolar or depth");
    s.mode = segment::parse_mode(mode);
  }
  if (body.contains("inspection")) s.inspection = json_bool(body, "inspection");
  return s;
}

namespace {

// {view: K} or {camera: {...}}: the camera a screen-space tool was drawn in.
void camera_ref_from(const json& body, SelectRequest& r) {
  const bool has_view = body.contains("view") && !body["view"].is_null();
  const bool has_camera = body.contains("camera") && !body["camera"].is_null();
  if (has_view == has_camera) bad_request("give either 'view' (a camera index) or 'camera' (a free camera)");
  if (has_view) r.camera_index = json_integer(body, "view", 0, 1 << 20);
  else r.free = free_camera_from_json(body["camera"]);
}

// [[x, y], ...] in pixels of the camera's full-size image.
std::vector<edit::Point2> points_from(const json& body) {
  if (!body.contains("points") || !body["points"].is_array()) bad_request("points: expected an array of [x, y]");
  const json& a = body["points"];
  if (a.size() > 100000) bad_request("points: more than 100000");
  std::vector<edit::Point2> out;
  out.reserve(a.size());
  for (const json& p : a) {
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
      bad_request("points: each point must be [x, y] numbers");
    const double x = p[0].get<double>(), y = p[1].get<double>();
    if (!(std::isfinite(x) && std::isfinite(y) && std::fabs(x) <= 1e6 && std::fabs(y) <= 1e6))
      bad_request("points: coordinates must be finite and within +-1e6");
    out.push_back({x, y});
  }
  return out;
}

}  // namespace

SelectRequest select_from_json(const std::string& tool, const json& body) {
  edit::ShapeKind shape = edit::ShapeKind::kRect;
  const std::optional<edit::SelectKind> kind = edit::parse_select_kind(tool, &shape);
  if (!kind) throw AppError(ErrorKind::kNotFound, "no selection tool '" + tool + "' (" + edit::select_kind_list() + ")");
  SelectRequest r;
  edit::SelectOp& op = r.op;
  op.kind = *kind;
  switch (op.kind) {
    case edit::SelectKind::kBox:
      json_only_keys(body, {"lo", "hi", "mode"});
      op.lo = json_vec3(body, "lo", kCoordLimit);
      op.hi = json_vec3(body, "hi", kCoordLimit);
      if (op.lo.x > op.hi.x || op.lo.y > op.hi.y || op.lo.z > op.hi.z) bad_request("box: lo must not exceed hi on any axis");
      break;
    case edit::SelectKind::kSphere:
      json_only_keys(body, {"center", "radius", "mode"});
      op.center = json_vec3(body, "center", kCoordLimit);
      op.radius = json_number(body, "radius", 0, kCoordLimit);
      if (!(op.radius > 0)) bad_request("radius: must be > 0");
      break;
    case edit::SelectKind::kShape:
      json_only_keys(body, {"view", "camera", "points", "radius", "mode", "visible", "min_weight"});
      camera_ref_from(body, r);
      op.shape.kind = shape;
      op.shape.points = points_from(body);
      if (shape == edit::ShapeKind::kBrush) op.shape.radius = json_number(body, "radius", 0.5, 1e4);
      op.screen.visible_only = json_bool(body, "visible", false);
      op.screen.min_weight = json_number(body, "min_weight", 0, 1, 0.1);
      break;
    case edit::SelectKind::kColor:
      json_only_keys(body, {"view", "camera", "x", "y", "color", "tolerance", "mode"});
      if (body.contains("color")) {
        const edit::Rgb c = parse_rgb(json_string(body, "color", 64), "color");
        op.color = Vec3{c.r, c.g, c.b};
      } else {
        camera_ref_from(body, r);
        op.x = json_number(body, "x", 0, 1e5);
        op.y = json_number(body, "y", 0, 1e5);
      }
      op.tolerance = json_number(body, "tolerance", 0, 1.8, 0.1);
      break;
    case edit::SelectKind::kOpacity:
    case edit::SelectKind::kSize:
      json_only_keys(body, {"min", "max", "mode"});
      op.min = json_number(body, "min", 0, op.kind == edit::SelectKind::kOpacity ? 1 : kCoordLimit, 0.0);
      op.max = json_number(body, "max", 0, op.kind == edit::SelectKind::kOpacity ? 1 : kCoordLimit,
                           op.kind == edit::SelectKind::kOpacity ? 1.0 : kCoordLimit);
      if (op.min > op.max) bad_request("min: must not exceed max");
      break;
    case edit::SelectKind::kGrow:
    case edit::SelectKind::kShrink:
      json_only_keys(body, {"k", "radius", "steps", "mode"});
      op.k = json_integer(body, "k", 0, 1000, body.contains("radius") ? 0 : 8);
      op.distance = json_number(body, "radius", 0, kCoordLimit, 0.0);
      op.steps = json_integer(body, "steps", 1, 100, 1);
      if (op.k == 0 && !(op.distance > 0)) bad_request("radius: give k (neighbours) or a radius > 0");
      break;
    default:
      json_only_keys(body, {"mode"});
      break;
  }
  try {
    op.mode = edit::parse_combine_mode(json_string(body, "mode", 16, std::string("replace")));
  } catch (const Error& e) {
    bad_request(e.what());
  }
  return r;
}

edit::EditOp edit_from_json(const std::string& name, const json& body) {
  const std::optional<edit::EditKind> kind = edit::parse_edit_kind(name);
  if (!kind) throw AppError(ErrorKind::kNotFound, "no edit '" + name + "' (" + edit::edit_kind_list() + ")");
  edit::EditOp op;
  op.kind = *kind;
  switch (op.kind) {
    case edit::EditKind::kColorize: {
      op.color = parse_rgb(json_string(body, "color", 64), "color");
      const std::string m = json_string(body, "mode", 16, std::string("replace"));
      if (m != "replace" && m != "balanced") bad_request("mode: expected replace or balanced");
      op.color_mode = edit::parse_colorize_mode(m);
      break;
    }
    case edit::EditKind::kScale:
      op.factor = json_number(body, "factor", 0.01, 100);
      break;
    case edit::EditKind::kCopy:
    case edit::EditKind::kTransform:
      op.transform = similarity_from(body);
      break;
    case edit::EditKind::kCombine:
      op.transform = similarity_from(body);
      op.direction = edit::CombineDirection::kFrom;
      if (body.contains("path") == body.contains("upload"))
        bad_request("give either 'path' (inside the data folder) or 'upload' (an uploaded scene's name)");
      op.other_path = json_string(body, body.contains("upload") ? "upload" : "path", 4096);
      if (op.other_path.empty()) bad_request(std::string(body.contains("upload") ? "upload" : "path") + ": empty");
      break;
    default:
      break;
  }
  try {
    edit::check_edit_op(op);
  } catch (const Error& e) {
    bad_request(e.what());
  }
  return op;
}

json to_json(const SceneInfo& s) {
  json cams = json::array();
  Vec3 up_sum{0, 0, 0};
  for (size_t i = 0; i < s.cameras.size(); ++i) {
    const Camera& c = s.cameras[i];
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
  const double n = std::sqrt(up_sum.x * up_sum.x + up_sum.y * up_sum.y + up_sum.z * up_sum.z);
  return {{"name", s.name},
          {"ply", s.ply},
          {"gaussians", s.gaussians},
          {"sh_degree", s.sh_degree},
          {"bounds", {{"lo", vec_json(s.lo)}, {"hi", vec_json(s.hi)}}},
          {"robust_bounds",
           {{"lo", vec_json(s.robust.lo)},
            {"hi", vec_json(s.robust.hi)},
            {"center", vec_json(s.robust.center)},
            {"radius", s.robust.radius}}},
          {"pivot", vec_json(s.robust.center)},
          {"orbit_distance", s.orbit_distance},
          {"up", n > 1e-9 ? vec_json(up_sum / n) : vec_json({0, 0, 1})},
          {"cameras", cams},
          {"preview_side", s.preview_side},
          {"out_dir", s.out_dir},
          {"data_dir", s.data_dir},
          {"background", json::array({s.background[0], s.background[1], s.background[2]})}};
}

json to_json(const JobStatus& job) {
  return {{"id", job.id},       {"name", job.name},       {"state", job.state}, {"done", job.done},
          {"total", job.total}, {"message", job.message}, {"error", job.error}, {"seconds", job.seconds}};
}

json to_json(const AppStatus& s) {
  json j;
  j["job"] = to_json(s.job);
  j["busy"] = s.busy;
  j["queued"] = s.queued;
  const EditStatus& e = s.edit;
  j["edit"] = {{"gaussians", e.gaussians},   {"selected", e.selected},     {"can_undo", e.can_undo},
               {"can_redo", e.can_redo},     {"undo_steps", e.undo_steps}, {"redo_steps", e.redo_steps},
               {"notice", e.notice},         {"revision", e.revision}};
  j["history"] = to_json(e.history);
  const SegmentationStatus& g = s.segmentation;
  json views = json::array();
  for (const ViewEvidence& v : g.views)
    views.push_back({{"index", v.index},
                     {"name", v.name},
                     {"camera", v.camera},
                     {"status", v.status},
                     {"status_text", v.status_text},
                     {"positive", v.positive},
                     {"negative", v.negative},
                     {"not_sent", v.not_sent},
                     {"not_sent_reason", v.not_sent_reason},
                     {"mask_pixels", v.mask_pixels},
                     {"sam_score", v.sam_score},
                     {"overlap", v.overlap},
                     {"inspected", v.inspected}});
  j["segmentation"] = {{"state", g.state},
                       {"message", g.message},
                       {"stale", g.stale},
                       {"clicks", g.clicks},
                       {"steps", g.steps},
                       {"selected", g.selected},
                       {"can_undo", g.can_undo},
                       {"can_redo", g.can_redo},
                       {"can_grow", g.can_grow},
                       {"can_shrink", g.can_shrink},
                       {"views", views},
                       {"thumb_version", g.thumb_version},
                       {"settings",
                        {{"tau", g.settings.tau},
                         {"views", g.settings.views_spec},
                         {"mode", segment::mode_name(g.settings.mode)},
                         {"inspection", g.settings.inspection}}}};
  j["log"] = json::array();
  for (const LogEntry& e : s.log)
    j["log"].push_back({{"seq", e.seq}, {"time", e.time}, {"level", e.level}, {"text", e.text}});
  j["version"] = s.version;
  return j;
}

json to_json(const EditResult& r) {
  json j = {{"label", r.label},         {"notes", r.notes},       {"notice", r.notice},
            {"gaussians", r.gaussians}, {"selected", r.selected}, {"kind", step_kind_name(r.kind)}};
  if (r.job) j["job"] = r.job;
  return j;
}

json to_json(const Timeline& t) {
  json entries = json::array();
  for (const TimelineEntry& e : t.entries) entries.push_back({{"kind", step_kind_name(e.kind)}, {"label", e.label}});
  return {{"entries", entries},
          {"cursor", t.cursor},
          {"can_undo", t.cursor > 0},
          {"can_redo", t.cursor < t.entries.size()}};
}

json to_json(const SelectionBounds& b) {
  return {{"of", b.of_selection ? "selection" : "scene"}, {"count", b.count},          {"lo", vec_json(b.lo)},
          {"hi", vec_json(b.hi)},                         {"center", vec_json(b.center)}, {"radius", b.radius}};
}

SceneSource scene_source_from_json(const json& body) {
  return body.is_object() && body.contains("upload") ? SceneSource::kUpload : SceneSource::kDataFolder;
}

json to_json(const SceneFileEntry& e) {
  json j = {{"name", e.name}, {"kind", e.kind}, {"bytes", e.bytes}};
  if (e.gaussians) j["gaussians"] = e.gaussians;
  return j;
}

json to_json(const std::vector<SceneFileEntry>& entries) {
  json a = json::array();
  for (const SceneFileEntry& e : entries) a.push_back(to_json(e));
  return a;
}

json to_json(const ExportResult& r) { return {{"path", r.path}, {"gaussians", r.gaussians}, {"notes", r.notes}}; }

}  // namespace isegman::server
