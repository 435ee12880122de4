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

SelectRequest select_from_json(const std::string& tool, const json& body) {
  SelectRequest r;
  const std::string mode = json_string(body, "mode", 16, std::string("replace"));
  if (tool == "box") {
    r.tool = SelectTool::kBox;
    r.lo = json_vec3(body, "lo", kCoordLimit);
    r.hi = json_vec3(body, "hi", kCoordLimit);
  } else if (tool == "sphere") {
    r.tool = SelectTool::kSphere;
    r.center = json_vec3(body, "center", kCoordLimit);
    r.radius = json_number(body, "radius", 0, kCoordLimit);
  } else if (tool == "invert") {
    r.tool = SelectTool::kInvert;
  } else if (tool == "clear") {
    r.tool = SelectTool::kClear;
  } else if (tool == "all") {
    r.tool = SelectTool::kAll;
  } else {
    throw AppError(ErrorKind::kNotFound, "no selection tool '" + tool + "' (box, sphere, invert, clear, all)");
  }
  if (r.tool == SelectTool::kBox || r.tool == SelectTool::kSphere) {
    try {
      r.mode = edit::parse_combine_mode(mode);
    } catch (const Error& e) {
      bad_request(e.what());
    }
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
      op.other_path = json_string(body, "path", 4096);
      if (op.other_path.empty()) bad_request("path: empty");
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
  j["history"] = to_json(s.history);
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
                       {"selected", g.selected},
                       {"can_undo", g.can_undo},
                       {"can_redo", g.can_redo},
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

json to_json(const ExportResult& r) { return {{"path", r.path}, {"gaussians", r.gaussians}, {"notes", r.notes}}; }

}  // namespace isegman::server
