#include "server/pick.h"

#include <algorithm>
#include <cmath>

namespace isegman::server {

PickResult pick_surface(const GaussianScene& scene, const Camera& full, double x, double y, RenderSettings settings,
                        int max_side) {
  PickResult r;
  if (!(x >= 0 && y >= 0 && x < full.width && y < full.height)) return r;
  Camera cam = full;
  const int side = std::max(full.width, full.height);
  if (side > max_side) {
    const double s = double(max_side) / side;
    cam = full.resized(std::max(1, int(std::lround(full.width * s))), std::max(1, int(std::lround(full.height * s))));
  }
  const double sx = double(cam.width) / full.width, sy = double(cam.height) / full.height;
  settings.depth = true;
  const RenderOutput out = render(scene, cam, settings);
  const int px = std::min(cam.width - 1, int(x * sx)), py = std::min(cam.height - 1, int(y * sy));
  // The nearest covered pixel (squared distance), searching outwards a few pixels.
  const int reach = std::max(2, int(std::lround(0.03 * std::max(cam.width, cam.height))));
  int best_x = -1, best_y = -1, best_d = 1 << 30;
  for (int dy = -reach; dy <= reach; ++dy)
    for (int dx = -reach; dx <= reach; ++dx) {
      const int qx = px + dx, qy = py + dy, d = dx * dx + dy * dy;
      if (qx < 0 || qy < 0 || qx >= cam.width || qy >= cam.height || d >= best_d) continue;
      if (out.alpha.at(qx, qy) < 0.5f || !(out.depth.at(qx, qy) > 0)) continue;
      best_x = qx, best_y = qy, best_d = d;
    }
  if (best_x < 0) return r;
  const double z = out.depth.at(best_x, best_y);
  // The ray through the clicked point (not the neighbour's centre) at the neighbour's depth.
  const double u = best_d == 0 ? x * sx : best_x + 0.5, v = best_d == 0 ? y * sy : best_y + 0.5;
  const Vec3 pc{(u - cam.cx) / cam.fx * z, (v - cam.cy) / cam.fy * z, z};
  r.hit = true;
  r.point = cam.camera_to_world(pc);
  r.depth = z;
  return r;
}

}  // namespace isegman::server
