// The page's name for the scene: the trainer's output folder
// (.../<name>/point_cloud/iteration_N/point_cloud.ply) or the file's stem; a generic name
// ("scene", "output", "point_cloud", ...) gives way to the folder above it, so the
// fixtures' fern/scene/ is "fern", not "scene". "scene" when nothing better is known.
#pragma once

#include <string>

namespace isegman::server {

std::string scene_name(const std::string& ply_path);

}  // namespace isegman::server
