#include "server/scene_name.h"

#include <filesystem>

namespace fs = std::filesystem;

namespace isegman::server {

std::string scene_name(const std::string& ply_path) {
  auto generic = [](const std::string& n) {
    return n.empty() || n == "scene" || n == "scenes" || n == "output" || n == "outputs" || n == "model" ||
           n == "point_cloud" || n == "splat" || n == "gaussians" || n == "." || n == "/";
  };
  if (ply_path.empty()) return "scene";  // built in memory (the demo, tests)
  std::error_code ec;
  fs::path p = fs::absolute(fs::path(ply_path), ec).lexically_normal();
  if (ec) p = fs::path(ply_path).lexically_normal();
  fs::path folder = p.parent_path();
  std::string name = p.stem().string();
  // .../<scene>/point_cloud/iteration_N/point_cloud.ply -> <scene>
  if (p.filename() == "point_cloud.ply" && p.parent_path().parent_path().filename() == "point_cloud") {
    folder = p.parent_path().parent_path().parent_path();
    name = folder.filename().string();
    folder = folder.parent_path();
  }
  while (generic(name) && folder.has_filename()) {
    name = folder.filename().string();
    folder = folder.parent_path();
  }
  return generic(name) ? "scene" : name;
}

}  // namespace isegman::server
