// isegman edit <scene> [selection] <operation> [options] ... --out FILE: the manipulation
// toolbox on the command line (see docs/edit.md). Operations chain left to right on one
// edit session; each prints what it changed.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "app/args.h"
#include "app/command.h"
#include "core/error.h"
#include "core/output_plan.h"
#include "core/selection.h"
#include "edit/checks.h"
#include "edit/colorize.h"
#include "edit/edit_op.h"
#include "edit/history.h"
#include "edit/scene_format.h"
#include "edit/screen_selection.h"
#include "edit/select_op.h"
#include "edit/selection_tools.h"
#include "edit/transform.h"
#include "io/atomic_file.h"
#include "io/scene_loader.h"

namespace isegman::app {

// `isegman semantic` (src/app/cmd_semantic.cc) does instruction-driven editing.
int run_semantic(const std::vector<std::string>& argv);

namespace {

using namespace isegman::edit;

const char* kUsage = R"(usage: isegman edit <scene> [selection] <operation> [options] [<operation> ...] --out FILE

<scene>: a scene directory or a splat file: INRIA PLY, compressed PLY, .splat, .spz, .sog
        (the format is detected by content).
--out FILE        result, *.ply (INRIA PLY), *.compressed.ply, *.splat or *.spz; never an input
--save-selection FILE   also write the final selection (.isel)
--history-mb N    undo history cap (default 512)

Selection (before the first operation, or after `select`):
  --selection FILE          a selection file (.isel) made for this scene
  --box x0,y0,z0,x1,y1,z1   centres inside the box (repeatable: union)
  --sphere x,y,z,r          centres inside the sphere (repeatable: union)
  --outside                 the boxes/spheres select what lies outside them
  --opacity-min A / --opacity-max A   keep Gaussians with sigmoid(opacity) in range
  --size-min S / --size-max S         keep Gaussians whose largest scale is in range
  --rect CAM:x0,y0,x1,y1    centres that project into a rectangle of camera CAM's image
  --lasso CAM:x,y,x,y,...   ... into a polygon (>= 3 points)
  --brush CAM:R:x,y,...     ... into a brush stroke of radius R pixels
                            (pixels of CAM's full-size image; CAM: id or name of a
                            camera of the scene folder; repeatable: union)
  --visible                 the screen shapes take only Gaussians on the visible surface
  --opacity-min A / --opacity-max A   keep Gaussians with sigmoid(opacity) in range
  --size-min S / --size-max S         keep Gaussians whose largest scale is in range
  --similar-color C [--color-tolerance T]   keep Gaussians whose base colour is within T
                            (RGB distance, default 0.1) of C
  --grow K [--grow-radius R] [--grow-steps N]   add K nearest neighbours (within R);
                            K = 0: every neighbour within R
  --shrink K [--shrink-radius R] [--shrink-steps N]   drop Gaussians with an unselected
                            neighbour (same rule)
  --invert                  invert the final selection
  (order: file | shapes, then thresholds, then grow, shrink, then invert)

Operations (each acts on the current selection S):
  remove                    delete S
  extract                   keep only S
  colorize --color C [--mode replace|balanced]   C: '#RRGGBB' or r,g,b in [0,1]
  scale --factor E          scale S by E > 0 about its centroid
  copy [T]                  paste a transformed copy of S (the copy becomes S)
  transform [T]             move/rotate/scale S in place (`move` is accepted as an alias)
  combine --into OTHER [T]  insert S into scene OTHER; the result is OTHER + S
  combine --from OTHER [T]  insert all of scene OTHER here; the inserted Gaussians become S
  select [selection] [--combine replace|add|subtract|intersect]
  undo / redo               step back / forward in the history
  T: [--translate x,y,z] [--rotate-deg rx,ry,rz] [--scale s] [--pivot x,y,z]
     rotation about x, then y, then z (world axes), about S's centroid unless --pivot.)";

// The edit words (edit_op.h; `move` is the old alias of `transform`) and the session words.
const std::set<std::string> kOps = {"remove", "extract", "colorize", "scale", "copy", "transform", "move",
                                    "combine", "select", "undo", "redo"};
const std::set<std::string> kGlobalValue = {"out", "save-selection", "history-mb"};
const std::set<std::string> kSelectValue = {"selection", "box", "sphere", "opacity-min", "opacity-max",
                                            "size-min", "size-max", "grow", "grow-radius", "grow-steps",
                                            "shrink", "shrink-radius", "shrink-steps", "rect", "lasso", "brush",
                                            "similar-color", "color-tolerance"};
const std::set<std::string> kSelectSwitch = {"outside", "invert", "visible"};
const std::set<std::string> kTransformValue = {"translate", "rotate-deg", "scale", "pivot"};

struct Segment {
  std::string op;  // "" for the leading segment (scene + initial selection)
  std::vector<std::string> args;
};

std::set<std::string> op_value_flags(const std::string& op) {
  std::set<std::string> f;
  if (op.empty() || op == "select") {
    f = kSelectValue;
    if (op == "select") f.insert("combine");
  } else if (op == "colorize") {
    f = {"color", "mode"};
  } else if (op == "scale") {
    f = {"factor"};
  } else if (op == "copy" || op == "transform" || op == "move") {
    f = kTransformValue;
  } else if (op == "combine") {
    f = kTransformValue;
    f.insert("into");
    f.insert("from");
  }
  return f;
}

std::set<std::string> op_switch_flags(const std::string& op) {
  return (op.empty() || op == "select") ? kSelectSwitch : std::set<std::string>{};
}

bool takes_value(const std::string& token, const std::string& op) {
  if (token.size() < 3 || token.compare(0, 2, "--") != 0 || token.find('=') != std::string::npos) return false;
  const std::string name = token.substr(2);
  return kGlobalValue.count(name) || op_value_flags(op).count(name);
}

std::string fmt(const Vec3& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.4g, %.4g, %.4g)", v.x, v.y, v.z);
  return buf;
}

struct Loaded {
  GaussianScene scene;
  std::string file;  // the file the Gaussians came from
  std::vector<Camera> cameras;  // a scene folder's cameras (for the screen shapes)
};

Loaded load_any(const std::string& path) {
  Loaded l;
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    SceneLoadOptions opt;
    opt.require_cameras = false;
    SceneBundle b = load_scene(path, opt);
    l.scene = std::move(b.gaussians);
    l.file = b.ply_path;
    l.cameras = std::move(b.cameras);
  } else {
    SceneFormat f;
    std::vector<std::string> notes;
    l.scene = read_scene_file(path, &f, &notes);
    for (const auto& n : notes) std::printf("note: %s\n", n.c_str());
    l.file = path;
  }
  return l;
}

