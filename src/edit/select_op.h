// The selection vocabulary, written once: a typed SelectOp (what `isegman edit`'s
// selection flags and the web API's /api/select/<tool> both mean) and running it on the
// current selection. Shape tools (box, sphere, screen shapes, colour, attribute ranges)
// meet the current selection by a CombineMode; grow and shrink change it; invert, clear
// and all replace it.
#pragma once

#include <optional>
#include <string>

#include "core/camera.h"
#include "core/scene.h"
#include "core/selection.h"
#include "edit/edit_op.h"
#include "edit/screen_selection.h"

namespace isegman::edit {

enum class SelectKind {
  kBox, kSphere,              // 3D shapes (centres inside)
  kShape,                     // rect / lasso / brush in a camera's image
  kColor,                     // similar base colour (the eyedropper)
  kOpacity, kSize,            // attribute ranges
  kGrow, kShrink,             // by neighbours
  kInvert, kClear, kAll,
};

struct SelectOp {
  SelectKind kind = SelectKind::kClear;
  CombineMode mode = CombineMode::kReplace;  // shape tools
  Vec3 lo, hi;                // box
  Vec3 center;                // sphere
  double radius = 0;          // sphere
  Camera camera;              // kShape, kColor with a pixel
  ScreenShape shape;          // kShape
  ScreenSelectOptions screen; // kShape: visible surface only, weight threshold
  std::optional<Vec3> color;  // kColor: the reference colour, or
  double x = 0, y = 0;        // kColor: the pixel whose top Gaussian gives it
  double tolerance = 0.1;     // kColor
  double min = 0, max = 0;    // kOpacity (activated, [0, 1]), kSize (largest axis scale, scene units)
  int k = 8;                  // kGrow/kShrink: neighbours (0: every one within `distance`)
  double distance = 0;        // kGrow/kShrink: radius in scene units (<= 0: none, k > 0 then)
  int steps = 1;              // kGrow/kShrink
};

// "box", "sphere", "rect", "lasso", "brush", "color", "opacity", "size", "grow",
// "shrink", "invert", "clear", "all" (rect/lasso/brush are kShape with that shape).
std::optional<SelectKind> parse_select_kind(const std::string& word, ShapeKind* shape = nullptr);
std::string select_kind_list();

struct SelectOutcome {
  Selection selection;  // the new current selection
  std::string label;    // e.g. "rect selection (add): 120 Gaussians"
};

// Runs `op` against `current` on `scene`; throws Error naming the field for invalid
// parameters (the CLI and the API refuse the same inputs).
SelectOutcome run_select(const GaussianScene& scene, const Selection& current, const SelectOp& op);

}  // namespace isegman::edit
