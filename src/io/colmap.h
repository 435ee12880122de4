// COLMAP sparse models (cameras + images; points3D is not needed), text and binary.
// COLMAP stores world-to-camera poses (quaternion qw qx qy qz and translation) in OpenCV
// axes with the same pixel convention as isegman, so a pinhole camera maps one to one.
// Distorted models keep fx, fy, cx, cy; the distortion is reported and ignored.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/math.h"

namespace isegman {

// A COLMAP camera model: numeric id (cameras.bin), name (cameras.txt), parameter count.
struct ColmapCameraModel {
  int id;
  const char* name;
  int num_params;
  bool single_focal;  // params start with f, cx, cy (else fx, fy, cx, cy)
  bool fisheye;       // not a perspective projection at all
};
// nullptr when unknown.
const ColmapCameraModel* colmap_model_by_id(int id);
const ColmapCameraModel* colmap_model_by_name(const std::string& name);

struct ColmapCamera {
  uint32_t camera_id = 0;
  int model_id = 1;  // PINHOLE
  uint64_t width = 0, height = 0;
  std::vector<double> params;
};

struct ColmapImage {
  uint32_t image_id = 0;
  Quat q;  // world -> camera rotation, (w, x, y, z)
  Vec3 t;  // world -> camera translation
  uint32_t camera_id = 0;
  std::string name;  // path relative to the images folder, e.g. "DSC_0001.JPG"
};

// Parsers from memory; `source` names the file in errors. They check every count
// against the bytes left before allocating, the model ids, parameter counts and finite
// values, and refuse trailing bytes.
std::vector<ColmapCamera> parse_colmap_cameras_bin(const uint8_t* data, size_t size,
                                                   const std::string& source);
std::vector<ColmapImage> parse_colmap_images_bin(const uint8_t* data, size_t size,
                                                 const std::string& source);
std::vector<ColmapCamera> parse_colmap_cameras_txt(const std::string& text, const std::string& source);
std::vector<ColmapImage> parse_colmap_images_txt(const std::string& text, const std::string& source);

// Joins cameras and images into isegman cameras, sorted by image name (as the INRIA
// trainer does). Camera::id is the COLMAP image id; Camera::name the image file stem;
// image_path is images_dir/name when images_dir is not empty. Notes (distortion ignored,
// ...) are appended to `notes`. Errors name `images_source` / `cameras_source`.
std::vector<Camera> colmap_to_cameras(const std::vector<ColmapCamera>& cameras,
                                      const std::vector<ColmapImage>& images,
                                      const std::string& cameras_source,
                                      const std::string& images_source,
                                      const std::string& images_dir,
                                      std::vector<std::string>* notes);

// The model folder for `path`: `path` itself when it holds cameras+images (.bin or .txt),
// else path/sparse/0 or path/sparse. Empty when none is found.
std::string find_colmap_model_dir(const std::string& path);

// Reads a model folder or a scene folder containing sparse/0 or sparse/. Binary is
// preferred when both are present. `format` receives "COLMAP binary" or "COLMAP text".
std::vector<Camera> read_colmap_model(const std::string& path,
                                      std::vector<std::string>* notes = nullptr,
                                      std::string* format = nullptr);

// Writers: one PINHOLE camera per distinct intrinsics, one image per camera, image
// names = camera name + the extension of image_path (".png" when unknown), and an empty
// points3D file so COLMAP itself can open the model. The folder must exist.
std::vector<uint8_t> serialize_colmap_cameras_bin(const std::vector<ColmapCamera>& cameras);
std::vector<uint8_t> serialize_colmap_images_bin(const std::vector<ColmapImage>& images);
void cameras_to_colmap(const std::vector<Camera>& cameras, std::vector<ColmapCamera>& out_cameras,
                       std::vector<ColmapImage>& out_images);
void write_colmap_text(const std::string& dir, const std::vector<Camera>& cameras);
void write_colmap_binary(const std::string& dir, const std::vector<Camera>& cameras);

}  // namespace isegman
