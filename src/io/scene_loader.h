// Loads a scene as trainers write it: a directory with
// point_cloud/iteration_<N>/point_cloud.ply (highest N wins) and cameras.json, or a bare
// splat file in any format io/gaussian_file.h reads (PLY, compressed PLY, .splat, .spz,
// .sog file or folder) with a camera file given separately. Without any camera file the
// scene gets virtual views (core/virtual_views.h). Source photos are found by img_name in
// images/ inside or beside the scene directory.
#pragma once

#include <string>

#include "core/scene.h"
#include "core/virtual_views.h"

namespace isegman {

struct SceneLoadOptions {
  std::string cameras_path;  // overrides the directory's cameras.json
  std::string images_dir;    // overrides the search for source photos
  bool require_cameras = true;
  // No camera file: make virtual views (otherwise require_cameras decides).
  bool virtual_views_when_missing = true;
  // Add virtual views even when the scene has cameras.
  bool add_virtual_views = false;
  VirtualViewOptions virtual_views;
  std::vector<std::string>* notes = nullptr;  // what the readers tolerated, views made
};

SceneBundle load_scene(const std::string& path, const SceneLoadOptions& options = {});

// Finds the PLY a scene directory points at (highest iteration); throws when none.
std::string find_scene_ply(const std::string& dir);

// Writes a trainer-style scene directory: point_cloud/iteration_<N>/point_cloud.ply and
// cameras.json (each file written atomically).
void write_scene_dir(const std::string& dir, const GaussianScene& gaussians, const std::vector<Camera>& cameras,
                     int iteration = 30000);

}  // namespace isegman
