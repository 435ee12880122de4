#include "edit/select_op.h"

#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "edit/selection_tools.h"

namespace isegman::edit {

namespace {

struct KindName {
  const char* name;
  SelectKind kind;
  ShapeKind shape;
};
constexpr KindName kKinds[] = {
    {"box", SelectKind::kBox, ShapeKind::kRect},       {"sphere", SelectKind::kSphere, ShapeKind::kRect},
    {"rect", SelectKind::kShape, ShapeKind::kRect},    {"lasso", SelectKind::kShape, ShapeKind::kLasso},
    {"brush", SelectKind::kShape, ShapeKind::kBrush},  {"color", SelectKind::kColor, ShapeKind::kRect},
    {"opacity", SelectKind::kOpacity, ShapeKind::kRect}, {"size", SelectKind::kSize, ShapeKind::kRect},
    {"grow", SelectKind::kGrow, ShapeKind::kRect},     {"shrink", SelectKind::kShrink, ShapeKind::kRect},
    {"invert", SelectKind::kInvert, ShapeKind::kRect}, {"clear", SelectKind::kClear, ShapeKind::kRect},
    {"all", SelectKind::kAll, ShapeKind::kRect}};

std::string neighbour_rule(const SelectOp& op) {
  char buf[96];
  if (op.k > 0 && op.distance > 0) std::snprintf(buf, sizeof buf, "%d neighbours within %.4g", op.k, op.distance);
  else if (op.k > 0) std::snprintf(buf, sizeof buf, "%d neighbours", op.k);
  else std::snprintf(buf, sizeof buf, "radius %.4g", op.distance);
  std::string s = buf;
  if (op.steps > 1) s += ", " + std::to_string(op.steps) + " steps";
  return s;
}

}  // namespace

std::optional<SelectKind> parse_select_kind(const std::string& word, ShapeKind* shape) {
  for (const KindName& k : kKinds)
    if (word == k.name) {
      if (shape) *shape = k.shape;
      return k.kind;
    }
  return std::nullopt;
}

std::string select_kind_list() {
  std::string s;
  for (const KindName& k : kKinds) s += (s.empty() ? "" : ", ") + std::string(k.name);
  return s;
}

SelectOutcome run_select(const GaussianScene& scene, const Selection& current, const SelectOp& op) {
  Selection shape;  // shape tools: what the tool picked, met with `current` by op.mode
  std::string what;
  SelectOutcome out;
  switch (op.kind) {
    case SelectKind::kBox:
      shape = select_box(scene, op.lo, op.hi);
      what = "box selection";
      break;
    case SelectKind::kSphere:
      shape = select_sphere(scene, op.center, op.radius);
      what = "sphere selection";
      break;
    case SelectKind::kShape:
      shape = select_in_shape(scene, op.camera, op.shape, op.screen);
      what = std::string(shape_kind_name(op.shape.kind)) + " selection" + (op.screen.visible_only ? ", visible" : "");
      break;
    case SelectKind::kColor: {
      Vec3 ref;
      if (op.color) {
        ref = *op.color;
      } else {
        const int64_t g = gaussian_at(scene, op.camera, op.x, op.y, op.screen.render);
        if (g < 0) throw Error("eyedropper", "no Gaussian covers that pixel");
        ref = base_color(scene, size_t(g));
      }
      shape = select_similar_color(scene, ref, op.tolerance);
      char buf[96];
      std::snprintf(buf, sizeof buf, "colour selection (#%02x%02x%02x, tolerance %.3g)", int(std::lround(ref.x * 255)),
                    int(std::lround(ref.y * 255)), int(std::lround(ref.z * 255)), op.tolerance);
      what = buf;
      break;
    }
    case SelectKind::kOpacity:
      shape = select_opacity(scene, op.min, op.max);
      what = "opacity range";
      break;
    case SelectKind::kSize:
      shape = select_size(scene, op.min, op.max);
      what = "size range";
      break;
    case SelectKind::kGrow:
      out.selection = grow(scene, current, op.k, op.distance, op.steps);
      out.label = "grow selection (" + neighbour_rule(op) + ")";
      break;
    case SelectKind::kShrink:
      out.selection = shrink(scene, current, op.k, op.distance, op.steps);
      out.label = "shrink selection (" + neighbour_rule(op) + ")";
      break;
    case SelectKind::kInvert:
      out.selection = invert(current);
      out.label = "invert selection";
      break;
    case SelectKind::kClear:
      out.selection = Selection::none_of(scene);
      out.label = "clear selection";
      break;
    case SelectKind::kAll:
      out.selection = Selection::all_of(scene);
      out.label = "select all";
      break;
  }
  if (out.label.empty()) {
    out.selection = combine_selections(current, shape, op.mode);
    out.label = what + " (" + combine_mode_name(op.mode) + ")";
  }
  out.label += ": " + std::to_string(out.selection.count()) + " Gaussians";
  return out;
}

}  // namespace isegman::edit