// A scene argument's files: the path itself and, for a trainer folder, its PLY and cameras.
void plan_scene_inputs(OutputPlan& plan, const std::string& path, const std::string& what) {
  plan.input(path, what);
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    plan.input(find_scene_ply(path), what + " PLY");
    plan.input((std::filesystem::path(path) / "cameras.json").string(), what + " cameras");
  }
}

Vec3 vec_arg(const Args& a, const std::string& flag, const Vec3& fallback) {
  if (!a.has(flag)) return fallback;
  std::vector<double> v = parse_numbers(a.get(flag), 3, "--" + flag);
  for (double c : v)
    if (std::fabs(c) > 1e7) throw Error("--" + flag + ": each component must be within [-1e7, 1e7], got '" + a.get(flag) + "'");
  return {v[0], v[1], v[2]};
}

Similarity similarity_from(const Args& a) {
  Similarity t;
  t.translation = vec_arg(a, "translate", {0, 0, 0});
  const Vec3 r = vec_arg(a, "rotate-deg", {0, 0, 0});
  t.rotation = rotation_from_euler_deg(r.x, r.y, r.z);
  t.scale = a.get_double("scale", 1.0);
  if (!(t.scale >= 1e-4 && t.scale <= 1e4)) throw Error("--scale " + a.get("scale") + " is outside [1e-4, 1e4]");
  if (a.has("pivot")) t.pivot = vec_arg(a, "pivot", {});
  return t;
}

// --rect CAM:x0,y0,x1,y1 / --lasso CAM:x,y,... / --brush CAM:R:x,y,... as the SelectOp the
// web API's rect / lasso / brush fill (edit/select_op.h).
SelectOp screen_op(const std::string& flag, const std::string& value, bool visible, const std::vector<Camera>& cameras) {
  const std::string what = "--" + flag;
  const size_t colon = value.find(':');
  if (colon == std::string::npos) throw Error(what + " '" + value + "': expected CAM:x,y,... (CAM: a camera id or name)");
  const std::string cam = value.substr(0, colon);
  std::string rest = value.substr(colon + 1);
  if (cameras.empty()) throw Error(what + ": the scene has no cameras (give a scene folder with cameras.json)");
  const Camera* c = find_camera(cameras, cam);
  if (!c) throw Error(what + ": no camera with id or name '" + cam + "'");
  SelectOp op;
  op.kind = SelectKind::kShape;
  op.camera = *c;
  op.shape.kind = parse_shape_kind(flag);
  op.screen.visible_only = visible;
  if (op.shape.kind == ShapeKind::kBrush) {
    const size_t c2 = rest.find(':');
    if (c2 == std::string::npos) throw Error(what + " '" + value + "': expected CAM:R:x,y,... (R: radius in pixels)");
    op.shape.radius = parse_numbers(rest.substr(0, c2), 1, what + " radius")[0];
    rest = rest.substr(c2 + 1);
  }
  const size_t commas = size_t(std::count(rest.begin(), rest.end(), ','));
  if (commas % 2 == 0) throw Error(what + ": expected an even count of coordinates x,y,x,y,...");
  const std::vector<double> v = parse_numbers(rest, int(commas + 1), what);
  for (size_t k = 0; k + 1 < v.size(); k += 2) op.shape.points.push_back({v[k], v[k + 1]});
  check_shape(op.shape);
  return op;
}

