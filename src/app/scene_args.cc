#include "app/scene_args.h"

#include <cstdio>

#include "core/error.h"
#include "io/scene_loader.h"

namespace isegman::app {

const std::set<std::string>& scene_value_flags() {
  static const std::set<std::string> f = {"cameras", "images", "virtual-views", "virtual-size", "virtual-layout"};
  return f;
}
const std::set<std::string>& scene_switch_flags() {
  static const std::set<std::string> f = {"add-virtual-views"};
  return f;
}
const char* scene_flags_help() {
  return "<scene>: a trainer scene directory or a splat file (PLY, compressed PLY, .splat, .spz, .sog)\n"
         "--cameras FILE      camera file (cameras.json, COLMAP, poses_bounds.npy, transforms.json)\n"
         "--images DIR        source photos\n"
         "--virtual-views N   number of virtual views made when the scene has no cameras (default 24)\n"
         "--virtual-size WxH  their image size (default 800x600)\n"
         "--virtual-layout L  auto | orbit | sphere | forward (default auto)\n"
         "--add-virtual-views add the virtual views to the scene's own cameras\n";
}

SceneBundle load_scene_from_args(const Args& args, bool require_cameras) {
  SceneLoadOptions opt;
  opt.cameras_path = args.get("cameras");
  opt.images_dir = args.get("images");
  opt.require_cameras = require_cameras;
  opt.add_virtual_views = args.has("add-virtual-views");
  opt.virtual_views.count = args.get_int("virtual-views", opt.virtual_views.count);
  if (opt.virtual_views.count < 1 || opt.virtual_views.count > 10000)
    throw Error("--virtual-views must be between 1 and 10000");
  if (args.has("virtual-size")) {
    const std::string s = args.get("virtual-size");
    int w = 0, h = 0;
    char tail = 0;
    if (std::sscanf(s.c_str(), "%dx%d%c", &w, &h, &tail) != 2 || w < 1 || h < 1 || w > 16384 || h > 16384)
      throw Error("--virtual-size: expected WxH (e.g. 800x600), got '" + s + "'");
    opt.virtual_views.width = w;
    opt.virtual_views.height = h;
  }
  if (args.has("virtual-layout")) opt.virtual_views.layout = parse_virtual_layout(args.get("virtual-layout"));
  std::vector<std::string> notes;
  opt.notes = &notes;
  SceneBundle b = load_scene(args.positional(0, "<scene>: a scene directory or a splat file"), opt);
  for (const auto& n : notes) std::printf("note: %s\n", n.c_str());
  return b;
}

}  // namespace isegman::app
