// Scene loading shared by the commands: <scene> positional + --cameras/--images, and the
// virtual views of scenes without cameras (--virtual-views N, --virtual-size WxH,
// --virtual-layout auto|orbit|sphere|forward, --add-virtual-views).
#pragma once

#include <set>
#include <string>

#include "app/args.h"
#include "core/scene.h"

namespace isegman::app {

// The value flags and switches load_scene_from_args reads: add them to a command's Args.
const std::set<std::string>& scene_value_flags();
const std::set<std::string>& scene_switch_flags();
// One line per flag for the commands' help texts.
const char* scene_flags_help();

// Prints the loaders' notes (format mismatches, virtual views) to stdout.
SceneBundle load_scene_from_args(const Args& args, bool require_cameras = true);

}  // namespace isegman::app
