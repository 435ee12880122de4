// The API's JSON: request bodies to the app's typed requests, and the app's typed
// answers to JSON. The only place (with api.cc) that knows JSON; field checks come from
// validation.h and answer 400 naming the field.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "edit/edit_op.h"
#include "server/app_state.h"

namespace isegman::server {

using nlohmann::json;

// {view: K | camera: {...}, x, y, label}.
ClickRecord click_from_json(const json& body);
// {tau, views, mode, inspection}, every field optional.
SettingsRequest settings_from_json(const json& body);
// /api/select/<tool> (edit/select_op.h's names), every one with `mode`
// (replace/add/subtract/intersect) where it combines:
//   box {lo, hi}, sphere {center, radius};
//   rect / lasso / brush {view | camera, points: [[x, y], ...], radius (brush, pixels),
//     visible, min_weight}: pixels of the camera's full-size image, as clicks;
//   color {view | camera, x, y | color, tolerance} (the eyedropper);
//   opacity / size {min, max}; grow / shrink {k | radius, steps}; invert, clear, all.
// Unknown tools are AppError(kNotFound).
SelectRequest select_from_json(const std::string& tool, const json& body);
// /api/edit/<name> (edit_op.h's names; `move` = transform): colorize {color, mode},
// scale {factor}, copy / transform {translate, rotate, scale}, combine {path | upload, ...}.
// Unknown names are AppError(kNotFound).
edit::EditOp edit_from_json(const std::string& name, const json& body);
// combine's {upload: name} (an uploaded scene) or {path} (inside the data folder).
SceneSource scene_source_from_json(const json& body);
// {"eye":[..], "target":[..], "up":[..], "fov": deg, "width": w, "height": h}.
FreeCameraSpec free_camera_from_json(const json& j);

json to_json(const SceneInfo& info);
json to_json(const AppStatus& status);
json to_json(const JobStatus& job);
json to_json(const EditResult& result);
json to_json(const Timeline& history);
json to_json(const SelectionBounds& bounds);
json to_json(const ExportResult& result);
json to_json(const SceneFileEntry& entry);
json to_json(const std::vector<SceneFileEntry>& entries);

}  // namespace isegman::server
