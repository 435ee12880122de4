#include "io/camera_loader.h"

#include <cctype>
#include <filesystem>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/cameras_json.h"
#include "io/colmap.h"
#include "io/llff.h"
#include "io/npy.h"
#include "io/transforms_json.h"

namespace isegman {

namespace fs = std::filesystem;

namespace {

std::vector<Camera> load_colmap(const std::string& path, CameraLoadReport* report) {
  std::vector<std::string> notes;
  std::string format;
  std::vector<Camera> cams = read_colmap_model(path, &notes, &format);
  if (report) {
    report->format = format;
    report->notes.insert(report->notes.end(), notes.begin(), notes.end());
  }
  return cams;
}

std::vector<Camera> load_file(const std::string& path, CameraLoadReport* report) {
  const std::string file = fs::path(path).filename().string();
  // A file of a COLMAP model stands for its folder.
  for (const char* name : {"cameras.txt", "images.txt", "points3D.txt", "cameras.bin", "images.bin", "points3D.bin"})
    if (file == name) {
      std::string dir = fs::path(path).parent_path().string();
      if (dir.empty()) dir = ".";
      if (find_colmap_model_dir(dir) != dir)
        throw Error(path, "is part of a COLMAP model, but its folder lacks cameras and images files of one kind "
                          "(.bin or .txt)");
      return load_colmap(dir, report);
    }

  std::vector<uint8_t> bytes = read_file_bytes(path);
  std::vector<std::string> notes;
  std::vector<Camera> cams;
  if (is_npy(bytes.data(), bytes.size())) {
    std::string images_note;
    std::vector<std::pair<double, double>> bounds;
    cams = read_llff(path, LlffOptions{}, &notes, &bounds);
    if (report) report->format = "LLFF poses_bounds.npy";
  } else {
    size_t i = 0;
    if (bytes.size() >= 3 && bytes[0] == 0xEF && bytes[1] == 0xBB && bytes[2] == 0xBF) i = 3;  // UTF-8 BOM
    while (i < bytes.size() && std::isspace(bytes[i])) ++i;
    const char first = i < bytes.size() ? char(bytes[i]) : '\0';
    std::string text(bytes.begin() + long(i), bytes.end());
    if (first == '[') {
      cams = parse_cameras_json(text, path);
      if (report) report->format = "INRIA cameras.json";
    } else if (first == '{') {
      cams = parse_transforms_json(text, path, fs::path(path).parent_path().string(), &notes);
      if (report) report->format = "transforms.json (nerfstudio / NeRF)";
    } else if (text.rfind("# Camera list", 0) == 0 || text.rfind("# Image list", 0) == 0) {
      // A renamed COLMAP text file: its folder must hold the model.
      std::string dir = fs::path(path).parent_path().string();
      if (dir.empty()) dir = ".";
      return load_colmap(dir, report);
    } else {
      throw Error(path, "unrecognised camera file format (expected INRIA cameras.json, transforms.json, "
                        "LLFF poses_bounds.npy, or a COLMAP model folder)");
    }
  }
  if (report) report->notes.insert(report->notes.end(), notes.begin(), notes.end());
  return cams;
}

}  // namespace

std::vector<Camera> load_cameras_any(const std::string& path, CameraLoadReport* report) {
  std::error_code ec;
  if (!fs::is_directory(path, ec)) return load_file(path, report);
  // A folder: a COLMAP model (or a scene with sparse/0, sparse/), else one known file.
  if (!find_colmap_model_dir(path).empty()) return load_colmap(path, report);
  for (const char* name : {"transforms.json", "poses_bounds.npy", "cameras.json"}) {
    fs::path p = fs::path(path) / name;
    if (fs::is_regular_file(p, ec)) return load_file(p.string(), report);
  }
  throw Error(path, "no cameras found in this folder (looked for a COLMAP model in it, sparse/0 or sparse/, "
                    "and for transforms.json, poses_bounds.npy, cameras.json)");
}

// Every format goes through one uniqueness check: duplicate ids or names would make a
// camera unreachable and let one render overwrite another.
std::vector<Camera> load_cameras(const std::string& path, CameraLoadReport* report) {
  std::vector<Camera> cams = load_cameras_any(path, report);
  validate_camera_set(cams, path);
  return cams;
}

}  // namespace isegman
