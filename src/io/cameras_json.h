// The INRIA trainer's cameras.json: a list of {id, img_name, width, height, position
// (camera centre), rotation (3x3 camera-to-world, rows as nested lists), fx, fy}.
// The principal point is the image centre unless "cx"/"cy" are present.
#pragma once

#include <string>
#include <vector>

#include "core/camera.h"

namespace isegman {

std::vector<Camera> parse_cameras_json(const std::string& text, const std::string& source);
std::vector<Camera> read_cameras_json(const std::string& path);
std::string cameras_to_json(const std::vector<Camera>& cameras);
void write_cameras_json(const std::string& path, const std::vector<Camera>& cameras);

}  // namespace isegman
