// Building blocks of the synthetic scenes (the demo scene and the hard evaluation scenes):
// flat, surface-aligned Gaussians as a trainer leaves them on opaque surfaces, each with
// a label so the ground truth of every object is known per Gaussian.
#pragma once

#include <vector>

#include "core/random.h"
#include "core/scene.h"

namespace isegman {

// Quaternion turning the local z axis onto `n`.
Quat align_z_to(const Vec3& n);

struct SceneBuilder {
  GaussianScene& g;
  std::vector<int>& labels;
  SplitMix64& rng;
  int degree = 3;
  double size_scale = 1.0;  // > 1 imitates the coarse Gaussians of a short training
  // Imperfect surfaces as a trainer leaves them on real captures (both 0 by default: no
  // extra random numbers are drawn and every scene built without them stays as it was).
  // depth_jitter: the standard deviation (metres) of each centre's offset along the
  // normal, cut at 2.5 of it; shape_jitter: the log-spread of sizes and of the two tangent
  // axes' ratio, also thickening some Gaussians and tilting them off the surface.
  double depth_jitter = 0;
  double shape_jitter = 0;

  // Adds a flat Gaussian at p tangent to the surface with normal n.
  void splat(const Vec3& p, const Vec3& n, double size, const Vec3& rgb, int label, double shine);
  // Adds an elongated flat Gaussian: `length` along `along` (in the tangent plane of n).
  void strip(const Vec3& p, const Vec3& n, const Vec3& along, double length, double width, const Vec3& rgb,
             int label, double shine);
  // Adds a roundish semi-transparent Gaussian in free space (a floater a trainer leaves
  // where few views constrain it), labelled -1.
  void floater(const Vec3& p, double size, const Vec3& rgb, double opacity);
};

}  // namespace isegman
