#include "server/edit_state.h"

#include <algorithm>
#include <cmath>
#include <mutex>

#include "core/selection.h"
#include "edit/selection_tools.h"
#include "io/gaussian_file.h"
#include "io/ply.h"
#include "server/app_error.h"

namespace isegman::server {

namespace {

// Tints the selection's coverage magenta (it stands out on any object colour) at `tint`
// (0..1, the page's highlight opacity) and draws its outline at twice that, so a low
// opacity leaves edit results (a recolour) visible.
void highlight(Image& color, const Image& coverage, float tint_opacity) {
  const float tint[3] = {1.f, 0.2f, 0.8f};
  const float edge = std::min(1.f, 2 * tint_opacity);
  const int w = color.width, h = color.height;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float c = std::clamp(coverage.at(x, y), 0.f, 1.f);
      if (c <= 0.f) continue;
      const float a = tint_opacity * c;
      for (int k = 0; k < 3; ++k) color.at(x, y, k) = color.at(x, y, k) * (1 - a) + tint[k] * a;
    }
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      if (coverage.at(x, y) <= 0.5f) continue;
      if (coverage.at(x - 1, y) <= 0.5f || coverage.at(x + 1, y) <= 0.5f || coverage.at(x, y - 1) <= 0.5f ||
          coverage.at(x, y + 1) <= 0.5f)
        for (int k = 0; k < 3; ++k) color.at(x, y, k) = color.at(x, y, k) * (1 - edge) + tint[k] * edge;
    }
}

size_t count_selected(const std::vector<bool>& mask) { return size_t(std::count(mask.begin(), mask.end(), true)); }

}  // namespace

const char* step_kind_name(StepKind kind) {
  switch (kind) {
    case StepKind::kClick: return "click";
    case StepKind::kEdit: return "edit";
    case StepKind::kSelect: return "select";
  }
  return "edit";
}

EditState::EditState(GaussianScene scene) : session_(std::move(scene)) {}

GaussianScene EditState::scene_copy(uint64_t& fingerprint) const {
  std::shared_lock<std::shared_mutex> lock(mu_);
  fingerprint = session_.fingerprint();
  return session_.scene();
}

uint64_t EditState::fingerprint() const {
  std::shared_lock<std::shared_mutex> lock(mu_);
  return session_.fingerprint();
}

void EditState::bounds(Vec3& lo, Vec3& hi, int& sh_degree) const {
  std::shared_lock<std::shared_mutex> lock(mu_);
  session_.scene().bounds(lo, hi);
  sh_degree = session_.scene().sh_degree;
}

RobustBounds EditState::robust_bounds() const {
  std::shared_lock<std::shared_mutex> lock(mu_);
  return isegman::robust_bounds(session_.scene());
}

EditStatus EditState::status() const {
  std::shared_lock<std::shared_mutex> lock(mu_);
  EditStatus s;
  s.gaussians = session_.scene().size();
  s.selected = count_selected(session_.mask());
  s.can_undo = session_.history().can_undo();
  s.can_redo = session_.history().can_redo();
  s.undo_steps = session_.history().undo_steps();
  s.redo_steps = session_.history().redo_steps();
  s.notice = session_.notice();
  s.revision = revision_.load();
  s.fingerprint = session_.fingerprint();
  s.history = timeline_;
  return s;
}

EditResult EditState::result(const std::string& label, const std::vector<std::string>& notes) const {
  return {label, notes, session_.notice(), session_.scene().size(), count_selected(session_.mask())};
}

void EditState::record(StepKind kind, const std::string& label) {
  // A new step drops the redo tail (History::push did the same), then the entries follow
  // the history's cap: steps it dropped from the front are dropped here too.
  timeline_.entries.resize(timeline_.cursor);
  timeline_.entries.push_back({kind, label, session_.fingerprint()});
  timeline_.cursor = timeline_.entries.size();
  const size_t kept = session_.history().undo_steps();
  if (timeline_.cursor > kept) {
    const size_t drop = timeline_.cursor - kept;
    timeline_.entries.erase(timeline_.entries.begin(), timeline_.entries.begin() + long(drop));
    timeline_.cursor = kept;
  }
}

EditResult EditState::select(const edit::SelectOp& op) {
  std::unique_lock<std::shared_mutex> lock(mu_);
  edit::SelectOutcome next;
  try {
    next = edit::run_select(session_.scene(), session_.selection(), op);
  } catch (const AppError&) {
    throw;
  } catch (const Error& e) {
    invalid(e.what());
  }
  session_.select(next.selection, next.label);
  record(StepKind::kSelect, next.label);
  ++revision_;
  EditResult out = result(next.label, {});
  out.kind = StepKind::kSelect;
  return out;
}

bool EditState::select_from_segmentation(const std::vector<bool>& mask, uint64_t fingerprint,
                                         const std::string& label, StepKind kind) {
  std::unique_lock<std::shared_mutex> lock(mu_);
  if (fingerprint != session_.fingerprint()) return false;
  session_.select(Selection::from_mask(session_.scene(), mask, fingerprint), label);
  record(kind, label);
  ++revision_;
  return true;
}

