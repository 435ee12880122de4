#include "io/camera_loader.h"

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/cameras_json.h"

namespace isegman {

std::vector<Camera> load_cameras(const std::string& path, CameraLoadReport* report) {
  std::vector<uint8_t> bytes = read_file_bytes(path);
  size_t i = 0;
  while (i < bytes.size() && std::isspace(bytes[i])) ++i;
  if (i < bytes.size() && bytes[i] == '[') {
    if (report) report->format = "INRIA cameras.json";
    return parse_cameras_json(std::string(bytes.begin(), bytes.end()), path);
  }
  throw Error(path, "unrecognised camera file format");
}

}  // namespace isegman
