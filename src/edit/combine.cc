#include "edit/combine.h"

#include <algorithm>

#include "core/error.h"
#include "edit/checks.h"

namespace isegman::edit {

std::string convert_sh_degree(GaussianScene& rec, int degree) {
  if (degree < 0 || degree > 3) throw Error("combine", "SH degree " + std::to_string(degree) + " is not in 0..3");
  const int from = rec.sh_degree;
  if (from == degree) return "";
  const size_t n = rec.size();
  const int k_from = sh_coeff_count(from), k_to = sh_coeff_count(degree), k_min = std::min(k_from, k_to);
  std::vector<float> sh(n * size_t(k_to) * 3, 0.f);
  for (size_t i = 0; i < n; ++i)
    std::copy(rec.sh.begin() + i * k_from * 3, rec.sh.begin() + i * k_from * 3 + k_min * 3,
              sh.begin() + i * k_to * 3);
  rec.sh = std::move(sh);
  rec.sh_degree = degree;
  if (from < degree)
    return "SH degree " + std::to_string(from) + " of the inserted Gaussians was padded with zeros to the target's " +
           std::to_string(degree) + " (their colour stays as it was)";
  return "SH degree " + std::to_string(from) + " of the inserted Gaussians was truncated to the target's " +
         std::to_string(degree) + " (view-dependent detail of bands " + std::to_string(degree + 1) + "-" +
         std::to_string(from) + " is lost)";
}

Delta plan_combine(const GaussianScene& target, const std::vector<bool>& target_mask, const GaussianScene& source,
                   const Selection& sel, const Similarity& t) {
  const std::string op = "combine";
  check_selection(source, sel, op);
  check_similarity(t, op);
  if (target_mask.size() != target.size()) throw Error(op, "target selection mask does not match the target scene");
  if (target.size() == 0) throw Error(op, "the target scene has no Gaussians");
  Delta d;
  const std::vector<uint32_t> idx = mask_indices(sel.mask);
  GaussianScene rec = gather(source, idx);
  const Vec3 pivot = t.pivot ? *t.pivot : selection_centroid(source, sel.mask);
  transform_records(rec, t, pivot, op);
  std::string note = convert_sh_degree(rec, target.sh_degree);
  if (!note.empty()) d.notes.push_back(note);

  // Normals follow the target.
  const bool target_normals = !target.normals.empty();
  if (target_normals && rec.normals.empty()) {
    rec.normals.assign(3 * rec.size(), 0.f);
    d.notes.push_back("the source has no normals: the inserted Gaussians get zero normals");
  } else if (!target_normals) {
    rec.normals.clear();
  }
  // Extras follow the target.
  std::vector<ExtraProperty> extras;
  for (const ExtraProperty& te : target.extras) {
    ExtraProperty e{te.name, te.type, te.size, std::vector<uint8_t>(rec.size() * size_t(te.size))};
    auto it = std::find_if(rec.extras.begin(), rec.extras.end(),
                           [&](const ExtraProperty& s) { return s.name == te.name && s.size == te.size; });
    if (it != rec.extras.end()) e.data = it->data;
    else d.notes.push_back("the source has no property '" + te.name + "': the inserted Gaussians get zeros");
    extras.push_back(std::move(e));
  }
  for (const ExtraProperty& se : rec.extras) {
    bool kept = std::any_of(target.extras.begin(), target.extras.end(),
                            [&](const ExtraProperty& te) { return te.name == se.name && te.size == se.size; });
    if (!kept) d.notes.push_back("the target has no property '" + se.name + "': it is dropped from the inserted Gaussians");
  }
  rec.extras = std::move(extras);

  d.appended = std::move(rec);
  d.appended_mask.assign(idx.size(), true);
  d.flipped = mask_indices(target_mask);  // clear the target's own selection
  d.label = "combine: insert " + std::to_string(idx.size()) + " Gaussians into a scene of " +
            std::to_string(target.size());
  return d;
}

}  // namespace isegman::edit
