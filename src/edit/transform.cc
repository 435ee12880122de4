#include "edit/transform.h"

#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "edit/checks.h"
#include "edit/sh_rotation.h"

namespace isegman::edit {
namespace {

std::string fmt_vec(const Vec3& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.4g, %.4g, %.4g)", v.x, v.y, v.z);
  return buf;
}

}  // namespace

Quat rotation_from_euler_deg(double rx, double ry, double rz) {
  const double k = M_PI / 180.0;
  Quat qx = Quat::from_axis_angle({1, 0, 0}, rx * k);
  Quat qy = Quat::from_axis_angle({0, 1, 0}, ry * k);
  Quat qz = Quat::from_axis_angle({0, 0, 1}, rz * k);
  return (qz * qy * qx).normalized();
}

void check_similarity(const Similarity& t, const std::string& op) {
  check_finite(t.translation, "translation", op);
  check_finite(t.rotation, "rotation", op);
  check_finite(t.scale, "scale factor", op);
  if (!(t.scale > 0)) throw Error(op, "scale factor must be > 0, got " + std::to_string(t.scale));
  if (t.pivot) check_finite(*t.pivot, "pivot", op);
}

void transform_records(GaussianScene& rec, const Similarity& t, const Vec3& pivot, const std::string& op) {
  check_similarity(t, op);
  const Quat q = t.rotation.normalized();
  const Mat3 R = q.to_matrix();
  const bool identity_rotation = q.x == 0 && q.y == 0 && q.z == 0;
  const ShRotation shr(R);
  const float log_s = float(std::log(t.scale));
  for (size_t i = 0; i < rec.size(); ++i) {
    const Vec3 p = rec.position(i);
    const Vec3 np = (R * (p - pivot)) * t.scale + pivot + t.translation;
    rec.positions[3 * i] = float(np.x);
    rec.positions[3 * i + 1] = float(np.y);
    rec.positions[3 * i + 2] = float(np.z);
    if (t.scale != 1.0)
      for (int a = 0; a < 3; ++a) rec.scales[3 * i + a] += log_s;
    if (identity_rotation) continue;
    const Quat g = q * rec.rotation(i);  // keeps the stored quaternion's norm
    rec.rotations[4 * i] = float(g.w);
    rec.rotations[4 * i + 1] = float(g.x);
    rec.rotations[4 * i + 2] = float(g.y);
    rec.rotations[4 * i + 3] = float(g.z);
    if (!rec.normals.empty()) {
      Vec3 n = R * Vec3{rec.normals[3 * i], rec.normals[3 * i + 1], rec.normals[3 * i + 2]};
      rec.normals[3 * i] = float(n.x);
      rec.normals[3 * i + 1] = float(n.y);
      rec.normals[3 * i + 2] = float(n.z);
    }
    if (rec.sh_degree > 0) shr.apply(rec.sh_degree, rec.sh_of(i));
  }
  check_result(rec, op);
}

Delta plan_scale(const GaussianScene& scene, const Selection& sel, double eps) {
  const std::string op = "scale";
  check_selection(scene, sel, op);
  check_finite(eps, "scale factor", op);
  if (!(eps > 0)) throw Error(op, "scale factor must be > 0, got " + std::to_string(eps));
  Similarity t;
  t.scale = eps;
  Delta d = plan_transform(scene, sel, t);
  char buf[64];
  std::snprintf(buf, sizeof buf, "scale %zu Gaussians by %g", d.modified.size(), eps);
  d.label = buf;
  return d;
}

Delta plan_transform(const GaussianScene& scene, const Selection& sel, const Similarity& t) {
  const std::string op = "transform";
  check_selection(scene, sel, op);
  check_similarity(t, op);
  Delta d;
  d.modified = mask_indices(sel.mask);
  d.before = gather(scene, d.modified);
  d.after = d.before;
  const Vec3 pivot = t.pivot ? *t.pivot : selection_centroid(scene, sel.mask);
  transform_records(d.after, t, pivot, op);
  d.label = "transform " + std::to_string(d.modified.size()) + " Gaussians about " + fmt_vec(pivot);
  return d;
}

Delta plan_copy(const GaussianScene& scene, const Selection& sel, const Similarity& t) {
  const std::string op = "copy";
  check_selection(scene, sel, op);
  check_similarity(t, op);
  Delta d;
  const std::vector<uint32_t> idx = mask_indices(sel.mask);
  d.appended = gather(scene, idx);
  const Vec3 pivot = t.pivot ? *t.pivot : selection_centroid(scene, sel.mask);
  transform_records(d.appended, t, pivot, op);
  d.appended_mask.assign(idx.size(), true);
  d.flipped = idx;  // the originals leave the selection: the copy is selected
  d.label = "copy " + std::to_string(idx.size()) + " Gaussians (pivot " + fmt_vec(pivot) + ")";
  return d;
}

}  // namespace isegman::edit
