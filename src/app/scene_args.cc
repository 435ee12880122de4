#include "app/scene_args.h"

#include "io/scene_loader.h"

namespace isegman::app {

SceneBundle load_scene_from_args(const Args& args, bool require_cameras) {
  SceneLoadOptions opt;
  opt.cameras_path = args.get("cameras");
  opt.images_dir = args.get("images");
  opt.require_cameras = require_cameras;
  return load_scene(args.positional(0, "<scene>: a scene directory or a PLY file"), opt);
}

}  // namespace isegman::app
