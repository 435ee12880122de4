#include "edit/edit_op.h"

#include <cmath>

#include "core/error.h"
#include "edit/combine.h"
#include "edit/remove.h"
#include "edit/selection_tools.h"

namespace isegman::edit {

namespace {

struct KindName {
  EditKind kind;
  const char* name;
};
constexpr KindName kKinds[] = {{EditKind::kRemove, "remove"}, {EditKind::kExtract, "extract"},
                               {EditKind::kColorize, "colorize"}, {EditKind::kScale, "scale"},
                               {EditKind::kCopy, "copy"},       {EditKind::kTransform, "transform"},
                               {EditKind::kCombine, "combine"}};

bool finite(double v) { return std::isfinite(v); }

}  // namespace

std::optional<EditKind> parse_edit_kind(const std::string& word) {
  // `move` was the web API's name for `transform` before the vocabularies were merged.
  if (word == "move") return EditKind::kTransform;
  for (const KindName& k : kKinds)
    if (word == k.name) return k.kind;
  return std::nullopt;
}

const char* edit_kind_name(EditKind kind) {
  for (const KindName& k : kKinds)
    if (k.kind == kind) return k.name;
  return "?";
}

std::string edit_kind_list() {
  std::string s;
  for (const KindName& k : kKinds) s += (s.empty() ? "" : ", ") + std::string(k.name);
  return s;
}

void check_edit_op(const EditOp& op) {
  const std::string name = edit_kind_name(op.kind);
  switch (op.kind) {
    case EditKind::kColorize:
      for (double c : {op.color.r, op.color.g, op.color.b})
        if (!(finite(c) && c >= 0 && c <= 1)) throw Error(name, "colour components must be in [0, 1]");
      break;
    case EditKind::kScale:
      if (!(finite(op.factor) && op.factor > 0)) throw Error(name, "the factor must be finite and > 0");
      break;
    case EditKind::kCopy:
    case EditKind::kTransform:
      check_similarity(op.transform, name);
      break;
    case EditKind::kCombine:
      check_similarity(op.transform, name);
      if (op.other_path.empty()) throw Error(name, "no other scene given");
      break;
    default:
      break;
  }
}

CombineMode parse_combine_mode(const std::string& text) {
  if (text == "replace") return CombineMode::kReplace;
  if (text == "add") return CombineMode::kAdd;
  if (text == "subtract") return CombineMode::kSubtract;
  if (text == "intersect") return CombineMode::kIntersect;
  throw Error("mode", "expected replace, add, subtract or intersect, got '" + text.substr(0, 40) + "'");
}

const char* combine_mode_name(CombineMode mode) {
  switch (mode) {
    case CombineMode::kReplace: return "replace";
    case CombineMode::kAdd: return "add";
    case CombineMode::kSubtract: return "subtract";
    case CombineMode::kIntersect: return "intersect";
  }
  return "?";
}

Selection combine_selections(const Selection& current, const Selection& shape, CombineMode mode) {
  switch (mode) {
    case CombineMode::kReplace: return shape;
    case CombineMode::kAdd: return unite(current, shape);
    case CombineMode::kSubtract: return subtract(current, shape);
    case CombineMode::kIntersect: return intersect(current, shape);
  }
  return shape;
}

Delta plan_edit(const EditOp& op, const GaussianScene& scene, const Selection& selection,
                const GaussianScene* other) {
  check_edit_op(op);
  const std::string name = edit_kind_name(op.kind);
  const bool inserts = op.kind == EditKind::kCombine && op.direction == CombineDirection::kFrom;
  if (!inserts && selection.empty()) throw Error(name, "the selection is empty");
  switch (op.kind) {
    case EditKind::kRemove: return plan_remove(scene, selection);
    case EditKind::kExtract: return plan_extract(scene, selection);
    case EditKind::kColorize: return plan_colorize(scene, selection, op.color, op.color_mode);
    case EditKind::kScale: return plan_scale(scene, selection, op.factor);
    case EditKind::kCopy: return plan_copy(scene, selection, op.transform);
    case EditKind::kTransform: return plan_transform(scene, selection, op.transform);
    case EditKind::kCombine:
      if (!other) throw Error(name, "the other scene was not loaded");
      if (op.direction == CombineDirection::kInto)
        throw Error(name, "combine --into changes scenes: apply it with apply_edit");
      return plan_combine(scene, selection.mask, *other, Selection::all_of(*other), op.transform);
  }
  throw Error(name, "unknown operation");
}

EditOutcome apply_edit(EditSession& session, const EditOp& op, const GaussianScene* other) {
  EditOutcome out;
  out.gaussians_before = session.scene().size();
  Delta d;
  if (op.kind == EditKind::kCombine && op.direction == CombineDirection::kInto) {
    check_edit_op(op);
    if (!other) throw Error("combine", "the other scene was not loaded");
    const Selection sel = session.selection();
    if (sel.empty()) throw Error("combine", "the selection is empty");
    d = plan_combine(*other, std::vector<bool>(other->size(), false), session.scene(), sel, op.transform);
    out.gaussians_before = other->size();
    // The session continues on the other scene (its history starts here).
    session = EditSession(*other, session.history().limits());
  } else {
    d = plan_edit(op, session.scene(), session.selection(), other);
  }
  out.label = d.label.empty() ? edit_kind_name(op.kind) : d.label;
  out.notes = d.notes;
  session.apply(std::move(d));
  return out;
}

}  // namespace isegman::edit