// Builds a selection from selection flags; `given` says whether any flag was present.
Selection selection_from(const Args& a, const GaussianScene& scene, const std::vector<Camera>& cameras,
                         std::vector<std::string>& inputs, bool& given) {
  given = false;
  Selection shapes = Selection::none_of(scene);
  bool have_base = false;
  if (a.has("selection")) {
    const std::string path = a.get("selection");
    Selection file = read_selection(path);
    file.check_matches(scene, path);
    file.scene_fingerprint = scene.fingerprint();  // a file saved with the legacy fingerprint joins the others
    shapes = unite(shapes, file);
    inputs.push_back(path);
    have_base = true;
  }
  Selection geo = Selection::none_of(scene);
  bool have_geo = false;
  for (const std::string& b : a.all("box")) {
    std::vector<double> v = parse_numbers(b, 6, "--box");
    geo = unite(geo, select_box(scene, {v[0], v[1], v[2]}, {v[3], v[4], v[5]}));
    have_geo = true;
  }
  for (const std::string& s : a.all("sphere")) {
    std::vector<double> v = parse_numbers(s, 4, "--sphere");
    geo = unite(geo, select_sphere(scene, {v[0], v[1], v[2]}, v[3]));
    have_geo = true;
  }
  if (a.has("outside")) {
    if (!have_geo) throw Error("--outside needs --box or --sphere");
    geo = invert(geo);
  }
  bool have_screen = false;
  for (const char* flag : {"rect", "lasso", "brush"})
    for (const std::string& v : a.all(flag)) {
      geo = unite(geo, run_select(scene, Selection::none_of(scene), screen_op(flag, v, a.has("visible"), cameras)).selection);
      have_geo = have_screen = true;
    }
  if (a.has("visible") && !have_screen) throw Error("--visible needs --rect, --lasso or --brush");
  if (have_geo) shapes = unite(shapes, geo);
  have_base |= have_geo;
  const bool thresholds = a.has("opacity-min") || a.has("opacity-max") || a.has("size-min") || a.has("size-max") ||
                          a.has("similar-color");
  Selection sel = have_base ? shapes : (thresholds ? Selection::all_of(scene) : Selection::none_of(scene));
  if (a.has("opacity-min") || a.has("opacity-max"))
    sel = intersect(sel, select_opacity(scene, a.get_double("opacity-min", 0.0), a.get_double("opacity-max", 1.0)));
  if (a.has("size-min") || a.has("size-max"))
    sel = intersect(sel, select_size(scene, a.get_double("size-min", 0.0), a.get_double("size-max", 1e30)));
  if (a.has("similar-color")) {
    const Rgb c = parse_color(a.get("similar-color"));
    sel = intersect(sel, select_similar_color(scene, {c.r, c.g, c.b}, a.get_double("color-tolerance", 0.1)));
  }
  if (a.has("grow"))
    sel = grow(scene, sel, a.get_int("grow", 8), a.get_double("grow-radius", 0.0), a.get_int("grow-steps", 1));
  if (a.has("shrink"))
    sel = shrink(scene, sel, a.get_int("shrink", 8), a.get_double("shrink-radius", 0.0), a.get_int("shrink-steps", 1));
  if (a.has("invert")) sel = invert(sel);
  given = have_base || thresholds || a.has("grow") || a.has("shrink") || a.has("invert");
  return sel;
}

