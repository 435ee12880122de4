// What the page draws, apart from the scene: Gaussians hidden by "hide selection" or
// "isolate selection". A display state only: the scene, the history and exports do not
// see it. Hidden flags are per Gaussian index, so they hold while the scene keeps its
// Gaussian count (selections, colorize, scale and transform in place) and are dropped as
// soon as the count changes (remove, extract, copy, combine, or undoing one of those).
#pragma once

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

namespace isegman::server {

enum class DisplayOp { kHide, kIsolate, kShowAll };

struct DisplayResult {
  std::string label;
  size_t hidden = 0;
  uint64_t revision = 0;
};

class DisplayState {
 public:
  // Hide: the selection is hidden too. Isolate: everything but the selection is hidden
  // (what was hidden stays hidden). Show all: nothing hidden. `selection` has one flag per
  // Gaussian of the current scene; AppError(kConflict) for hide/isolate without a selection.
  DisplayResult apply(DisplayOp op, const std::vector<bool>& selection);
  // The hidden flags for a scene of `count` Gaussians; empty when nothing is hidden (or the
  // flags were made for another Gaussian count, which also forgets them).
  std::vector<bool> hidden(size_t count);
  uint64_t revision() const;

 private:
  mutable std::mutex mu_;
  std::vector<bool> hidden_;
  uint64_t revision_ = 0;
};

}  // namespace isegman::server
