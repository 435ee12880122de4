#include "server/segmentation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "io/image_io.h"
#include "models/tensor_memory.h"
#include "segment/overlay.h"
#include "segment/propagation.h"
#include "segment/view_selection.h"
#include "segment/views.h"
#include "segment/voting_views.h"
#include "server/app_error.h"
#include "server/view_reuse.h"

namespace isegman::server {

namespace {

bool same_camera(const Camera& a, const Camera& b) {
  if (a.width != b.width || a.height != b.height || a.fx != b.fx || a.fy != b.fy || a.cx != b.cx || a.cy != b.cy)
    return false;
  for (int i = 0; i < 3; ++i) {
    if (a.t[i] != b.t[i]) return false;
    for (int j = 0; j < 3; ++j)
      if (a.R.m[i][j] != b.R.m[i][j]) return false;
  }
  return true;
}

// The training camera nearest a free camera that sees `point` (position relative to the
// distance to the point, then viewing direction, as the page's nearest camera); the
// nearest of all when none sees it.
int nearest_camera(const std::vector<Camera>& cameras, const Camera& free, const Vec3& point) {
  const Vec3 eye = free.center(), forward = free.R.row(2);
  const double scale = std::max(norm(point - eye), 1e-9);
  const std::vector<segment::ViewCandidate> seen = segment::score_views(cameras, -1, point);
  int best = 0, best_seeing = -1;
  double best_score = 1e300, best_seeing_score = 1e300;
  for (size_t i = 0; i < cameras.size(); ++i) {
    const double score = norm(cameras[i].center() - eye) / scale + (1 - dot(cameras[i].R.row(2), forward));
    if (score < best_score) best_score = score, best = int(i);
    if (seen[i].sees && score < best_seeing_score) best_seeing_score = score, best_seeing = int(i);
  }
  return best_seeing >= 0 ? best_seeing : best;
}

// Bytes of a scene copy's parameter arrays.
size_t scene_bytes(const GaussianScene& g) {
  size_t n = (g.positions.capacity() + g.normals.capacity() + g.sh.capacity() + g.opacity.capacity() +
              g.scales.capacity() + g.rotations.capacity()) *
             sizeof(float);
  for (const ExtraProperty& e : g.extras) n += e.data.capacity();
  return n;
}

}  // namespace

Segmentation::Segmentation(std::shared_ptr<const models::SamModel> sam, segment::SessionOptions session_options,
                           segment::ViewOptions view_options, SegmentSettings settings)
    : sam_(std::move(sam)), base_session_(session_options), view_options_(view_options), settings_(settings) {
  view_options_.use_photos = false;  // edits change the scene: segment what is rendered
}

segment::SessionOptions Segmentation::session_options() const {
  segment::SessionOptions o = base_session_;
  o.tau = settings_.tau;
  o.propagation.mode = settings_.mode;
  o.inspection = settings_.inspection;
  return o;
}

void Segmentation::keep_current() {
  if (!session_) return;
  kept_.push_back({std::move(snapshot_), fingerprint_, std::move(session_), std::move(log_), std::move(redo_),
                   std::move(free_views_)});
  if (kept_.size() > kKept) kept_.erase(kept_.begin());
  trim_cache();
  log_.clear();
  redo_.clear();
  free_views_.clear();
}

size_t Segmentation::bytes_of(const Kept& k) {
  size_t n = k.snapshot ? scene_bytes(k.snapshot->gaussians) : 0;
  if (k.session)
    for (const segment::SegmentView& v : k.session->views()) n += segment::view_bytes(v);
  return n;
}

size_t Segmentation::kept_bytes() const {
  size_t n = 0;
  for (const Kept& k : kept_) n += bytes_of(k);
  return n;
}

size_t Segmentation::spare_bytes() const {
  size_t n = 0;
  for (const segment::SegmentView& v : spare_) n += segment::view_bytes(v);
  return n;
}

void Segmentation::trim_cache() {
  while (!kept_.empty() && kept_bytes() + spare_bytes() > kept_budget_) kept_.erase(kept_.begin());
  while (!spare_.empty() && spare_bytes() > kept_budget_) spare_.erase(spare_.begin());
}

void Segmentation::set_kept_budget(size_t bytes) {
  kept_budget_ = bytes;
  trim_cache();
}

std::vector<int> Segmentation::view_cameras() const {
  std::vector<int> out;
  if (session_)
    for (const segment::SegmentView& v : session_->views()) out.push_back(v.camera_index);
  return out;
}

std::vector<uint64_t> Segmentation::kept() const {
  std::vector<uint64_t> out;
  for (const Kept& k : kept_) out.push_back(k.fingerprint);
  return out;
}

bool Segmentation::restore(uint64_t fingerprint) {
  auto it = std::find_if(kept_.begin(), kept_.end(), [&](const Kept& k) { return k.fingerprint == fingerprint; });
  if (it == kept_.end()) return false;
  Kept k = std::move(*it);
  kept_.erase(it);
  if (fingerprint_ != fingerprint) keep_current();
  snapshot_ = std::move(k.snapshot);
  fingerprint_ = k.fingerprint;
  session_ = std::move(k.session);
  log_ = std::move(k.log);
  redo_ = std::move(k.redo);
  free_views_ = std::move(k.free_views);
  return true;
}

void Segmentation::open(std::shared_ptr<const SceneBundle> snapshot, uint64_t fingerprint, const Progress& progress) {
  if (session_ && fingerprint_ != fingerprint) keep_current();
  if (restore(fingerprint)) return;
  session_.reset();
  snapshot_ = std::move(snapshot);
  fingerprint_ = fingerprint;
  log_.clear();
  redo_.clear();
  // The scene this one was edited from is the newest kept one.
  const Kept* donor = kept_.empty() ? nullptr : &kept_.back();
  rebuild(progress, donor ? donor->session.get() : nullptr, donor ? &donor->snapshot->gaussians : nullptr);
}

void Segmentation::prepare(std::shared_ptr<const SceneBundle> snapshot, uint64_t fingerprint, const Progress& progress) {
  if (prepared_for(fingerprint) || fingerprint == fingerprint_) return;
  prepared_.reset();
  Prepared p;
  p.chosen = segment::sample_views(snapshot->cameras, settings_.views_spec);
  std::vector<int> all = p.chosen;
  if (session_)
    for (const segment::SegmentView& v : session_->views())
      if (v.camera_index >= 0 && std::find(all.begin(), all.end(), v.camera_index) == all.end())
        all.push_back(v.camera_index);
  std::vector<segment::SegmentView> views =
      build_views(*snapshot, all, session_.get(), snapshot_ ? &snapshot_->gaussians : nullptr, progress, int(all.size()));
  for (size_t k = 0; k < views.size(); ++k) (k < p.chosen.size() ? p.views : p.extra).push_back(std::move(views[k]));
  p.snapshot = std::move(snapshot);
  p.fingerprint = fingerprint;
  prepared_ = std::move(p);
}

std::vector<segment::SegmentView> Segmentation::build_views(const SceneBundle& snap, const std::vector<int>& chosen,
                                                            const segment::Session* donor,
                                                            const GaussianScene* donor_scene, const Progress& progress,
                                                            int total) {
  last_reused_ = last_rebuilt_ = 0;
  std::optional<SceneDiff> diff;
  if (donor && donor_scene) diff = diff_scenes(*donor_scene, snap.gaussians);
  const RenderSettings rs = view_render_settings(view_options_);
  std::vector<segment::SegmentView> views;
  views.reserve(chosen.size());
  for (size_t k = 0; k < chosen.size(); ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    const segment::SegmentView* old = nullptr;
    if (diff)
      for (const segment::SegmentView& v : donor->views())
        if (v.camera_index == chosen[k]) old = &v;
    char line[256];
    const std::string& name = snap.cameras.at(size_t(chosen[k])).name;
    if (old && !diff_reaches_view(*donor_scene, snap.gaussians, *diff, old->camera, rs)) {
      views.push_back(reuse_view(*old, snap.gaussians, view_options_));
      ++last_reused_;
      std::snprintf(line, sizeof line, "view %zu/%zu %s: kept (the change does not reach it), %.0f ms", k + 1,
                    chosen.size(), name.c_str(),
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    } else {
      models::SamTimings t;
      views.push_back(segment::build_view(snap.gaussians, snap.cameras.at(size_t(chosen[k])), chosen[k], *sam_,
                                          view_options_, &t));
      ++last_rebuilt_;
      std::snprintf(line, sizeof line, "view %zu/%zu %s: re-rendered, %.0f ms (%s)", k + 1, chosen.size(), name.c_str(),
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count(),
                    t.from_cache ? "embedding from cache" : "embedding computed");
    }
    if (progress) progress(int(k + 1), total, line);
  }
  // Encoded: clicks only decode, so the encoder's cached activation blocks go back.
  models::trim_tensor_memory_pool();
  return views;
}

void Segmentation::rebuild(const Progress& progress, const segment::Session* donor, const GaussianScene* donor_scene) {
  session_.reset();
  free_views_.clear();
  std::vector<int> chosen = segment::sample_views(snapshot_->cameras, settings_.views_spec);
  // Cameras the logged clicks were made in are always views.
  for (const ClickRecord& c : log_)
    if (c.camera_index >= 0 && std::find(chosen.begin(), chosen.end(), c.camera_index) == chosen.end())
      chosen.push_back(c.camera_index);
  const int total = int(chosen.size()) + int(log_.size());
  std::vector<segment::SegmentView> views;
  if (prepared_for(fingerprint_) && prepared_->chosen == chosen) {
    snapshot_ = prepared_->snapshot;  // the views index its Gaussians
    views = std::move(prepared_->views);
    spare_ = std::move(prepared_->extra);
    spare_fingerprint_ = fingerprint_;
    trim_cache();  // prepared ahead of the budget
    if (progress) progress(int(chosen.size()), total, "views prepared after the edit");
  } else {
    views = build_views(*snapshot_, chosen, donor, donor_scene, progress, total);
  }
  prepared_.reset();
  int done = int(chosen.size());
  session_ = std::make_unique<segment::Session>(snapshot_->gaussians, std::move(views), sam_, session_options());
  free_views_.assign(session_->views().size(), {});
  std::vector<ClickRecord> replay = std::move(log_);
  log_.clear();
  for (const ClickRecord& c : replay) {
    try {
      click(c, nullptr);
    } catch (const AppError&) {
      // A larger or smaller mask the new settings' round does not offer: the click stays as it is.
      if (c.granularity == 0) throw;
    }
    ++done;
    if (progress) progress(done, total, "replayed click " + std::to_string(log_.size()));
  }
}

int Segmentation::view_for(const ClickRecord& c, const Progress& progress) {
  if (hidden_of(c)) return shown_view_for(c, progress);
  const auto& views = session_->views();
  if (c.camera_index >= 0) {
    for (size_t k = 0; k < views.size(); ++k)
      if (views[k].camera_index == c.camera_index) return int(k);
    if (c.camera_index >= int(snapshot_->cameras.size())) throw AppError(ErrorKind::kInvalid, "view: no camera " + std::to_string(c.camera_index));
    if (spare_fingerprint_ == fingerprint_)
      for (size_t k = 0; k < spare_.size(); ++k)
        if (spare_[k].camera_index == c.camera_index) {
          const int added = session_->add_view(std::move(spare_[k]));
          spare_.erase(spare_.begin() + long(k));
          free_views_.resize(session_->views().size());
          return added;
        }
    if (progress) progress(0, 1, "adding view " + snapshot_->cameras[size_t(c.camera_index)].name);
    const int k = session_->add_view(segment::build_view(snapshot_->gaussians, snapshot_->cameras[size_t(c.camera_index)],
                                                         c.camera_index, *sam_, view_options_));
    free_views_.resize(session_->views().size());
    return k;
  }
  if (!c.free_camera) throw AppError(ErrorKind::kInvalid, "click: neither a view nor a free camera");
  for (size_t k = 0; k < free_views_.size(); ++k)
    if (free_views_[k].camera && free_views_[k].hidden.empty() && same_camera(*free_views_[k].camera, *c.free_camera))
      return int(k);
  if (progress) progress(0, 1, "computing the free camera's view (render + SAM embedding)");
  const int k = session_->add_view(segment::build_view(snapshot_->gaussians, *c.free_camera, -1, *sam_, view_options_));
  free_views_.resize(session_->views().size());
  free_views_[size_t(k)].camera = *c.free_camera;
  return k;
}

const segment::SegmentView* Segmentation::built_view(int camera) const {
  if (session_)
    for (const segment::SegmentView& v : session_->views())
      if (v.camera_index == camera) return &v;
  if (spare_fingerprint_ == fingerprint_)
    for (const segment::SegmentView& v : spare_)
      if (v.camera_index == camera) return &v;
  return nullptr;
}

bool Segmentation::has_view_of(int camera) const { return built_view(camera) != nullptr; }

bool Segmentation::decoder_ready(int camera) const {
  const segment::SegmentView* v = built_view(camera);
  return v && models::SamModel::decoder_values_bytes(v->embedding) > 0;
}

int Segmentation::chosen_view_count() const {
  int k = 0;
  return segment::parse_auto_views(settings_.views_spec, k) && int(snapshot_->cameras.size()) > k ? k : 0;
}

bool Segmentation::prefetch_one(int camera, const Progress& progress) {
  const int k_views = chosen_view_count();
  if (!session_ || !log_.empty() || camera < 0 || camera >= int(snapshot_->cameras.size()) || k_views == 0)
    return false;
  if (spare_fingerprint_ != fingerprint_) spare_.clear();
  spare_fingerprint_ = fingerprint_;
  if (decoder_tried_fingerprint_ != fingerprint_) decoder_tried_.clear();
  decoder_tried_fingerprint_ = fingerprint_;
  const segment::SegmentView* own = built_view(camera);
  std::vector<int> wanted;
  if (own) {
    // The user clicks what they look at: a click at the centre stands in for it, and the
    // views are those such a click would choose (choose_views_for).
    // Chosen once per camera and scene: this runs again for each view it builds.
    if (ahead_camera_ != camera || ahead_fingerprint_ != fingerprint_) {
      const Camera& vc = own->camera;
      const Click centre{vc.cx, vc.cy, 1};
      bool surface = false;
      ahead_views_ = segment::choose_voting_views(snapshot_->gaussians, *neighbours(), snapshot_->cameras, camera, *own,
                                                  centre, *sam_, base_session_.propagation.min_alpha, k_views, &surface);
      if (!surface) ahead_views_.clear();
      ahead_camera_ = camera;
      ahead_fingerprint_ = fingerprint_;
    }
    if (ahead_views_.empty()) return false;
    wanted = ahead_views_;
  } else {
    wanted = {camera};
  }
  // One decode at the view's centre makes them; its answer is not used. Once per camera and
  // scene: a decoder that keeps nothing (or fails) is not asked again on every call.
  auto make_decoder_values = [&](const segment::SegmentView& v) {
    decoder_tried_.insert(v.camera_index);
    sam_->decode(v.embedding, {models::Click{v.camera.cx, v.camera.cy, 1}});
  };
  for (const int c : wanted) {
    if (const segment::SegmentView* v = built_view(c)) {
      if (decoder_tried_.count(c) || models::SamModel::decoder_values_bytes(v->embedding) > 0) continue;
      make_decoder_values(*v);
      return true;
    }
    // Room for one more view (estimated as the size of a built one) without evicting any.
    const size_t one = session_->views().empty() ? 0 : segment::view_bytes(session_->views().front());
    if (kept_bytes() + spare_bytes() + one > kept_budget_) return false;
    const std::string& name = snapshot_->cameras[size_t(c)].name;
    if (progress) progress(0, 1, "building ahead the view " + name + " (likely used by a click in " +
                                     snapshot_->cameras[size_t(camera)].name + ")");
    spare_.push_back(segment::build_view(snapshot_->gaussians, snapshot_->cameras[size_t(c)], c, *sam_, view_options_));
    make_decoder_values(spare_.back());
    return true;
  }
  // All built: the encoder's cached activation blocks go back (kept while building on).
  models::trim_tensor_memory_pool();
  return false;
}

const std::shared_ptr<const CentreIndex>& Segmentation::neighbours() {
  if (!neighbours_ || neighbours_of_.lock() != snapshot_) {
    neighbours_ = std::make_shared<const CentreIndex>(snapshot_->gaussians);
    neighbours_of_ = snapshot_;
  }
  return neighbours_;
}

bool Segmentation::choose_views_for(const ClickRecord& c, const Progress& progress) {
  const int k_views = chosen_view_count();
  if ((c.camera_index < 0 && !c.free_camera) || hidden_of(c) || !session_->clicks().empty() || k_views == 0)
    return false;
  const int k = view_for(c, progress);
  const segment::SegmentView& clicked = session_->views()[size_t(k)];
  const Camera& full = c.free_camera ? *c.free_camera : snapshot_->cameras.at(size_t(c.camera_index));
  const Click at = rescaled(c.click, full.width, full.height, clicked.camera.width, clicked.camera.height);
  Vec3 point;
  if (!segment::surface_point(clicked, at.x, at.y, base_session_.propagation.min_alpha, point)) return false;
  // A free camera's views are chosen around the training camera nearest it.
  const int anchor = c.free_camera ? nearest_camera(snapshot_->cameras, *c.free_camera, point) : c.camera_index;
  std::vector<int> chosen = segment::choose_voting_views(snapshot_->gaussians, *neighbours(), snapshot_->cameras, anchor,
                                                        clicked, at, *sam_, base_session_.propagation.min_alpha, k_views);
  std::vector<int> have;
  for (const int camera : view_cameras())
    if (camera >= 0) have.push_back(camera);
  std::sort(have.begin(), have.end());
  if (have == chosen) {
    session_->share_neighbours(neighbours());  // not a second index of the same scene
    return false;
  }
  // Every built view of this scene is a candidate: the session's and the spare ones. The
  // missing ones are built first, so a failure leaves the session as it was.
  if (spare_fingerprint_ != fingerprint_) spare_.clear();
  spare_fingerprint_ = fingerprint_;
  std::vector<segment::SegmentView> fresh;
  for (size_t i = 0; i < chosen.size(); ++i) {
    if (has_view_of(chosen[i])) continue;
    const std::string& name = snapshot_->cameras[size_t(chosen[i])].name;
    if (progress) progress(int(i), int(chosen.size()), "view " + name + " sees the clicked point: render + SAM embedding");
    fresh.push_back(segment::build_view(snapshot_->gaussians, snapshot_->cameras[size_t(chosen[i])], chosen[i], *sam_,
                                        view_options_));
  }
  models::trim_tensor_memory_pool();
  std::vector<segment::SegmentView> pool = session_->take_views();
  session_.reset();
  // Views added for clicks (free cameras, renders without hidden Gaussians) stay, after the chosen ones.
  std::vector<segment::SegmentView> added_views;
  std::vector<AddedView> added;
  for (size_t i = 0; i < pool.size(); ++i)
    if (i < free_views_.size() && free_views_[i].camera) {
      added_views.push_back(std::move(pool[i]));
      added.push_back(std::move(free_views_[i]));
      pool[i].camera_index = -1;  // moved from: not a spare
    }
  for (segment::SegmentView& v : spare_) pool.push_back(std::move(v));
  for (segment::SegmentView& v : fresh) pool.push_back(std::move(v));
  spare_.clear();
  std::vector<segment::SegmentView> views;
  for (const int camera : chosen) {
    auto it = std::find_if(pool.begin(), pool.end(), [&](const segment::SegmentView& v) { return v.camera_index == camera; });
    views.push_back(std::move(*it));  // present: built above or before
    pool.erase(it);
  }
  for (segment::SegmentView& v : pool)
    if (v.camera_index >= 0) spare_.push_back(std::move(v));  // a later click elsewhere may need them
  trim_cache();
  free_views_.assign(views.size(), {});
  for (size_t i = 0; i < added_views.size(); ++i) {
    views.push_back(std::move(added_views[i]));
    free_views_.push_back(std::move(added[i]));
  }
  session_ = std::make_unique<segment::Session>(snapshot_->gaussians, std::move(views), sam_, session_options());
  session_->share_neighbours(neighbours());
  return true;
}

const std::vector<bool>* Segmentation::hidden_of(const ClickRecord& c) const {
  if (c.hidden.size() != snapshot_->gaussians.size()) return nullptr;
  return std::find(c.hidden.begin(), c.hidden.end(), true) != c.hidden.end() ? &c.hidden : nullptr;
}

int Segmentation::shown_view_for(const ClickRecord& c, const Progress& progress) {
  const Camera& cam = c.free_camera ? *c.free_camera : snapshot_->cameras.at(size_t(c.camera_index));
  for (size_t k = 0; k < free_views_.size(); ++k)
    if (free_views_[k].camera && free_views_[k].hidden == c.hidden && same_camera(*free_views_[k].camera, cam))
      return int(k);
  if (progress) progress(0, 1, "rendering the clicked view without the hidden Gaussians (render + SAM embedding)");
  // Same indices as the snapshot (the session's votes index it); a hidden Gaussian's alpha
  // is ~1e-13, far under the rasteriser's 1/255 cut, so it neither shows nor gets a vote.
  GaussianScene shown = snapshot_->gaussians;
  for (size_t i = 0; i < c.hidden.size(); ++i)
    if (c.hidden[i]) shown.opacity[i] = -30.f;
  segment::SegmentView view = segment::build_view(shown, cam, -1, *sam_, view_options_);
  view.name = (c.free_camera ? std::string("free") : cam.name) + "_shown";
  const int k = session_->add_view(std::move(view));
  free_views_.resize(session_->views().size());
  free_views_[size_t(k)] = {cam, c.hidden};
  return k;
}

segment::RoundReport Segmentation::step_granularity(int step, const Progress& progress) {
  if (!session_) throw AppError(ErrorKind::kConflict, "segmentation is not ready");
  if (step == 0) throw AppError(ErrorKind::kInvalid, "granularity: the step must be +1 (larger) or -1 (smaller)");
  if (log_.empty() || session_->clicks().empty()) throw AppError(ErrorKind::kConflict, "no click to make larger or smaller");
  if (session_->clicks().back().click.label != 1)
    throw AppError(ErrorKind::kConflict, "the last click is negative: only a positive click's mask grows or shrinks");
  if (progress) progress(0, 1, std::string("segmenting: the clicked view's ") + (step > 0 ? "larger" : "smaller") + " mask");
  ClickRecord c = log_.back();  // the click it changes: its camera and hidden Gaussians
  c.granularity = step > 0 ? 1 : -1;
  const std::vector<bool>* hidden = hidden_of(c);
  session_->set_excluded(hidden ? *hidden : std::vector<bool>{});
  segment::RoundReport r = session_->change_granularity(c.granularity);
  if (r.no_granularity)
    throw AppError(ErrorKind::kConflict, std::string("SAM has no ") + (step > 0 ? "larger" : "smaller") +
                                             " mask holding the last click in its view");
  log_.push_back(std::move(c));
  return r;
}

segment::RoundReport Segmentation::click(const ClickRecord& c, const Progress& progress) {
  if (!session_) throw AppError(ErrorKind::kConflict, "segmentation is not ready");
  if (c.granularity != 0) return step_granularity(c.granularity, progress);  // redone or replayed
  const Camera& full = c.free_camera ? *c.free_camera : snapshot_->cameras.at(size_t(c.camera_index));
  if (!(c.click.x >= 0 && c.click.x < full.width && c.click.y >= 0 && c.click.y < full.height))
    throw AppError(ErrorKind::kInvalid, "click: x and y must lie in the camera's image");
  if (log_.empty()) choose_views_for(c, progress);
  const int k = view_for(c, progress);
  // The view works at a lower resolution: continuous coordinates just scale.
  const Camera& work = session_->views()[size_t(k)].camera;
  if (progress) progress(0, 1, "segmenting: propagation, SAM, inspection, voting");
  const std::vector<bool>* hidden = hidden_of(c);
  session_->set_excluded(hidden ? *hidden : std::vector<bool>{});
  segment::RoundReport r = session_->click(k, rescaled(c.click, full.width, full.height, work.width, work.height));
  if (!r.duplicate) log_.push_back(c);  // the same click again is no click: the log follows the session's history
  return r;
}

void Segmentation::undo() {
  if (!session_ || log_.empty() || !session_->undo()) throw AppError(ErrorKind::kConflict, "no click to undo");
  redo_.push_back(log_.back());
  log_.pop_back();
}

void Segmentation::redo(const Progress& progress) {
  if (redo_.empty()) throw AppError(ErrorKind::kConflict, "no click to redo");
  ClickRecord c = redo_.back();
  redo_.pop_back();
  std::vector<ClickRecord> keep = std::move(redo_);
  click(c, progress);
  redo_ = std::move(keep);
}

void Segmentation::reconfigure(const SegmentSettings& s, const Progress& progress) {
  if (!snapshot_) throw AppError(ErrorKind::kConflict, "segmentation is not ready");
  // Validate the view spec before dropping anything.
  segment::sample_views(snapshot_->cameras, s.views_spec);
  settings_ = s;
  kept_.clear();  // made under other settings
  prepared_.reset();
  redo_.clear();
  // Same scene, same view options: every view of the current session is still valid.
  const std::unique_ptr<segment::Session> old = std::move(session_);
  const std::shared_ptr<const SceneBundle> old_snapshot = snapshot_;
  rebuild(progress, old.get(), old_snapshot ? &old_snapshot->gaussians : nullptr);
}

const std::vector<bool>& Segmentation::selection() const {
  static const std::vector<bool> none;
  return session_ ? session_->selection() : none;
}

size_t Segmentation::selected_count() const {
  const auto& s = selection();
  return size_t(std::count(s.begin(), s.end(), true));
}

size_t Segmentation::view_count() const { return session_ ? session_->views().size() : 0; }

std::vector<ViewEvidence> Segmentation::evidence() const {
  std::vector<ViewEvidence> out;
  if (!session_) return out;
  const auto& views = session_->views();
  const auto& states = session_->view_states();
  for (size_t k = 0; k < views.size(); ++k) {
    const segment::ViewState& st = states[k];
    ViewEvidence e;
    for (const auto& c : st.clicks) (c.label ? e.positive : e.negative)++;
    e.status = "idle";
    switch (st.status) {
      case segment::ViewStatus::Accepted: e.status = "accepted"; break;
      case segment::ViewStatus::NoClicks: e.status = "no-clicks"; break;
      case segment::ViewStatus::EmptyMask: e.status = "empty-mask"; break;
      case segment::ViewStatus::NoOverlap:
      case segment::ViewStatus::NegativeInside: e.status = "dropped"; break;
      case segment::ViewStatus::Skipped: e.status = "skipped"; break;
    }
    e.index = k;
    e.name = views[k].name;
    e.camera = views[k].camera_index;
    e.status_text = segment::status_name(st.status);
    e.not_sent = st.not_sent.size();
    e.not_sent_reason = st.not_sent.empty() ? "" : st.not_sent.front();
    e.mask_pixels = st.mask_pixels;
    e.sam_score = st.sam_score;
    e.overlap = st.overlap;
    e.inspected = st.inspected;
    out.push_back(std::move(e));
  }
  return out;
}

std::vector<std::vector<uint8_t>> Segmentation::thumbnails(int side) const {
  std::vector<std::vector<uint8_t>> out;
  if (!session_) return out;
  const auto& views = session_->views();
  for (size_t k = 0; k < views.size(); ++k) {
    const bool any = selected_count() > 0;
    Image overlay = segment::make_overlay(views[k].rgb_image(), session_->view_states()[k],
                                          any ? session_->selection_coverage(int(k)) : Image());
    const double s = double(side) / std::max(overlay.width, overlay.height);
    if (s < 1)
      overlay = resize_image(overlay, std::max(1, int(std::lround(overlay.width * s))),
                             std::max(1, int(std::lround(overlay.height * s))));
    out.push_back(encode_jpeg(overlay, 85));
  }
  return out;
}

}  // namespace isegman::server
