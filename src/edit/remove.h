// Removal of a selection S, and extraction (keep only S).
#pragma once

#include "core/scene.h"
#include "core/selection.h"
#include "edit/delta.h"

namespace isegman::edit {

// Deletes S. Refuses to delete every Gaussian (the result would be no scene).
Delta plan_remove(const GaussianScene& scene, const Selection& selection);
// Deletes everything but S (S stays selected).
Delta plan_extract(const GaussianScene& scene, const Selection& selection);

}  // namespace isegman::edit
