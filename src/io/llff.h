// LLFF poses_bounds.npy: an N x 17 float array. Each row is a 3x5 matrix (row-major)
// [R | t | hwf] followed by the near and far depth bounds. The rotation columns are the
// camera's axes in world space in LLFF's order [down, right, back] (camera-to-world), t
// is the camera centre and hwf = (height, width, focal) of the full-resolution photos.
// In OpenCV axes (x right, y down, z forward): right = col1, down = col0, forward = -col2.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/camera.h"
#include "io/npy.h"

namespace isegman {

struct LlffOptions {
  // Folder of the photos; empty: images/ beside the file, else the images_N with the
  // smallest N. Names come from its sorted image files when their count matches.
  std::string images_dir;
  // > 0: scale the cameras to this image width (e.g. images_8: width / 8), focal with it.
  int target_width = 0;
  // With no target width: when the photos found have another size with the same
  // aspect ratio than hwf (a downscaled folder), scale the cameras to the photos' size.
  bool size_from_images = true;
};

// Converts the array; names are used when there are exactly as many as rows, else the
// cameras are named "000", "001", ... `bounds` receives (near, far) per camera.
std::vector<Camera> llff_to_cameras(const NpyArray& array, const std::string& source,
                                    const std::vector<std::string>& image_paths,
                                    std::vector<std::pair<double, double>>* bounds = nullptr);

std::vector<Camera> read_llff(const std::string& path, const LlffOptions& options = {},
                              std::vector<std::string>* notes = nullptr,
                              std::vector<std::pair<double, double>>* bounds = nullptr);

// The N x 17 rows for `cameras` (row-major). LLFF has one focal length and a centred
// principal point: cameras with fx != fy or an off-centre principal point are refused.
std::vector<double> cameras_to_llff(const std::vector<Camera>& cameras, double near_bound, double far_bound);
void write_llff(const std::string& path, const std::vector<Camera>& cameras, double near_bound,
                double far_bound);

}  // namespace isegman