// The operation words of one segment as an EditOp (edit/edit_op.h: the same type the
// web API fills, so the two cannot drift).
EditOp edit_op_from(const std::string& word, const Args& a) {
  EditOp e;
  e.kind = *parse_edit_kind(word);
  if (e.kind == EditKind::kColorize) {
    if (!a.has("color")) throw Error("colorize: --color '#RRGGBB' or r,g,b is required");
    e.color = parse_color(a.get("color"));
    e.color_mode = parse_colorize_mode(a.get("mode", "replace"));
  } else if (e.kind == EditKind::kScale) {
    if (!a.has("factor")) throw Error("scale: --factor E is required");
    e.factor = a.get_double("factor", 1.0);
    if (!(e.factor >= 1e-4 && e.factor <= 1e4)) throw Error("scale: --factor " + a.get("factor") + " is outside [1e-4, 1e4]");
  } else if (e.kind == EditKind::kCopy || e.kind == EditKind::kTransform || e.kind == EditKind::kCombine) {
    e.transform = similarity_from(a);
  }
  if (e.kind == EditKind::kCombine) {
    if (a.has("into") == a.has("from")) throw Error("combine: give either --into OTHER_SCENE or --from OTHER_SCENE");
    e.direction = a.has("into") ? CombineDirection::kInto : CombineDirection::kFrom;
    e.other_path = a.get(a.has("into") ? "into" : "from");
  }
  check_edit_op(e);
  return e;
}

void print_selection(const EditSession& e, const char* what) {
  const size_t n = e.selection().count();
  if (n == 0) {
    std::printf("  %s: nothing selected (of %zu Gaussians)\n", what, e.scene().size());
    return;
  }
  std::printf("  %s: %zu of %zu Gaussians, centroid %s\n", what, n, e.scene().size(),
              fmt(selection_centroid(e.scene(), e.mask())).c_str());
}

