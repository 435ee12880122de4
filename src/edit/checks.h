// Argument checks shared by every edit operation, so each one rejects bad input with
// the same clear message: an empty selection, a selection made for another scene,
// non-finite or out-of-range parameters, and non-finite results.
#pragma once

#include <string>
#include <vector>

#include "core/math.h"
#include "core/scene.h"
#include "core/selection.h"

namespace isegman::edit {

// Throws Error(op, ...) unless `selection` belongs to `scene` and selects something.
void check_selection(const GaussianScene& scene, const Selection& selection, const std::string& op);
// Throws Error(op, "<what> must be finite") for NaN/inf.
void check_finite(double value, const std::string& what, const std::string& op);
void check_finite(const Vec3& value, const std::string& what, const std::string& op);
void check_finite(const Quat& value, const std::string& what, const std::string& op);
// Throws Error(op, ...) when a produced record set holds a non-finite value.
void check_result(const GaussianScene& records, const std::string& op);

// Unweighted mean of the selected Gaussians' centres (the paper's mean(mu)).
Vec3 selection_centroid(const GaussianScene& scene, const std::vector<bool>& mask);

}  // namespace isegman::edit
