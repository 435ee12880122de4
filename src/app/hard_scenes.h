// The segmentation evaluation set: synthetic scenes with exact per-Gaussian labels, built
// to reproduce how one click fails on real captures: foliage and a trellis with gaps in
// front of a wall, a vase seen through the trellis, an object behind an occluder, a thin
// pillar that leaves the frame, a tiny object, a compound object (a lamp of three parts),
// forward-facing and orbit cameras, and a coarse copy made of fewer, larger Gaussians as
// a short training leaves them. The demo scene's four objects are the clean orbit cases.
#pragma once

#include <string>
#include <vector>

#include "app/demo_scene.h"
#include "core/click.h"
#include "core/image.h"

namespace isegman {

struct EvalTaskSpec {
  std::string name;  // scene/object
  std::string kind;  // the failure kind it reproduces
  int object = 0;    // label of the target in the scene
  int camera = 0;    // the clicked camera
  double x = 0, y = 0;  // the clicked pixel (integer indices; its centre is x + 0.5, y + 0.5)
};

struct EvalScene {
  std::string name;
  DemoScene scene;
  std::vector<EvalTaskSpec> tasks;
};

struct EvalSetOptions {
  int width = 480, height = 360;
  float density = 1.0f;
  // Photos per photo of each capture: camera_factor - 1 more between each camera and the
  // next along its path, as a capture of 100-300 photos has (voting views must then be
  // chosen among them). Tasks keep their camera and pixel.
  int camera_factor = 1;
};

std::vector<EvalScene> make_eval_scenes(const EvalSetOptions& options = {});

// `factor` x the cameras of a capture: between each camera and the next, factor - 1 more
// on the way (centres on the line between them, orientations slerped), all renamed in path
// order with the first name's prefix (orbit_000, orbit_001, ...). Camera i becomes i * factor.
void densify_cameras(std::vector<Camera>& cameras, int factor);

// A click on `object` near the 3D point `anchor`: the first camera from `first_camera` on
// (wrapping) in which the anchor projects inside the image (with a margin) and a pixel
// within `search_px` of it shows the object (>= 95 % of its blending weight); the pixel
// closest to the projection wins. False when no camera has one.
bool find_click(const DemoScene& scene, int object, const Vec3& anchor, int first_camera, double search_px,
                int& camera, double& x, double& y);

// A task's click, then `count` - 1 more drawn anywhere on the object as its clicked camera
// shows it (its rendered truth mask > 0.5), as users click: near edges, on thin parts.
// The draws are fixed per task (seeded by its name).
std::vector<Click> task_clicks(const EvalScene& scene, const EvalTaskSpec& task, int count);

// `own`, then `count` - 1 clicks drawn uniformly from the pixels of `mask` (one channel or
// more: a pixel is on where any channel > 0.5) whose every neighbour within `inset` pixels
// (a square) is on too, in the mask's pixels. Fixed by `name` (its FNV-1a hash seeds the
// draws). Fewer when no pixel qualifies.
std::vector<Click> clicks_drawn_on(const Image& mask, const std::string& name, const Click& own, int count, int inset = 0);

}  // namespace isegman
