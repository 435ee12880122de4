// The page's free (orbit/pan/zoom) camera: eye, target, up, horizontal field of view and
// image size, checked and turned into a Camera.
#pragma once

#include <nlohmann/json.hpp>

#include "core/camera.h"

namespace isegman::server {

struct FreeCameraSpec {
  Vec3 eye, target, up{0, 0, 1};
  double fov_x_deg = 60;
  int width = 640, height = 480;
};

// Throws HttpError(400) on a degenerate spec (eye == target, up along the view, fov or
// size out of range).
Camera make_free_camera(const FreeCameraSpec& spec);
// From {"eye":[..], "target":[..], "up":[..], "fov": deg, "width": w, "height": h}.
FreeCameraSpec free_camera_from_json(const nlohmann::json& j);

}  // namespace isegman::server
