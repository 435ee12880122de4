// A calibrated pinhole view: intrinsics, world-to-camera pose (OpenCV axes: x right,
// y down, z forward) and image size. Pixel coordinates are continuous with pixel (i, j)
// covering [i, i+1) x [j, j+1), so its centre is (i + 0.5, j + 0.5) (COLMAP convention).
#pragma once

#include <cstdint>

#include <string>
#include <vector>

#include "core/math.h"

namespace isegman {

// Limits of a plausible camera (validate()): image side, pixel count, focal length.
constexpr int kMaxImageSide = 32768;
constexpr int64_t kMaxImagePixels = int64_t(1) << 28;
constexpr double kMaxFocal = 1e7;

struct Camera {
  int id = 0;
  std::string name;        // img_name: stem of the source image file
  std::string image_path;  // optional: the source photo, when known
  int width = 0, height = 0;
  double fx = 0, fy = 0, cx = 0, cy = 0;
  Mat3 R;  // world -> camera rotation
  Vec3 t;  // world -> camera translation: p_cam = R p_world + t

  Vec3 center() const { return -(R.transposed() * t); }
  Vec3 world_to_camera(const Vec3& p) const { return R * p + t; }
  Vec3 camera_to_world(const Vec3& p) const { return R.transposed() * (p - t); }
  // Projects a camera-space point to pixel coordinates (requires z > 0).
  void project_camera_point(const Vec3& pc, double& u, double& v) const {
    u = fx * pc.x / pc.z + cx;
    v = fy * pc.y / pc.z + cy;
  }
  // Projects a world point; returns false when it lies behind the camera.
  bool project(const Vec3& pw, double& u, double& v, double* depth = nullptr) const;
  // Direction (world space, unit) of the ray through pixel coordinates (u, v).
  Vec3 ray_direction(double u, double v) const;

  // Builds a camera from a camera-to-world rotation (columns = camera axes in world
  // space, OpenCV) and the camera centre, as INRIA's cameras.json stores it.
  static Camera from_center_rotation(const Vec3& center, const Mat3& cam_to_world);
  // A camera at `eye` looking at `target` with the given world up vector (image y goes
  // along -up). Principal point at the image centre.
  static Camera look_at(const Vec3& eye, const Vec3& target, const Vec3& up, int width,
                        int height, double fov_x_deg);

  // The same view at another resolution (intrinsics scaled with the image).
  Camera resized(int new_width, int new_height) const;
  // Checks sizes, focal lengths and the rotation; throws Error naming `source`.
  void validate(const std::string& source) const;
};

// Throws Error(source, ...) when two cameras share an id or a name (one would be
// unreachable and its renders overwritten).
void validate_camera_set(const std::vector<Camera>& cameras, const std::string& source);

// Finds a camera by numeric id or by name; nullptr when absent.
const Camera* find_camera(const std::vector<Camera>& cameras, const std::string& id_or_name);

}  // namespace isegman
