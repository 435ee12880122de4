#include "server/free_camera.h"

#include <cmath>

#include "server/http_error.h"
#include "server/validation.h"

namespace isegman::server {

namespace {
constexpr double kCoordLimit = 1e7;
double length(const Vec3& v) { return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }
Vec3 cross3(const Vec3& a, const Vec3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
}  // namespace

Camera make_free_camera(const FreeCameraSpec& s) {
  if (!(s.fov_x_deg >= 5 && s.fov_x_deg <= 150)) bad_request("camera: fov must be in [5, 150] degrees");
  if (s.width < 16 || s.height < 16 || s.width > 4096 || s.height > 4096)
    bad_request("camera: width and height must be in [16, 4096]");
  const Vec3 d = s.target - s.eye;
  const double dl = length(d), ul = length(s.up);
  if (!(dl > 1e-9)) bad_request("camera: eye and target coincide");
  if (!(ul > 1e-9)) bad_request("camera: up vector is zero");
  if (length(cross3(d / dl, s.up / ul)) < 1e-6) bad_request("camera: up vector is parallel to the view direction");
  Camera c = Camera::look_at(s.eye, s.target, s.up, s.width, s.height, s.fov_x_deg);
  c.name = "free";
  c.id = -1;
  return c;
}

FreeCameraSpec free_camera_from_json(const nlohmann::json& j) {
  if (!j.is_object()) bad_request("camera: expected an object");
  FreeCameraSpec s;
  s.eye = json_vec3(j, "eye", kCoordLimit);
  s.target = json_vec3(j, "target", kCoordLimit);
  s.up = json_vec3(j, "up", kCoordLimit, Vec3{0, 0, 1});
  s.fov_x_deg = json_number(j, "fov", 5, 150, 60.0);
  s.width = json_integer(j, "width", 16, 4096, 640);
  s.height = json_integer(j, "height", 16, 4096, 480);
  return s;
}

}  // namespace isegman::server
