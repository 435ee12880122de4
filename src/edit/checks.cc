#include "edit/checks.h"

#include <cmath>

#include "core/error.h"

namespace isegman::edit {

void check_selection(const GaussianScene& scene, const Selection& selection, const std::string& op) {
  selection.check_matches(scene, op);
  if (selection.empty()) throw Error(op, "the selection is empty: select some Gaussians first");
}

void check_finite(double v, const std::string& what, const std::string& op) {
  if (!std::isfinite(v)) throw Error(op, what + " must be a finite number");
}
void check_finite(const Vec3& v, const std::string& what, const std::string& op) {
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
    throw Error(op, what + " must be finite numbers");
}
void check_finite(const Quat& q, const std::string& what, const std::string& op) {
  if (!std::isfinite(q.w) || !std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
    throw Error(op, what + " must be finite numbers");
  if (q.norm() == 0) throw Error(op, what + " is a zero quaternion");
}

void check_result(const GaussianScene& rec, const std::string& op) {
  try {
    rec.validate(op);
  } catch (const Error& e) {
    throw Error(op, std::string("the result would not be a valid scene (") + e.what() +
                        "); the parameters are too large or too small");
  }
}

Vec3 selection_centroid(const GaussianScene& scene, const std::vector<bool>& mask) {
  Vec3 sum;
  size_t n = 0;
  for (size_t i = 0; i < scene.size() && i < mask.size(); ++i)
    if (mask[i]) {
      sum += scene.position(i);
      ++n;
    }
  return n ? sum / double(n) : Vec3{};
}

}  // namespace isegman::edit
