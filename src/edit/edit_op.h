// The edit vocabulary, written once: a typed EditOp (what the CLI's operation words and
// the web API's /api/edit/<name> both mean), the selection-combine modes, and running an
// op on an EditSession through the toolbox's plan_* functions and the history.
//
// One name per operation (the API's older `move` is accepted as an alias of
// `transform`). Parsing the words of a request is the caller's job (app/cmd_edit.cc for
// argv, server/api_json.cc for JSON); both fill the same EditOp, so the same request
// gives the same delta, bit for bit.
//
// Loading files is not done here: combine names its other scene by path, and the caller
// loads it (with its own path rules) and passes the Gaussians in.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/scene.h"
#include "core/selection.h"
#include "edit/colorize.h"
#include "edit/delta.h"
#include "edit/history.h"
#include "edit/transform.h"

namespace isegman::edit {

enum class EditKind { kRemove, kExtract, kColorize, kScale, kCopy, kTransform, kCombine };

// Where combine puts the Gaussians:
//   kInto: the selection S of this scene goes into the other scene, and the session
//          continues on the other scene (CLI `combine --into OTHER`).
//   kFrom: every Gaussian of the other scene is inserted into this scene and becomes
//          the selection (CLI `combine --from OTHER`, API `/api/edit/combine {path}`).
enum class CombineDirection { kInto, kFrom };

struct EditOp {
  EditKind kind = EditKind::kRemove;
  Rgb color;                                          // colorize
  ColorizeMode color_mode = ColorizeMode::kReplace;   // colorize
  double factor = 1;                                  // scale
  Similarity transform;                               // copy, transform, combine
  CombineDirection direction = CombineDirection::kFrom;  // combine
  std::string other_path;                             // combine: the other scene (loaded by the caller)
};

// "remove", "extract", "colorize", "scale", "copy", "transform" ("move" accepted),
// "combine"; nullopt for anything else.
std::optional<EditKind> parse_edit_kind(const std::string& word);
const char* edit_kind_name(EditKind kind);
// The names, for messages: "remove, extract, colorize, scale, copy, transform, combine".
std::string edit_kind_list();

// Checks parameters (finite colour in [0, 1], factor > 0, a valid similarity); throws
// Error naming the field. Parsers call it so the CLI and the API refuse the same inputs.
void check_edit_op(const EditOp& op);

// How a new shape selection meets the current one.
enum class CombineMode { kReplace, kAdd, kSubtract, kIntersect };
// "replace" / "add" / "subtract" / "intersect"; throws Error otherwise.
CombineMode parse_combine_mode(const std::string& text);
const char* combine_mode_name(CombineMode mode);
Selection combine_selections(const Selection& current, const Selection& shape, CombineMode mode);

// The delta of `op` on `scene` with selection `selection` (for combine kFrom, `other` is
// the scene whose Gaussians are inserted). Not for combine kInto, which changes scenes:
// use apply_edit. Throws Error on an empty selection (except combine kFrom) or invalid
// parameters.
Delta plan_edit(const EditOp& op, const GaussianScene& scene, const Selection& selection,
                const GaussianScene* other = nullptr);

struct EditOutcome {
  std::string label;
  std::vector<std::string> notes;
  size_t gaussians_before = 0;  // of the scene the step started from (combine kInto: the other scene)
};

// Plans and applies `op` to `session`, recording it in the history. Combine kInto
// replaces the session by one on `other` (its history starts there) holding other + S.
EditOutcome apply_edit(EditSession& session, const EditOp& op, const GaussianScene* other = nullptr);

}  // namespace isegman::edit
