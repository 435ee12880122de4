#include "edit/remove.h"

#include "core/error.h"
#include "edit/checks.h"

namespace isegman::edit {

Delta plan_remove(const GaussianScene& scene, const Selection& sel) {
  check_selection(scene, sel, "remove");
  if (sel.count() == scene.size())
    throw Error("remove", "the selection holds all " + std::to_string(scene.size()) +
                              " Gaussians; removing them would leave an empty scene");
  Delta d;
  d.removed = mask_indices(sel.mask);
  d.removed_records = gather(scene, d.removed);
  d.removed_mask.assign(d.removed.size(), true);
  d.label = "remove " + std::to_string(d.removed.size()) + " Gaussians";
  return d;
}

Delta plan_extract(const GaussianScene& scene, const Selection& sel) {
  check_selection(scene, sel, "extract");
  std::vector<bool> rest(sel.mask.size());
  for (size_t i = 0; i < rest.size(); ++i) rest[i] = !sel.mask[i];
  Delta d;
  d.removed = mask_indices(rest);
  d.removed_records = gather(scene, d.removed);
  d.removed_mask.assign(d.removed.size(), false);
  d.label = "extract " + std::to_string(sel.count()) + " Gaussians (remove the other " +
            std::to_string(d.removed.size()) + ")";
  return d;
}

}  // namespace isegman::edit
