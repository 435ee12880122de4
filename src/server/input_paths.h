// Where the server may read: every input path a request names (the other scene of a
// combine) must lie inside the data folder given at launch (`--data-dir`, default the
// scene's parent folder), after resolving symlinks and "..". A path outside gets one
// answer whether or not something exists there, so requests cannot probe the disk.
#pragma once

#include <string>

#include "core/scene.h"

namespace isegman::server {

// The folder that holds the scene: the parent of a trainer output folder
// (<parent>/<scene>/point_cloud/iteration_N/point_cloud.ply) or of a bare file; "" when
// the bundle names no file.
std::string default_data_dir(const SceneBundle& bundle);

// `path` (relative to `data_dir`, or absolute) resolved inside `data_dir`; throws
// AppError(kInvalid) when `data_dir` is empty, when the path leads outside it, or when
// it does not exist inside it.
std::string resolve_input_path(const std::string& data_dir, const std::string& path);

}  // namespace isegman::server
