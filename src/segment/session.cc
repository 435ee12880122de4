#include "segment/session.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <numeric>

#include "core/error.h"
#include "core/parallel.h"
#include "models/onnx_graph.h"

namespace isegman::segment {

const char* status_name(ViewStatus s) {
  switch (s) {
    case ViewStatus::Accepted: return "accepted";
    case ViewStatus::NoClicks: return "no positive click reached it";
    case ViewStatus::EmptyMask: return "SAM returned an empty mask";
    case ViewStatus::NoOverlap: return "dropped by inspection: the mask misses the current selection";
    case ViewStatus::Skipped: return "skipped";
  }
  return "?";
}

namespace {
using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

Image mask_image(const std::vector<uint8_t>& m, int w, int h) {
  Image img(w, h, 1);
  for (size_t i = 0; i < m.size(); ++i) img.data[i] = m[i] ? 1.f : 0.f;
  return img;
}
}  // namespace

Session::Session(const GaussianScene& scene, std::vector<SegmentView> views,
                 std::shared_ptr<const models::SamModel> sam, SessionOptions options)
    : scene_(scene), views_(std::move(views)), sam_(std::move(sam)), options_(options) {
  if (views_.empty()) throw Error("segmentation needs at least one view");
  Vec3 lo, hi;
  scene.bounds(lo, hi);
  scene_extent_ = scene.size() ? norm(hi - lo) : 1.0;
  if (!std::isfinite(scene_extent_) || scene_extent_ <= 0) scene_extent_ = 1.0;
  state_.votes = VoteAccumulator(scene.size());
  state_.selection.assign(scene.size(), false);
  state_.views.resize(views_.size());
}

int Session::add_view(SegmentView view) {
  views_.push_back(std::move(view));
  state_.views.emplace_back();
  for (State& s : history_) s.views.emplace_back();
  return int(views_.size() - 1);
}

Image Session::selection_coverage(int view) const {
  std::vector<float> values(state_.selection.size());
  for (size_t i = 0; i < values.size(); ++i) values[i] = state_.selection[i] ? 1.f : 0.f;
  RenderSettings s;
  s.color = false;
  s.depth = false;
  s.threads = options_.threads;
  return rasterize(views_.at(size_t(view)).frame, s, &values).value;
}

RoundReport Session::click(int view, const Click& c) {
  if (view < 0 || view >= int(views_.size())) throw Error("click: no view " + std::to_string(view));
  const Camera& cam = views_[size_t(view)].camera;
  if (!(c.x >= 0 && c.y >= 0 && c.x < cam.width && c.y < cam.height))
    throw Error("click (" + std::to_string(c.x) + ", " + std::to_string(c.y) + ") is outside view '" +
                views_[size_t(view)].name + "' (" + std::to_string(cam.width) + "x" + std::to_string(cam.height) + ")");
  if (c.label != 0 && c.label != 1) throw Error("click label must be 1 (positive) or 0 (negative)");
  State next;  // run_round derives the views, votes and selection from the clicks
  next.clicks = state_.clicks;
  next.clicks.push_back({view, c});
  RoundReport report = run_round(next, state_);
  history_.push_back(std::move(state_));
  state_ = std::move(next);
  return report;
}

bool Session::undo() {
  if (history_.empty()) return false;
  state_ = std::move(history_.back());
  history_.pop_back();
  return true;
}

RoundReport Session::run_round(State& next, const State& prev) {
  RoundReport rep;
  const size_t V = views_.size();
  // 1. Propagate every click to every view (EIP).
  auto t0 = Clock::now();
  std::vector<ViewState> fresh(V);
  for (size_t k = 0; k < V; ++k) {
    for (const UserClick& uc : next.clicks) {
      if (uc.view == int(k)) {
        fresh[k].clicks.push_back(uc.click);
        continue;
      }
      Propagated p = propagate(views_[size_t(uc.view)], uc.click, views_[k], options_.propagation, scene_extent_);
      if (p.sent) fresh[k].clicks.push_back(p.click);
      else fresh[k].not_sent.push_back(p.reason);
    }
  }
  rep.ms_propagation = ms_since(t0);

  // 2. SAM in every view that has a positive click.
  t0 = Clock::now();
  std::atomic<int> segmented{0};
  // Small decoder graphs scale poorly over cores: decode several views side by side, each
  // on one core, then give the calling thread back its own thread count.
  const int workers = std::max(1, options_.sam_workers);
  struct RestoreThreads {  // the calling thread decodes too: give it its count back, even on a throw
    int n = models::threads_of_this_thread();
    ~RestoreThreads() { models::limit_threads_of_this_thread(n); }
  };
  {
    RestoreThreads restore_threads;
    parallel_for(V, workers, [&](int, size_t k) {
      if (workers > 1) models::limit_threads_of_this_thread(1);
      ViewState& vs = fresh[k];
      const bool positive = std::any_of(vs.clicks.begin(), vs.clicks.end(), [](const Click& c) { return c.label == 1; });
      if (!positive) {
        vs.status = ViewStatus::NoClicks;
        return;
      }
      vs.status = ViewStatus::Skipped;  // until inspection decides
      // Reuse last round's result when this view's clicks did not change.
      const ViewState& old = prev.views[k];
      bool same = old.clicks.size() == vs.clicks.size() && !old.low_res.empty();
      for (size_t i = 0; same && i < vs.clicks.size(); ++i)
        same = old.clicks[i].x == vs.clicks[i].x && old.clicks[i].y == vs.clicks[i].y &&
               old.clicks[i].label == vs.clicks[i].label;
      if (same) {
        vs.mask = old.mask;
        vs.mask_pixels = old.mask_pixels;
        vs.sam_score = old.sam_score;
        vs.low_res = old.low_res;
        return;
      }
      const std::vector<float>* previous =
          options_.reuse_previous_mask && !old.low_res.empty() ? &old.low_res : nullptr;
      models::SegmentResult r = sam_->decode(views_[k].embedding, vs.clicks, previous);
      ++segmented;
      vs.mask.resize(r.mask.data.size());
      vs.mask_pixels = 0;
      for (size_t i = 0; i < r.mask.data.size(); ++i) {
        vs.mask[i] = r.mask.data[i] > 0.5f;
        vs.mask_pixels += vs.mask[i];
      }
      vs.sam_score = r.score;
      vs.low_res = std::move(r.low_res_logits);
    });
  }
  rep.views_segmented = segmented;
  rep.ms_sam = ms_since(t0);

  // 3. Inspection and voting: the latest clicked view first, then the others nearest
  //    first; each mask votes only if it overlaps the selection rendered so far.
  t0 = Clock::now();
  const int anchor = next.clicks.back().view;
  std::vector<size_t> order(V);
  std::iota(order.begin(), order.end(), 0);
  const Vec3 anchor_centre = views_[size_t(anchor)].camera.center();
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    if ((a == size_t(anchor)) != (b == size_t(anchor))) return a == size_t(anchor);
    return norm(views_[a].camera.center() - anchor_centre) < norm(views_[b].camera.center() - anchor_centre);
  });
  // Votes are additive: start from the previous round's and update view by view.
  VoteAccumulator& acc = next.votes;
  acc = prev.votes;
  for (size_t k = 0; k < V; ++k)
    if (prev.views[k].status == ViewStatus::Accepted) acc.add(prev.views[k].positive, views_[k].all_votes, -1);
  bool first = true;
  std::vector<bool> current;
  for (size_t k : order) {
    ViewState& vs = fresh[k];
    if (vs.status == ViewStatus::NoClicks) continue;
    if (vs.mask_pixels == 0) {
      vs.status = ViewStatus::EmptyMask;
      ++rep.dropped;
      continue;
    }
    const SegmentView& view = views_[k];
    const Image mask = mask_image(vs.mask, view.camera.width, view.camera.height);
    const ViewState& old = prev.views[k];
    const bool inspect = !first && options_.inspection;
    const bool reuse = old.status == ViewStatus::Accepted && old.mask == vs.mask;
    std::vector<float> values;
    if (inspect) {
      current = acc.select(options_.tau, options_.min_total_weight);
      values.resize(current.size());
      for (size_t i = 0; i < values.size(); ++i) values[i] = current[i] ? 1.f : 0.f;
    }
    // One pass gives both the mask's votes and, for inspection, the selection's coverage
    // (votes of an unchanged mask are reused from the last round).
    Image coverage;
    ViewVotes positive;
    if (reuse) {
      positive = old.positive;
      if (inspect) {
        RenderSettings rs;
        rs.color = false;
        rs.depth = false;
        rs.threads = options_.threads;
        const std::vector<uint8_t> tiles = tiles_under_mask(mask, view.frame.grid_x, view.frame.grid_y);
        coverage = rasterize(view.frame, rs, &values, nullptr, &tiles).value;
      }
    } else {
      positive = masked_votes(view.frame, mask, options_.threads, inspect ? &values : nullptr,
                              inspect ? &coverage : nullptr);
    }
    if (inspect) {
      int overlap = 0;
      for (size_t i = 0; i < vs.mask.size(); ++i) overlap += vs.mask[i] && coverage.data[i] > 0.5f;
      vs.overlap = double(overlap) / vs.mask_pixels;
      vs.inspected = true;
      if (overlap == 0 || vs.overlap < options_.min_overlap) {
        vs.status = ViewStatus::NoOverlap;
        ++rep.dropped;
        continue;
      }
    }
    first = false;
    vs.positive = std::move(positive);
    acc.add(vs.positive, view.all_votes, +1);
    vs.status = ViewStatus::Accepted;
    ++rep.accepted;
  }
  next.views = std::move(fresh);
  next.selection = acc.select(options_.tau, options_.min_total_weight);
  rep.selected = size_t(std::count(next.selection.begin(), next.selection.end(), true));
  rep.ms_voting = ms_since(t0);
  return rep;
}

}  // namespace isegman::segment
