// A Delta is one undoable change of an edit state (a scene plus its selection mask),
// stored as what changed rather than as a scene copy: records of modified Gaussians
// (before and after), removed Gaussians (with their positions), appended Gaussians, and
// flipped selection flags. Memory is proportional to the Gaussians touched.
//
// Applying runs the parts in this order; reverting runs their inverses backwards:
//   1. overwrite `modified` (indices into the scene before the change) with `after`
//   2. erase `removed` (sorted indices into the scene after step 1)
//   3. append `appended` (with their selection flags)
//   4. toggle the selection flags at `flipped` (indices into the final scene)
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "core/scene.h"

namespace isegman::edit {

struct Delta {
  std::string label;                 // what the change was, e.g. "remove 812 Gaussians"
  std::vector<std::string> notes;    // things the user should know (padding, clamping)

  std::vector<uint32_t> modified;    // sorted, unique
  GaussianScene before, after;       // records of `modified`, in the same order

  std::vector<uint32_t> removed;     // sorted, unique
  GaussianScene removed_records;
  std::vector<bool> removed_mask;    // their selection flags

  GaussianScene appended;
  std::vector<bool> appended_mask;

  std::vector<uint32_t> flipped;     // sorted, unique

  bool empty() const {
    return modified.empty() && removed.empty() && appended.size() == 0 && flipped.empty();
  }
  // Heap bytes held (what the undo history pays for this step).
  size_t bytes() const;
};

// Applies / reverts a delta to `scene` and its selection `mask` (mask.size() == scene.size()).
// Throws Error when the delta does not fit the scene (an internal consistency check).
void apply_delta(const Delta& delta, GaussianScene& scene, std::vector<bool>& mask);
void revert_delta(const Delta& delta, GaussianScene& scene, std::vector<bool>& mask);

// Record primitives (every per-Gaussian array is carried: normals and extras included).
// Records of `indices` (any order) as a scene of indices.size() Gaussians.
GaussianScene gather(const GaussianScene& scene, const std::vector<uint32_t>& indices);
// Overwrites the Gaussians at `indices` with `records` (same layout required).
void scatter(GaussianScene& scene, const std::vector<uint32_t>& indices, const GaussianScene& records);
// Appends every Gaussian of `records` (same layout required).
void append_records(GaussianScene& scene, const GaussianScene& records);
// Heap bytes of a scene's arrays.
size_t scene_bytes(const GaussianScene& scene);

// Indices of the true flags of a mask.
std::vector<uint32_t> mask_indices(const std::vector<bool>& mask);

}  // namespace isegman::edit
