#include "core/camera.h"

#include <cmath>
#include <cstdint>
#include <map>
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
  // Bounded so every buffer sized from a camera fits in memory (2^28 pixels = 1 GiB RGBA).
  if (width > kMaxImageSide || height > kMaxImageSide || int64_t(width) * height > kMaxImagePixels)
    throw Error(source, who + " has an implausible image size " + std::to_string(width) + "x" +
                            std::to_string(height) + " (at most " + std::to_string(kMaxImageSide) +
                            " per side and " + std::to_string(kMaxImagePixels) + " pixels)");
  if (!(std::isfinite(fx) && std::isfinite(fy) && fx > 0 && fy > 0))
    throw Error(source, who + " has a non-positive or non-finite focal length");
  if (fx > kMaxFocal || fy > kMaxFocal)
    throw Error(source, who + " has an implausible focal length fx=" + std::to_string(fx) +
                            " fy=" + std::to_string(fy) + " (at most 1e7 pixels)");
  if (std::fabs(cx) > kMaxFocal || std::fabs(cy) > kMaxFocal)
    throw Error(source, who + " has an implausible principal point (|cx|, |cy| at most 1e7 pixels)");
  for (char ch : name)
    if (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f)
      throw Error(source, "camera " + std::to_string(id) + " has a name with a control character (NUL included)");
  if (name.size() > 1024) throw Error(source, "camera " + std::to_string(id) + " has a name longer than 1024 bytes");
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

void validate_camera_set(const std::vector<Camera>& cameras, const std::string& source) {
  std::map<int, size_t> ids;
  std::map<std::string, size_t> names;
  for (size_t i = 0; i < cameras.size(); ++i) {
    const Camera& c = cameras[i];
    if (!ids.emplace(c.id, i).second)
      throw Error(source, "two cameras have the id " + std::to_string(c.id) + " (entries " +
                              std::to_string(ids[c.id]) + " and " + std::to_string(i) + "); ids must be unique");
    if (!c.name.empty() && !names.emplace(c.name, i).second)
      throw Error(source, "two cameras are named '" + c.name.substr(0, 80) + "' (entries " +
                              std::to_string(names[c.name]) + " and " + std::to_string(i) + "); names must be unique");
  }
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
