// Combination: take a selection S of a source scene A and insert it, transformed, into
// a target scene B. The inserted Gaussians take B's layout: B's SH degree (A's
// coefficients are zero-padded when A's degree is lower, truncated when higher), B's
// normals (zeros when A has none) and B's extra properties (copied when A has one of
// the same name and size, zero otherwise). The notes say which of these happened.
#pragma once

#include "core/scene.h"
#include "core/selection.h"
#include "edit/delta.h"
#include "edit/transform.h"

namespace isegman::edit {

// Converts records to `degree` (pad with zeros or truncate), returns a note or "".
std::string convert_sh_degree(GaussianScene& records, int degree);

// A delta for a session on `target` that appends S of `source`, transformed by `t`
// (pivot: S's centroid in the source unless given). The inserted Gaussians end up
// selected and the target's previous selection is cleared (`target_mask` gives it).
Delta plan_combine(const GaussianScene& target, const std::vector<bool>& target_mask, const GaussianScene& source,
                   const Selection& source_selection, const Similarity& t);

}  // namespace isegman::edit
