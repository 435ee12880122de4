// Scene loading shared by the commands: <scene> positional + --cameras/--images.
#pragma once

#include "app/args.h"
#include "core/scene.h"

namespace isegman::app {

SceneBundle load_scene_from_args(const Args& args, bool require_cameras = true);

}  // namespace isegman::app
