// How much of a straight line through the scene its Gaussians let through, before any view
// is rendered: the product of (1 - alpha) over the Gaussians whose centres lie near the line,
// each at the highest density it reaches along it (the 3D Gaussian, not its projection, so
// an estimate of what a render would show). Voting-view selection asks it whether a
// camera's line of sight to the clicked object is open (view_selection.h).
#pragma once

#include "core/centre_index.h"
#include "core/math.h"
#include "core/scene.h"

namespace isegman::segment {

class LineOfSight {
 public:
  // The scene and the index must outlive this object.
  LineOfSight(const GaussianScene& scene, const CentreIndex& index);
  // Transmittance in [0, 1] along the segment from -> to.
  double transmittance(const Vec3& from, const Vec3& to) const;
  // How far from the line a centre is looked for: 3 sigma of the 99th percentile of the
  // Gaussians' largest scales (larger ones are ignored).
  double reach() const { return reach_; }

 private:
  const GaussianScene& scene_;
  const CentreIndex& index_;
  double reach_ = 0;
};

}  // namespace isegman::segment