EditResult EditState::edit(const edit::EditOp& op, const GaussianScene* other) {
  if (op.kind == edit::EditKind::kCombine && op.direction == edit::CombineDirection::kInto)
    invalid("combine: the web app inserts another scene into this one (from), not into another");
  std::unique_lock<std::shared_mutex> lock(mu_);
  const bool inserts = op.kind == edit::EditKind::kCombine;
  if (!inserts && session_.selection().empty())
    conflict("nothing is selected: click an object or use a selection tool first");
  edit::EditOutcome out;
  try {
    out = edit::apply_edit(session_, op, other);
  } catch (const AppError&) {
    throw;
  } catch (const Error& e) {
    invalid(e.what());
  }
  changed();
  record(StepKind::kEdit, out.label);
  return result(out.label, out.notes);
}

namespace {

void check_filter(const TimelineEntry& e, StepFilter filter, const char* verb) {
  if (filter == StepFilter::kClick && e.kind != StepKind::kClick)
    conflict(std::string("the step to ") + verb + " is not a click ('" + e.label + "'): use /api/" + verb);
  if (filter == StepFilter::kNotClick && e.kind == StepKind::kClick)
    conflict(std::string("the step to ") + verb + " is a click ('" + e.label + "'): use /api/" + verb);
}

}  // namespace

EditResult EditState::undo(StepFilter filter) {
  std::unique_lock<std::shared_mutex> lock(mu_);
  if (timeline_.cursor == 0 || !session_.history().can_undo())
    conflict(filter == StepFilter::kClick ? "no click to undo" : filter == StepFilter::kNotClick ? "no edit to undo" : "nothing to undo");
  const TimelineEntry entry = timeline_.entries[timeline_.cursor - 1];
  check_filter(entry, filter, "undo");
  const std::string label = session_.undo();
  --timeline_.cursor;
  changed();
  EditResult r = result(label, {});
  r.kind = entry.kind;
  r.fingerprint = entry.fingerprint;
  return r;
}

EditResult EditState::redo(StepFilter filter) {
  std::unique_lock<std::shared_mutex> lock(mu_);
  if (timeline_.cursor >= timeline_.entries.size() || !session_.history().can_redo())
    conflict(filter == StepFilter::kClick ? "no click to redo" : filter == StepFilter::kNotClick ? "no edit to redo" : "nothing to redo");
  const TimelineEntry entry = timeline_.entries[timeline_.cursor];
  check_filter(entry, filter, "redo");
  const std::string label = session_.redo();
  ++timeline_.cursor;
  changed();
  EditResult r = result(label, {});
  r.kind = entry.kind;
  r.fingerprint = entry.fingerprint;
  return r;
}

SelectionBounds EditState::selection_bounds() const {
  std::shared_lock<std::shared_mutex> lock(mu_);
  const GaussianScene& g = session_.scene();
  const auto& mask = session_.mask();
  SelectionBounds b;
  b.of_selection = std::find(mask.begin(), mask.end(), true) != mask.end();
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300}, sum{0, 0, 0};
  size_t n = 0;
  for (size_t i = 0; i < g.size(); ++i) {
    if (b.of_selection && !mask[i]) continue;
    const Vec3 p = g.position(i);
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
    sum += p;
    ++n;
  }
  const Vec3 c = sum / double(std::max<size_t>(n, 1));
  double r = 0;
  for (size_t i = 0; i < g.size(); ++i) {
    if (b.of_selection && !mask[i]) continue;
    const Vec3 d = g.position(i) - c;
    r = std::max(r, std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z));
  }
  b.count = n;
  b.lo = lo;
  b.hi = hi;
  b.center = c;
  b.radius = r;
  return b;
}

Image EditState::render(const Camera& camera, const RenderSettings& settings, float tint,
                        const std::vector<bool>* hidden) const {
  RenderOutput out;
  {
    std::shared_lock<std::shared_mutex> lock(mu_);
    const bool hides = hidden && hidden->size() == session_.scene().size();
    std::vector<bool> mask = session_.mask();
    GaussianScene shown;
    if (hides) {
      std::vector<bool> keep(mask.size());
      std::vector<bool> kept_mask;
      for (size_t i = 0; i < mask.size(); ++i) {
        keep[i] = !(*hidden)[i];
        if (keep[i]) kept_mask.push_back(mask[i]);
      }
      shown = session_.scene().subset(keep);
      mask = std::move(kept_mask);
    }
    std::vector<float> values;
    if (tint > 0 && std::find(mask.begin(), mask.end(), true) != mask.end()) {
      values.resize(mask.size());
      for (size_t i = 0; i < mask.size(); ++i) values[i] = mask[i] ? 1.f : 0.f;
    }
    out = isegman::render(hides ? shown : session_.scene(), camera, settings, values.empty() ? nullptr : &values);
  }
  if (!out.value.empty()) highlight(out.color, out.value, tint);
  return std::move(out.color);
}

std::vector<uint8_t> EditState::serialize(edit::SceneFormat format) const {
  std::shared_lock<std::shared_mutex> lock(mu_);
  try {
    return serialize_gaussians(session_.scene(), format);
  } catch (const Error& e) {
    conflict(e.what());
  }
}

size_t EditState::write(const std::string& path, const std::vector<std::string>& inputs,
                        std::vector<std::string>* notes) const {
  std::shared_lock<std::shared_mutex> lock(mu_);
  try {
    edit::write_scene_file(path, session_.scene(), inputs, notes);
  } catch (const Error& e) {
    invalid(e.what());
  }
  return session_.scene().size();
}

}  // namespace isegman::server
