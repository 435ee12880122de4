// Virtual views for scenes that come without cameras (a bare .splat/.spz/.sog or a PLY
// with no camera file), and the robust scene bounds they are placed around.
//
// robust_bounds: per axis, the 5th and 95th percentiles (configurable) of the Gaussian
// centres weighted by their activated opacity. Trained scenes carry far, faint outliers
// (floaters, background blobs), so the raw bounding box would put the views kilometres
// away; the percentile box is where the visible content is. The web app's orbit pivot
// uses the same function.
//
// make_virtual_views: `count` cameras named virtual_000, virtual_001, ... looking at the
// robust centre from a distance where the robust box fills about 80% of the field of view:
//   orbit   - a ring at 20 degrees elevation around the up axis;
//   sphere  - a Fibonacci spiral over the whole sphere (object scans);
//   forward - a small near-square grid of parallel views on a plane in front of the scene
//             (LLFF-style captures), spaced by 10% of the box's width;
//   auto    - forward when the existing cameras all look the same way (the mean of their
//             viewing directions is longer than 0.8), orbit otherwise.
// Up axis and forward direction come from the existing cameras when there are any (the
// mean of their -y and +z axes), otherwise from VirtualViewOptions (default: the
// COLMAP/OpenCV world where y points down and cameras look along +z).
#pragma once

#include <string>
#include <vector>

#include "core/camera.h"
#include "core/math.h"
#include "core/scene.h"

namespace isegman {

struct RobustBounds {
  Vec3 lo, hi;     // percentile box
  Vec3 center;     // middle of the box
  double radius;   // half its diagonal (>0: a tiny positive value for a degenerate scene)
};

// Throws Error when the scene has no Gaussians.
RobustBounds robust_bounds(const GaussianScene& scene, double lower_percentile = 5.0,
                           double upper_percentile = 95.0);

enum class VirtualLayout { kAuto, kOrbit, kSphere, kForward };

struct VirtualViewOptions {
  int count = 24;
  int width = 800, height = 600;
  double fov_x_deg = 60.0;
  VirtualLayout layout = VirtualLayout::kAuto;
  Vec3 up{0, -1, 0};       // world up when there are no cameras to take it from
  Vec3 forward{0, 0, 1};   // viewing direction of forward layouts without cameras
};

// Parses "auto", "orbit", "sphere" or "forward"; throws Error otherwise.
VirtualLayout parse_virtual_layout(const std::string& text);

// Views around the scene; `existing` (may be empty) only informs up/forward and the ids,
// which continue after the largest existing id.
std::vector<Camera> make_virtual_views(const GaussianScene& scene, const std::vector<Camera>& existing,
                                       const VirtualViewOptions& options);

}  // namespace isegman
