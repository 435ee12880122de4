// nerfstudio / instant-ngp / NeRF-synthetic transforms.json: {intrinsics..., "frames":
// [{"file_path", "transform_matrix" (4x4 camera-to-world, OpenGL axes: x right, y up,
// z back), per-frame intrinsics...}]}. Intrinsics: fl_x, fl_y, cx, cy, w, h (top level or
// per frame, the frame wins), or camera_angle_x (and camera_angle_y) with the image size
// read from the photo's header when w/h are absent. Distortion (k1.., p1..) is reported
// and ignored.
#pragma once

#include <string>
#include <vector>

#include "core/camera.h"

namespace isegman {

// `base_dir` is the folder that file_path entries are relative to (the JSON's folder).
std::vector<Camera> parse_transforms_json(const std::string& text, const std::string& source,
                                          const std::string& base_dir,
                                          std::vector<std::string>* notes = nullptr);
std::vector<Camera> read_transforms_json(const std::string& path, std::vector<std::string>* notes = nullptr);

// Writes fl_x, fl_y, cx, cy, w, h (top level when all cameras share them, else per
// frame) and file_path = "images/<name><ext of image_path, or .png>".
std::string cameras_to_transforms_json(const std::vector<Camera>& cameras);
void write_transforms_json(const std::string& path, const std::vector<Camera>& cameras);

}  // namespace isegman
