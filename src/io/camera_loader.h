// One entry point for every camera format: INRIA cameras.json, COLMAP sparse models
// (text or binary), LLFF poses_bounds.npy and nerfstudio/NeRF transforms.json.
// The format is detected from the content (and the folder layout for COLMAP).
#pragma once

#include <string>
#include <vector>

#include "core/camera.h"

namespace isegman {

struct CameraLoadReport {
  std::string format;              // e.g. "INRIA cameras.json", "COLMAP binary"
  std::vector<std::string> notes;  // e.g. "distortion of camera 1 (OPENCV) is ignored"
};

std::vector<Camera> load_cameras(const std::string& path, CameraLoadReport* report = nullptr);

}  // namespace isegman
