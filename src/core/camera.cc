#include "core/camera.h"

#include <cmath>
#include <cstdlib>

#include "core/error.h"

namespace isegman {

bool Camera::project(const Vec3& pw, double& u, double& v, double* depth) const {
  Vec3 pc = world_to_camera(pw);
  if (depth) *depth = pc.z;
  if (pc.z <= 0) return false;
  project_camera_point(pc, u, v);
  return true;
}

Vec3 Camera::ray_direction(double u, double v) const {
  Vec3 dc{(u - cx) / fx, (v - cy) / fy, 1.0};
  return normalized(R.transposed() * dc);
}

Camera Camera::from_center_rotation(const Vec3& center, const Mat3& cam_to_world) {
  Camera c;
  c.R = cam_to_world.transposed();
  c.t = -(c.R * center);
  return c;
}

Camera Camera::look_at(const Vec3& eye, const Vec3& target, const Vec3& up, int width,
                       int height, double fov_x_deg) {
  Vec3 z = normalized(target - eye);
  // Right-handed camera frame with y pointing down the image: x = y cross z, y ~ -up.
  Vec3 x = normalized(cross(z, up));
  Vec3 y = cross(z, x);
  Camera c = from_center_rotation(eye, Mat3::from_cols(x, y, z));
  c.width = width;
  c.height = height;
  c.fx = c.fy = 0.5 * width / std::tan(0.5 * fov_x_deg * M_PI / 180.0);
  c.cx = 0.5 * width;
  c.cy = 0.5 * height;
  return c;
}

Camera Camera::resized(int new_width, int new_height) const {
  Camera c = *this;
  double sx = double(new_width) / width, sy = double(new_height) / height;
  c.width = new_width;
  c.height = new_height;
  c.fx *= sx;
  c.cx *= sx;
  c.fy *= sy;
  c.cy *= sy;
  return c;
}

void Camera::validate(const std::string& source) const {
  const std::string who = "camera '" + (name.empty() ? std::to_string(id) : name) + "'";
  if (width <= 0 || height <= 0)
    throw Error(source, who + " has a zero or negative image size " + std::to_string(width) +
                            "x" + std::to_string(height));
  if (width > 65536 || height > 65536)
    throw Error(source, who + " has an implausible image size " + std::to_string(width) + "x" +
                            std::to_string(height));
  if (!(std::isfinite(fx) && std::isfinite(fy) && fx > 0 && fy > 0))
    throw Error(source, who + " has a non-positive or non-finite focal length");
  if (!(std::isfinite(cx) && std::isfinite(cy)))
    throw Error(source, who + " has a non-finite principal point");
  for (int r = 0; r < 3; ++r) {
    if (!std::isfinite(t[r])) throw Error(source, who + " has a non-finite position");
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(R.m[r][c])) throw Error(source, who + " has a non-finite rotation");
  }
  Mat3 rrt = R * R.transposed();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      if (std::fabs(rrt.m[r][c] - (r == c ? 1.0 : 0.0)) > 1e-3)
        throw Error(source, who + " has a rotation that is not orthonormal");
  if (R.det() < 0) throw Error(source, who + " has a reflection, not a rotation");
}

const Camera* find_camera(const std::vector<Camera>& cameras, const std::string& key) {
  for (const Camera& c : cameras)
    if (c.name == key) return &c;
  char* end = nullptr;
  long id = std::strtol(key.c_str(), &end, 10);
  if (!key.empty() && end && *end == '\0')
    for (const Camera& c : cameras)
      if (c.id == id) return &c;
  return nullptr;
}

}  // namespace isegman
