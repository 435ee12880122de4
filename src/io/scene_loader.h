// Loads a scene as trainers write it: a directory with
// point_cloud/iteration_<N>/point_cloud.ply (highest N wins) and cameras.json, or a bare
// PLY / .splat file with a camera file given separately. Source photos are found by
// img_name in images/ inside or beside the scene directory.
#pragma once

#include <string>

#include "core/scene.h"

namespace isegman {

struct SceneLoadOptions {
  std::string cameras_path;  // overrides the directory's cameras.json
  std::string images_dir;    // overrides the search for source photos
  bool require_cameras = true;
};

SceneBundle load_scene(const std::string& path, const SceneLoadOptions& options = {});

// Finds the PLY a scene directory points at (highest iteration); throws when none.
std::string find_scene_ply(const std::string& dir);

// Writes a trainer-style scene directory: point_cloud/iteration_<N>/point_cloud.ply and
// cameras.json (each file written atomically).
void write_scene_dir(const std::string& dir, const GaussianScene& gaussians, const std::vector<Camera>& cameras,
                     int iteration = 30000);

}  // namespace isegman
