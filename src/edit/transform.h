// Geometric edits of a selection S: scaling about its centroid (the paper's formula),
// moving/rotating/scaling it in place, and copy & paste with a similarity transform.
//
// A transform maps a point p to  p' = scale * R (p - pivot) + pivot + translation,
// with pivot = S's centroid unless given. Each Gaussian's orientation becomes R q (its
// stored quaternion norm is kept), its log-scales gain log(scale), its normal (when the
// scene has normals) turns by R, and its SH bands 1-3 are rotated (edit/sh_rotation.h)
// so the object looks the same from every side, only turned.
#pragma once

#include <optional>

#include "core/math.h"
#include "core/scene.h"
#include "core/selection.h"
#include "edit/delta.h"

namespace isegman::edit {

struct Similarity {
  Vec3 translation;
  Quat rotation;                // normalised before use; identity by default
  double scale = 1.0;           // uniform, > 0
  std::optional<Vec3> pivot;    // default: centroid of the selection
};

// R = Rz(rz) Ry(ry) Rx(rx), angles in degrees: rotate about x first, then y, then z
// (fixed world axes).
Quat rotation_from_euler_deg(double rx, double ry, double rz);

// Paper's scaling: mu' = (mu - mean(mu)) * eps + mean(mu), log s' = log s + log eps.
Delta plan_scale(const GaussianScene& scene, const Selection& selection, double eps);
// Applies `t` to S in place.
Delta plan_transform(const GaussianScene& scene, const Selection& selection, const Similarity& t);
// Appends a transformed copy of S; the selection moves to the copy.
Delta plan_copy(const GaussianScene& scene, const Selection& selection, const Similarity& t);

// Applies a similarity to every Gaussian of `records` about `pivot` (the building
// block of the operations above and of combine). Throws Error(op, ...) on a non-finite
// result.
void transform_records(GaussianScene& records, const Similarity& t, const Vec3& pivot, const std::string& op);

// Checks a similarity's parameters (finite, scale > 0, non-zero rotation).
void check_similarity(const Similarity& t, const std::string& op);

}  // namespace isegman::edit
