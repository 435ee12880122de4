// isegman info <scene>: what a scene holds.
#include <cstdio>

#include "app/args.h"
#include "app/command.h"
#include "app/scene_args.h"
#include "core/virtual_views.h"

namespace isegman::app {
namespace {

int run_info(const std::vector<std::string>& argv) {
  Args args(argv, scene_value_flags(), scene_switch_flags());
  SceneBundle b = load_scene_from_args(args, /*require_cameras=*/false);
  const GaussianScene& g = b.gaussians;
  Vec3 lo, hi;
  g.bounds(lo, hi);
  std::printf("scene:      %s\n", b.ply_path.c_str());
  std::printf("gaussians:  %zu\n", g.size());
  std::printf("sh degree:  %d (%d coefficients per channel)\n", g.sh_degree, g.coeffs());
  std::printf("bounds:     [%.4g, %.4g, %.4g] .. [%.4g, %.4g, %.4g]\n", lo.x, lo.y, lo.z, hi.x, hi.y, hi.z);
  const RobustBounds rb = robust_bounds(g);
  std::printf("robust:     [%.4g, %.4g, %.4g] .. [%.4g, %.4g, %.4g] (5th-95th opacity-weighted percentiles)\n",
              rb.lo.x, rb.lo.y, rb.lo.z, rb.hi.x, rb.hi.y, rb.hi.z);
  std::printf("normals:    %s\n", g.normals.empty() ? "no" : "yes");
  if (!g.extras.empty()) {
    std::printf("extra properties:");
    for (const auto& e : g.extras) std::printf(" %s(%s)", e.name.c_str(), e.type.c_str());
    std::printf("\n");
  }
  std::printf("fingerprint: %016llx\n", static_cast<unsigned long long>(g.fingerprint()));
  if (b.cameras.empty()) {
    std::printf("cameras:    none\n");
    return 0;
  }
  std::printf("cameras:    %zu from %s\n", b.cameras.size(),
              b.cameras_path.empty() ? "virtual views" : b.cameras_path.c_str());
  size_t with_images = 0;
  for (const auto& c : b.cameras) with_images += !c.image_path.empty();
  std::printf("images:     %zu of %zu found%s%s\n", with_images, b.cameras.size(), b.images_dir.empty() ? "" : " in ",
              b.images_dir.c_str());
  std::printf("  %-4s %-24s %9s %10s %10s %9s %9s\n", "id", "name", "size", "fx", "fy", "cx", "cy");
  for (const auto& c : b.cameras)
    std::printf("  %-4d %-24s %4dx%-4d %10.3f %10.3f %9.2f %9.2f\n", c.id, c.name.c_str(), c.width, c.height, c.fx,
                c.fy, c.cx, c.cy);
  return 0;
}

RegisterCommand reg("info", "Gaussian count, SH degree, bounds, cameras and image sizes of a scene",
                    "usage: isegman info <scene dir | file.ply> [--cameras FILE] [--images DIR]\n"
                    "  A scene dir is a trainer output: point_cloud/iteration_<N>/point_cloud.ply + cameras.json.\n"
                    "  --cameras FILE  cameras.json, COLMAP model (dir or file), poses_bounds.npy or transforms.json\n"
                    "  --images DIR    where the source photos are (matched by camera name)",
                    run_info);

}  // namespace
}  // namespace isegman::app