int run_edit(const std::vector<std::string>& argv) {
  // `edit <scene> --selection F semantic --instruction ... --out F` is the semantic tool:
  // it optimises the selection toward edited views, so it runs on its own.
  if (std::find(argv.begin(), argv.end(), "semantic") != argv.end()) {
    std::vector<std::string> rest;
    for (const std::string& t : argv) {
      if (t == "semantic") continue;
      if (kOps.count(t)) throw Error("edit: `semantic` cannot be chained with `" + t + "`; run it on its own");
      rest.push_back(t);
    }
    return run_semantic(rest);
  }
  // Split into segments at operation words (a flag's value is never an operation).
  std::vector<Segment> segs(1);
  std::vector<std::string> global;
  for (size_t i = 0; i < argv.size(); ++i) {
    const std::string& t = argv[i];
    const std::string& op = segs.back().op;
    if (kOps.count(t)) {
      segs.push_back({t, {}});
      continue;
    }
    const bool is_global = t.size() > 2 && t.compare(0, 2, "--") == 0 &&
                           kGlobalValue.count(t.substr(2, t.find('=') == std::string::npos ? std::string::npos
                                                                                            : t.find('=') - 2));
    std::vector<std::string>& dst = is_global ? global : segs.back().args;
    dst.push_back(t);
    if (takes_value(t, op) && i + 1 < argv.size()) dst.push_back(argv[++i]);
  }
  const Args g(global, kGlobalValue, {});
  if (!g.has("out")) throw Error("edit: --out FILE is required (*.ply, *.compressed.ply, *.splat or *.spz)");
  const std::string out = g.get("out");
  output_format_for(out);  // fail early on an unknown extension
  HistoryLimits limits;
  const double mb = g.get_double("history-mb", 512);
  if (!(mb >= 0 && mb < 1e7)) throw Error("--history-mb must be in [0, 1e7)");
  limits.max_bytes = size_t(mb * 1024 * 1024);

  const Args head(segs[0].args, op_value_flags(""), op_switch_flags(""));
  if (segs.size() < 2) throw Error("edit: no operation given (remove, extract, colorize, scale, copy, transform, combine, select)");
  const std::string scene_path = head.positional(0, "<scene>: a scene directory or a splat file");
  if (head.positionals().size() > 1) throw Error("edit: unexpected argument '" + head.positionals()[1] + "'");
  // Every file read (scene, selections, combine targets) against every file written,
  // before any work: no output may replace an input or the other output.
  OutputPlan plan;
  plan_scene_inputs(plan, scene_path, "scene");
  for (size_t s = 0; s < segs.size(); ++s) {
    const Args a(segs[s].args, op_value_flags(segs[s].op), op_switch_flags(segs[s].op));
    for (const std::string& f : a.all("selection")) plan.input(f, "selection file");
    for (const std::string& f : a.all("into")) plan_scene_inputs(plan, f, "combine target");
    for (const std::string& f : a.all("from")) plan_scene_inputs(plan, f, "combine source");
  }
  plan.output(out, "edited scene (--out)");
  if (g.has("save-selection")) plan.output(g.get("save-selection"), "selection (--save-selection)");
  plan.prepare();
  Loaded in = load_any(scene_path);
  std::vector<std::string> inputs{in.file, scene_path};
  refuse_overwriting_inputs(out, inputs);  // checked again at the end
  std::printf("scene %s: %zu Gaussians, SH degree %d\n", in.file.c_str(), in.scene.size(), in.scene.sh_degree);
  EditSession session(std::move(in.scene), limits);
  bool given = false;
  Selection first = selection_from(head, session.scene(), in.cameras, inputs, given);
  if (given) {
    session.select(first, "initial selection");
    print_selection(session, "selection");
  }

  for (size_t s = 1; s < segs.size(); ++s) {
    const std::string& op = segs[s].op;
    const Args a(segs[s].args, op_value_flags(op), op_switch_flags(op));
    if (!a.positionals().empty()) throw Error(op + ": unexpected argument '" + a.positionals()[0] + "'");
    std::printf("%s:\n", op.c_str());
    size_t n_before = session.scene().size();
    const bool had_selection = !session.selection().empty();
    const Vec3 c_before = selection_centroid(session.scene(), session.mask());
    if (op == "select") {
      bool any = false;
      Selection next = selection_from(a, session.scene(), in.cameras, inputs, any);
      if (!any) throw Error("select: give --selection, --box, --sphere, --rect, --lasso, --brush, a threshold, --grow, --shrink or --invert");
      const CombineMode mode = parse_combine_mode(a.get("combine", "replace"));
      session.select(combine_selections(session.selection(), next, mode),
                     std::string("select (") + combine_mode_name(mode) + ")");
    } else if (op == "undo" || op == "redo") {
      std::printf("  %s: %s\n", op == "undo" ? "undid" : "redid",
                  (op == "undo" ? session.undo() : session.redo()).c_str());
    } else {
      if (!had_selection && !(op == "combine" && a.has("from")))
        throw Error(op, "the selection is empty: give --selection, --box or --sphere (or `select ...`) first");
      const EditOp e = edit_op_from(op, a);
      std::optional<Loaded> other;
      if (e.kind == EditKind::kCombine) {
        other = load_any(e.other_path);
        inputs.push_back(other->file);
        inputs.push_back(e.other_path);
        std::printf("  %s %s: %zu Gaussians, SH degree %d\n", e.direction == CombineDirection::kInto ? "into" : "from",
                    other->file.c_str(), other->scene.size(), other->scene.sh_degree);
      }
      const EditOutcome r = apply_edit(session, e, other ? &other->scene : nullptr);
      n_before = r.gaussians_before;
      std::printf("  %s\n", r.label.c_str());
      for (const auto& n : r.notes) std::printf("  note: %s\n", n.c_str());
    }
    if (!session.notice().empty()) std::printf("  warning: %s\n", session.notice().c_str());
    const size_t n_after = session.scene().size();
    std::printf("  Gaussians: %zu -> %zu (%+lld)\n", n_before, n_after, (long long)n_after - (long long)n_before);
    if (had_selection && op != "select")
      std::printf("  centroid of the selection before: %s\n", fmt(c_before).c_str());
    print_selection(session, "selection now");
  }

  std::vector<std::string> notes;
  std::vector<uint32_t> order;  // scene index of each written Gaussian
  write_scene_file(out, session.scene(), inputs, &notes, &order);
  for (const auto& n : notes) std::printf("note: %s\n", n.c_str());
  std::printf("wrote %s (%s, %zu Gaussians, SH degree %d)\n", out.c_str(), format_name(output_format_for(out)),
              session.scene().size(), format_keeps_sh(output_format_for(out)) ? session.scene().sh_degree : 0);
  if (g.has("save-selection")) {
    const std::string sp = g.get("save-selection");
    refuse_overwriting_inputs(sp, inputs);
    // Tie the selection to the scene as written (a .splat quantises it): read it back.
    const GaussianScene written = read_scene_file(out);
    if (written.size() != session.scene().size() || order.size() != written.size())
      throw Error(out, "read back a different number of Gaussians");
    std::vector<bool> mask(written.size());
    for (size_t i = 0; i < order.size(); ++i) mask[i] = session.mask()[order[i]];
    write_selection(sp, Selection::from_mask(written, mask));
    std::printf("wrote %s (selection of %zu Gaussians)\n", sp.c_str(), session.selection().count());
  }
  return 0;
}

RegisterCommand reg("edit", "remove, recolour, scale, copy, move or combine a selection; write PLY or .splat",
                    kUsage, run_edit);

}  // namespace
}  // namespace isegman::app
