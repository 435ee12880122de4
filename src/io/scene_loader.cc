#include "io/scene_loader.h"

#include <filesystem>

#include "core/error.h"
#include "io/camera_loader.h"
#include "io/cameras_json.h"
#include "io/gaussian_file.h"
#include "io/ply.h"
#include "io/sog.h"

namespace fs = std::filesystem;

namespace isegman {

std::string find_scene_ply(const std::string& dir) {
  const fs::path root(dir);
  const fs::path pc = root / "point_cloud";
  long best = -1;
  fs::path best_path;
  std::error_code ec;
  if (fs::is_directory(pc, ec)) {
    for (const auto& entry : fs::directory_iterator(pc, ec)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind("iteration_", 0) != 0) continue;
      char* end = nullptr;
      long it = std::strtol(name.c_str() + 10, &end, 10);
      if (!end || *end != '\0' || name.size() == 10) continue;
      fs::path ply = entry.path() / "point_cloud.ply";
      if (it > best && fs::is_regular_file(ply, ec)) {
        best = it;
        best_path = ply;
      }
    }
  }
  if (best >= 0) return best_path.string();
  if (fs::is_regular_file(root / "point_cloud.ply", ec)) return (root / "point_cloud.ply").string();
  // A folder that holds the scene one level down (a capture's folder with scene/ and
  // images/): name it rather than leave the user to guess.
  std::string below;
  for (const auto& entry : fs::directory_iterator(root, ec)) {
    if (!entry.is_directory(ec)) continue;
    if (fs::is_directory(entry.path() / "point_cloud", ec) || fs::is_regular_file(entry.path() / "point_cloud.ply", ec))
      below += (below.empty() ? "" : ", ") + entry.path().string();
  }
  throw Error(dir, "no point_cloud/iteration_<N>/point_cloud.ply or point_cloud.ply in this scene directory" +
                       (below.empty() ? std::string() : "; a scene lies one level down: " + below));
}

namespace {
std::string find_images_dir(const fs::path& scene_root) {
  std::error_code ec;
  for (const fs::path& cand : {scene_root / "images", scene_root.parent_path() / "images"})
    if (fs::is_directory(cand, ec)) return cand.string();
  return "";
}

void attach_images(SceneBundle& b) {
  if (b.images_dir.empty()) return;
  std::error_code ec;
  for (Camera& c : b.cameras) {
    if (!c.image_path.empty()) continue;
    for (const char* ext : {"", ".png", ".jpg", ".jpeg", ".JPG", ".PNG", ".JPEG"}) {
      fs::path p = fs::path(b.images_dir) / (c.name + ext);
      if (fs::is_regular_file(p, ec)) {
        c.image_path = p.string();
        break;
      }
    }
  }
}
}  // namespace

SceneBundle load_scene(const std::string& path, const SceneLoadOptions& opt) {
  SceneBundle b;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error(path, "no such file or directory");
  fs::path root;
  if (fs::is_directory(path, ec) && !is_sog_dir(path)) {
    root = fs::path(path);
    b.ply_path = find_scene_ply(path);
    if (opt.cameras_path.empty() && fs::is_regular_file(root / "cameras.json", ec))
      b.cameras_path = (root / "cameras.json").string();
  } else {
    b.ply_path = path;
    // A PLY inside point_cloud/iteration_N/ belongs to the scene two levels up.
    fs::path p = fs::absolute(path, ec).parent_path();
    if (p.parent_path().filename() == "point_cloud") root = p.parent_path().parent_path();
    else root = p;
    if (opt.cameras_path.empty() && fs::is_regular_file(root / "cameras.json", ec))
      b.cameras_path = (root / "cameras.json").string();
  }
  if (!opt.cameras_path.empty()) b.cameras_path = opt.cameras_path;
  LoadedGaussians lg = load_gaussians(b.ply_path);
  b.gaussians = std::move(lg.scene);
  if (opt.notes) opt.notes->insert(opt.notes->end(), lg.notes.begin(), lg.notes.end());
  if (!b.cameras_path.empty()) {
    b.cameras = load_cameras(b.cameras_path);
  } else if (!opt.virtual_views_when_missing && opt.require_cameras) {
    throw Error(path, "no cameras: the scene has no cameras.json; pass a camera file (--cameras FILE)");
  }
  if ((b.cameras.empty() && opt.virtual_views_when_missing) || opt.add_virtual_views) {
    const std::vector<Camera> v = make_virtual_views(b.gaussians, b.cameras, opt.virtual_views);
    if (opt.notes)
      opt.notes->push_back(std::to_string(v.size()) + " virtual views (" + v.front().name + "..." + v.back().name +
                           ") around the robust centre of the Gaussians" +
                           (b.cameras.empty() ? std::string(": the scene has no camera file") : std::string()));
    b.cameras.insert(b.cameras.end(), v.begin(), v.end());
  }
  b.images_dir = opt.images_dir.empty() ? find_images_dir(root) : opt.images_dir;
  attach_images(b);
  return b;
}

void write_scene_dir(const std::string& dir, const GaussianScene& gaussians, const std::vector<Camera>& cameras,
                     int iteration) {
  fs::path root(dir);
  fs::path ply_dir = root / "point_cloud" / ("iteration_" + std::to_string(iteration));
  std::error_code ec;
  fs::create_directories(ply_dir, ec);
  if (ec) throw Error(ply_dir.string(), "cannot create directory: " + ec.message());
  write_ply((ply_dir / "point_cloud.ply").string(), gaussians);
  if (!cameras.empty()) write_cameras_json((root / "cameras.json").string(), cameras);
}

}  // namespace isegman
