// The page's free (orbit/pan/zoom) camera: eye, target, up, horizontal field of view and
// image size, checked and turned into a Camera.
#pragma once

#include "core/camera.h"

namespace isegman::server {

struct FreeCameraSpec {
  Vec3 eye, target, up{0, 0, 1};
  double fov_x_deg = 60;
  int width = 640, height = 480;
};

// Throws AppError(kInvalid) on a degenerate spec (eye == target, up along the view, fov or
// size out of range).
Camera make_free_camera(const FreeCameraSpec& spec);

}  // namespace isegman::server
