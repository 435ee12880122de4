#include "server/free_camera.h"

#include <cmath>

#include "server/app_error.h"

namespace isegman::server {

namespace {
double length(const Vec3& v) { return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }
Vec3 cross3(const Vec3& a, const Vec3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
}  // namespace

Camera make_free_camera(const FreeCameraSpec& s) {
  if (!(s.fov_x_deg >= 5 && s.fov_x_deg <= 150)) invalid("camera: fov must be in [5, 150] degrees");
  if (s.width < 16 || s.height < 16 || s.width > 4096 || s.height > 4096)
    invalid("camera: width and height must be in [16, 4096]");
  const Vec3 d = s.target - s.eye;
  const double dl = length(d), ul = length(s.up);
  if (!(dl > 1e-9)) invalid("camera: eye and target coincide");
  if (!(ul > 1e-9)) invalid("camera: up vector is zero");
  if (length(cross3(d / dl, s.up / ul)) < 1e-6) invalid("camera: up vector is parallel to the view direction");
  Camera c = Camera::look_at(s.eye, s.target, s.up, s.width, s.height, s.fov_x_deg);
  c.name = "free";
  c.id = -1;
  return c;
}

}  // namespace isegman::server
