// Pick-to-focus: the 3D surface point under a pixel, from the rasteriser's expected depth,
// so the page's orbit pivot lands on what the user double-clicked.
#pragma once

#include "core/camera.h"
#include "core/scene.h"
#include "render/rasterizer.h"

namespace isegman::server {

struct PickResult {
  bool hit = false;  // false: no surface (alpha < 0.5) near the pixel
  Vec3 point;        // world coordinates
  double depth = 0;  // camera-space z
};

// `x, y`: continuous pixel coordinates of `camera` (pixel (i, j) covers [i, i+1) x [j, j+1)).
// Renders at most `max_side` pixels on the long side; when the pixel itself is not covered
// (accumulated alpha < 0.5), the nearest covered pixel within 3% of the image is used.
PickResult pick_surface(const GaussianScene& scene, const Camera& camera, double x, double y,
                        RenderSettings settings, int max_side = 320);

}  // namespace isegman::server
