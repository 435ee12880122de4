#include "edit/delta.h"

#include <algorithm>

#include "core/error.h"

namespace isegman::edit {
namespace {

const char* kWhere = "edit history";

bool has_normals(const GaussianScene& s) { return !s.normals.empty(); }

// Records must have the scene's layout: SH degree, normals present or not, same extras.
void check_layout(const GaussianScene& scene, const GaussianScene& rec, const char* what) {
  if (rec.sh_degree != scene.sh_degree)
    throw Error(kWhere, std::string(what) + ": SH degree " + std::to_string(rec.sh_degree) +
                            " does not match the scene's " + std::to_string(scene.sh_degree));
  if (scene.size() > 0 && rec.size() > 0 && has_normals(scene) != has_normals(rec))
    throw Error(kWhere, std::string(what) + ": normals present in one of scene and records only");
  if (rec.extras.size() != scene.extras.size())
    throw Error(kWhere, std::string(what) + ": extra properties differ from the scene's");
  for (size_t e = 0; e < rec.extras.size(); ++e)
    if (rec.extras[e].name != scene.extras[e].name || rec.extras[e].size != scene.extras[e].size)
      throw Error(kWhere, std::string(what) + ": extra property '" + rec.extras[e].name + "' differs from the scene's");
}

void check_sorted_unique(const std::vector<uint32_t>& idx, size_t bound, const char* what) {
  for (size_t i = 0; i < idx.size(); ++i) {
    if (idx[i] >= bound)
      throw Error(kWhere, std::string(what) + " index " + std::to_string(idx[i]) + " is outside a scene of " +
                              std::to_string(bound) + " Gaussians");
    if (i > 0 && idx[i] <= idx[i - 1]) throw Error(kWhere, std::string(what) + " indices are not sorted and unique");
  }
}

template <typename T>
void copy_block(const std::vector<T>& src, size_t from, std::vector<T>& dst, size_t to, size_t stride) {
  std::copy(src.begin() + from * stride, src.begin() + (from + 1) * stride, dst.begin() + to * stride);
}

// Merges `rec` into `scene` so that rec's i-th Gaussian ends up at index at[i].
void insert_at(GaussianScene& scene, std::vector<bool>& mask, const std::vector<uint32_t>& at,
               const GaussianScene& rec, const std::vector<bool>& rec_mask) {
  const size_t n = scene.size(), r = rec.size(), m = n + r;
  check_sorted_unique(at, m, "reinserted");
  GaussianScene out;
  out.sh_degree = scene.sh_degree;
  const size_t k = size_t(scene.coeffs()) * 3;
  const bool normals = has_normals(scene) || (n == 0 && has_normals(rec));
  out.positions.resize(3 * m);
  if (normals) out.normals.resize(3 * m);
  out.sh.resize(k * m);
  out.opacity.resize(m);
  out.scales.resize(3 * m);
  out.rotations.resize(4 * m);
  for (const auto& e : scene.extras)
    out.extras.push_back(ExtraProperty{e.name, e.type, e.size, std::vector<uint8_t>(m * size_t(e.size))});
  std::vector<bool> out_mask(m);
  size_t ri = 0, si = 0;
  for (size_t f = 0; f < m; ++f) {
    const bool from_rec = ri < r && at[ri] == f;
    const GaussianScene& src = from_rec ? rec : scene;
    const size_t i = from_rec ? ri++ : si++;
    copy_block(src.positions, i, out.positions, f, 3);
    if (normals) {
      if (src.normals.empty()) std::fill(out.normals.begin() + 3 * f, out.normals.begin() + 3 * f + 3, 0.f);
      else copy_block(src.normals, i, out.normals, f, 3);
    }
    copy_block(src.sh, i, out.sh, f, k);
    out.opacity[f] = src.opacity[i];
    copy_block(src.scales, i, out.scales, f, 3);
    copy_block(src.rotations, i, out.rotations, f, 4);
    for (size_t e = 0; e < out.extras.size(); ++e)
      copy_block(src.extras[e].data, i, out.extras[e].data, f, size_t(out.extras[e].size));
    out_mask[f] = from_rec ? bool(rec_mask[i]) : bool(mask[i]);
  }
  scene = std::move(out);
  mask = std::move(out_mask);
}

void erase(GaussianScene& scene, std::vector<bool>& mask, const std::vector<uint32_t>& idx) {
  check_sorted_unique(idx, scene.size(), "removed");
  std::vector<bool> keep(scene.size(), true);
  for (uint32_t i : idx) keep[i] = false;
  scene = scene.subset(keep);
  std::vector<bool> m;
  m.reserve(scene.size());
  for (size_t i = 0; i < keep.size(); ++i)
    if (keep[i]) m.push_back(mask[i]);
  mask = std::move(m);
}

void truncate(GaussianScene& scene, std::vector<bool>& mask, size_t n) {
  scene.positions.resize(3 * n);
  if (!scene.normals.empty()) scene.normals.resize(3 * n);
  scene.sh.resize(n * size_t(scene.coeffs()) * 3);
  scene.opacity.resize(n);
  scene.scales.resize(3 * n);
  scene.rotations.resize(4 * n);
  for (auto& e : scene.extras) e.data.resize(n * size_t(e.size));
  mask.resize(n);
}

void flip(std::vector<bool>& mask, const std::vector<uint32_t>& idx) {
  check_sorted_unique(idx, mask.size(), "selection");
  for (uint32_t i : idx) mask[i] = !mask[i];
}

}  // namespace

size_t scene_bytes(const GaussianScene& s) {
  size_t b = 4 * (s.positions.capacity() + s.normals.capacity() + s.sh.capacity() + s.opacity.capacity() +
                  s.scales.capacity() + s.rotations.capacity());
  for (const auto& e : s.extras) b += e.data.capacity() + e.name.capacity() + e.type.capacity();
  return b;
}

size_t Delta::bytes() const {
  return sizeof(Delta) + label.capacity() + 4 * (modified.capacity() + removed.capacity() + flipped.capacity()) +
         scene_bytes(before) + scene_bytes(after) + scene_bytes(removed_records) + scene_bytes(appended) +
         (removed_mask.capacity() + appended_mask.capacity()) / 8;
}

std::vector<uint32_t> mask_indices(const std::vector<bool>& mask) {
  std::vector<uint32_t> idx;
  for (size_t i = 0; i < mask.size(); ++i)
    if (mask[i]) idx.push_back(uint32_t(i));
  return idx;
}

GaussianScene gather(const GaussianScene& scene, const std::vector<uint32_t>& idx) {
  GaussianScene out;
  out.sh_degree = scene.sh_degree;
  const size_t r = idx.size(), k = size_t(scene.coeffs()) * 3;
  out.positions.resize(3 * r);
  if (has_normals(scene)) out.normals.resize(3 * r);
  out.sh.resize(k * r);
  out.opacity.resize(r);
  out.scales.resize(3 * r);
  out.rotations.resize(4 * r);
  for (const auto& e : scene.extras)  // metadata only: never carry the scene's buffers
    out.extras.push_back(ExtraProperty{e.name, e.type, e.size, std::vector<uint8_t>(r * size_t(e.size))});
  for (size_t j = 0; j < r; ++j) {
    const size_t i = idx[j];
    if (i >= scene.size()) throw Error(kWhere, "gather index " + std::to_string(i) + " is outside the scene");
    copy_block(scene.positions, i, out.positions, j, 3);
    if (has_normals(scene)) copy_block(scene.normals, i, out.normals, j, 3);
    copy_block(scene.sh, i, out.sh, j, k);
    out.opacity[j] = scene.opacity[i];
    copy_block(scene.scales, i, out.scales, j, 3);
    copy_block(scene.rotations, i, out.rotations, j, 4);
    for (size_t e = 0; e < out.extras.size(); ++e)
      copy_block(scene.extras[e].data, i, out.extras[e].data, j, size_t(out.extras[e].size));
  }
  return out;
}

void scatter(GaussianScene& scene, const std::vector<uint32_t>& idx, const GaussianScene& rec) {
  check_layout(scene, rec, "modified records");
  if (rec.size() != idx.size()) throw Error(kWhere, "modified records and indices differ in count");
  const size_t k = size_t(scene.coeffs()) * 3;
  for (size_t j = 0; j < idx.size(); ++j) {
    const size_t i = idx[j];
    if (i >= scene.size()) throw Error(kWhere, "modified index " + std::to_string(i) + " is outside the scene");
    copy_block(rec.positions, j, scene.positions, i, 3);
    if (has_normals(scene) && has_normals(rec)) copy_block(rec.normals, j, scene.normals, i, 3);
    copy_block(rec.sh, j, scene.sh, i, k);
    scene.opacity[i] = rec.opacity[j];
    copy_block(rec.scales, j, scene.scales, i, 3);
    copy_block(rec.rotations, j, scene.rotations, i, 4);
    for (size_t e = 0; e < scene.extras.size(); ++e)
      copy_block(rec.extras[e].data, j, scene.extras[e].data, i, size_t(scene.extras[e].size));
  }
}

void append_records(GaussianScene& scene, const GaussianScene& rec) {
  check_layout(scene, rec, "appended records");
  if (rec.size() == 0) return;
  const bool scene_normals = has_normals(scene) || scene.size() == 0;
  scene.positions.insert(scene.positions.end(), rec.positions.begin(), rec.positions.end());
  if (scene_normals && has_normals(rec)) scene.normals.insert(scene.normals.end(), rec.normals.begin(), rec.normals.end());
  scene.sh.insert(scene.sh.end(), rec.sh.begin(), rec.sh.end());
  scene.opacity.insert(scene.opacity.end(), rec.opacity.begin(), rec.opacity.end());
  scene.scales.insert(scene.scales.end(), rec.scales.begin(), rec.scales.end());
  scene.rotations.insert(scene.rotations.end(), rec.rotations.begin(), rec.rotations.end());
  for (size_t e = 0; e < scene.extras.size(); ++e)
    scene.extras[e].data.insert(scene.extras[e].data.end(), rec.extras[e].data.begin(), rec.extras[e].data.end());
}

void apply_delta(const Delta& d, GaussianScene& scene, std::vector<bool>& mask) {
  if (mask.size() != scene.size()) throw Error(kWhere, "selection mask does not match the scene");
  check_sorted_unique(d.modified, scene.size(), "modified");
  if (!d.modified.empty()) scatter(scene, d.modified, d.after);
  if (!d.removed.empty()) {
    if (d.removed_records.size() != d.removed.size() || d.removed_mask.size() != d.removed.size())
      throw Error(kWhere, "removed records and indices differ in count");
    erase(scene, mask, d.removed);
  }
  if (d.appended.size() > 0) {
    if (d.appended_mask.size() != d.appended.size()) throw Error(kWhere, "appended records and flags differ in count");
    append_records(scene, d.appended);
    mask.insert(mask.end(), d.appended_mask.begin(), d.appended_mask.end());
  }
  flip(mask, d.flipped);
}

void revert_delta(const Delta& d, GaussianScene& scene, std::vector<bool>& mask) {
  if (mask.size() != scene.size()) throw Error(kWhere, "selection mask does not match the scene");
  flip(mask, d.flipped);
  if (d.appended.size() > 0) {
    if (scene.size() < d.appended.size()) throw Error(kWhere, "cannot revert an append: scene too small");
    truncate(scene, mask, scene.size() - d.appended.size());
  }
  if (!d.removed.empty()) insert_at(scene, mask, d.removed, d.removed_records, d.removed_mask);
  check_sorted_unique(d.modified, scene.size(), "modified");
  if (!d.modified.empty()) scatter(scene, d.modified, d.before);
}

}  // namespace isegman::edit
