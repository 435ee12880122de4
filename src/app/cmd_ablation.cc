// isegman ablation: the design choices of the segmentation measured on synthetic scenes
// whose per-Gaussian labels are known. `--set eval` (default): the evaluation set of hard
// cases (app/hard_scenes.h) with every addition beyond the paper switched off one at a
// time; `--set demo`: the demo scene with propagation modes, inspection and view sampling.
// Every object is selected from one click; the score is the IoU of the rendered selection
// against the true object in every camera that sees it.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <set>

#include "app/args.h"
#include "app/command.h"
#include "app/demo_scene.h"
#include "app/hard_scenes.h"
#include "app/segment_args.h"
#include "core/error.h"
#include "core/spatial_order.h"
#include "io/atomic_file.h"
#include "io/scene_loader.h"
#include "io/image_io.h"
#include "segment/corrective_click.h"
#include "segment/evaluation.h"
#include "segment/overlay.h"
#include "segment/pipeline.h"
#include "render/rasterizer.h"

namespace isegman::app {
namespace {

struct Config {
  std::string label;
  segment::PropagationMode mode;
  bool inspection;
  std::string views;
};

struct EvalConfig {
  std::string label;
  std::function<void(segment::SessionOptions&)> apply;
};

// One word per view status, for the per-view table beside the overlays.
const char* status_word(segment::ViewStatus s) {
  switch (s) {
    case segment::ViewStatus::Accepted: return "accepted";
    case segment::ViewStatus::NoClicks: return "no-click";
    case segment::ViewStatus::EmptyMask: return "empty";
    case segment::ViewStatus::NoOverlap: return "dropped";
    case segment::ViewStatus::Skipped: return "skipped";
    case segment::ViewStatus::NegativeInside: return "negative";
  }
  return "?";
}

int run_eval_ablation(const Args& args) {
  EvalSetOptions opt;
  opt.density = float(args.get_double("density", 1.0));
  opt.width = args.get_int("width", 480);
  opt.height = args.get_int("height", 360);
  if (!(opt.density > 0.01f && opt.density <= 50.f)) throw Error("--density must be in (0.01, 50]");
  opt.camera_factor = args.get_int("camera-factor", 1);
  if (opt.camera_factor < 1 || opt.camera_factor > 20) throw Error("--camera-factor must be between 1 and 20");
  const std::string only = args.get("only", "");
  const std::string overlays = args.get("overlays", "");
  // Clicks per synthetic task: its own click, then clicks drawn anywhere on the object
  // (task_clicks). The task's score is the mean over them.
  const int clicks_per_task = args.get_int("clicks-per-task", 1);
  if (clicks_per_task < 1 || clicks_per_task > 50) throw Error("--clicks-per-task must be between 1 and 50");
  // --second-clicks: each drawn click follows the task's own click (a second positive click
  // on the same object, as a user refines) instead of being scored alone.
  const bool second_clicks = args.has("second-clicks");
  if (second_clicks && clicks_per_task < 2) throw Error("--second-clicks needs --clicks-per-task 2 or more");
  // --corrective-clicks N: after each synthetic task's own click, up to N more as a user
  // corrects (segment/corrective_click.h): at the most interior pixel of the larger error in
  // the clicked view, positive where the selection misses the object, negative where it
  // takes something else. The task scores after its last click; rows per click count.
  const int corrective = args.get_int("corrective-clicks", 0);
  if (corrective < 0 || corrective > 20) throw Error("--corrective-clicks must be between 0 and 20");
  if (corrective > 0 && clicks_per_task > 1) throw Error("--corrective-clicks and --clicks-per-task exclude each other");
  // --granularity-choice: after each click, the user steps the clicked view's
  // granularity (Session::change_granularity) up to twice larger and twice smaller and keeps
  // the best; a row of those figures per task (the part or whole a click cannot tell apart).
  const bool granularity_choice = args.has("granularity-choice");
  if (granularity_choice && corrective > 0) throw Error("--granularity-choice and --corrective-clicks exclude each other");
  SegmentSetup setup = parse_segment_setup(args);
  auto sam = load_sam(setup);
  std::vector<EvalConfig> configs = {
      {"all additions (default)", [](segment::SessionOptions&) {}},
      {"paper: hybrid + overlap IIM", [](segment::SessionOptions& o) { o = segment::paper_pipeline(o); }},
      {"- depth layers", [](segment::SessionOptions& o) { o.depth_layers = false; }},
      {"- local depth layers", [](segment::SessionOptions& o) { o.layer_options.region = 0; }},
      {"- Gaussian depth extents", [](segment::SessionOptions& o) { o.layer_options.extent_sigmas = 0; }},
      {"- background gate", [](segment::SessionOptions& o) { o.background_gate = false; }},
      {"- see through occluders", [](segment::SessionOptions& o) { o.see_through = false; }},
      {"- neighbour coherence", [](segment::SessionOptions& o) { o.coherence = false; }},
      {"- centre evidence", [](segment::SessionOptions& o) { o.centre_rule.enabled = false; }},
      {"- agreement IIM", [](segment::SessionOptions& o) { o.agreement_inspection = false; }},
      {"+ candidate choice", [](segment::SessionOptions& o) { o.choose_candidate = true; }},
      {"- selection prompts", [](segment::SessionOptions& o) { o.selection_prompt_rounds = 0; }},
      {"- granularity consensus", [](segment::SessionOptions& o) { o.granularity_consensus = false; }},
      {"- part/whole neutral", [](segment::SessionOptions& o) { o.whole_neutral = false; }},
      {"- no hidden clicks", [](segment::SessionOptions& o) { o.propagation.hidden_fallback = true; }},
      {"- depth-consistent clicks", [](segment::SessionOptions& o) { o.propagation.depth_agreement = 0; }},
      {"- background plane", [](segment::SessionOptions& o) { o.background_options.plane = false; }},
      {"- object prior", [](segment::SessionOptions& o) { o.object_prior = false; }},
      {"- background votes against", [](segment::SessionOptions& o) { o.background_against = false; }},
      {"- surroundings' surface", [](segment::SessionOptions& o) { o.background_options.spread_scale = 0; }},
      {"- whole islands", [](segment::SessionOptions& o) { o.whole_islands.enabled = false; }},
      {"+ interior anchors", [](segment::SessionOptions& o) { o.interior_anchor.enabled = true; }},
      {"- whole-mask retry", [](segment::SessionOptions& o) { o.whole_mask_retry = false; }},
      {"- empty-selection retry", [](segment::SessionOptions& o) { o.empty_selection_retry = false; }},
      {"- grow to the selection", [](segment::SessionOptions& o) { o.grow_to_selection = false; }},
      {"- part growth", [](segment::SessionOptions& o) { segment::disable_part_growth(o); }},
      {"- click by click", [](segment::SessionOptions& o) { o.click_by_click = false; }},
      {"- negative granularity", [](segment::SessionOptions& o) { o.negative_granularity = false; }},
      {"- negative islands", [](segment::SessionOptions& o) { o.negative_islands = false; }},
      {"- band beyond the part", [](segment::SessionOptions& o) { o.beyond_part.band = false; }},
      {"- mask beyond the part", [](segment::SessionOptions& o) { o.beyond_part.whole = false; }},
      {"- attached parts", [](segment::SessionOptions& o) { o.attached_parts.enabled = false; }},
      {"- far-behind check", [](segment::SessionOptions& o) { o.background_options.max_far_behind = 1; }},
      {"- minority granularity try", [](segment::SessionOptions& o) { o.larger_views_share = 1; }},
      {"- islands' own share", [](segment::SessionOptions& o) { o.whole_islands.min_own_share = 0; }},
      {"- nearest estimate at the clicks",
       [](segment::SessionOptions& o) { o.background_options.max_seed_radius = o.background_options.seed_radius; }},
      {"- set aside by several views", [](segment::SessionOptions& o) { o.attached_parts.min_set_aside_views = 1; }},
      {"- apart islands", [](segment::SessionOptions& o) { o.apart.enabled = false; }},
      {"- seen behind the gaps", [](segment::SessionOptions& o) { o.apart.behind = false; }},
      {"- selection open beyond a part", [](segment::SessionOptions& o) { o.part_leaves_selection_open = false; }},
      {"- behind the clicked surface", [](segment::SessionOptions& o) { o.apart.behind_click_gap = 0; }},
      {"- pieces near what left", [](segment::SessionOptions& o) { o.apart.nearest_follow = false; }},
      {"- wide views vouch for parts", [](segment::SessionOptions& o) { o.attached_parts.min_view_overlap = 0; }},
      {"- enclosures seen through", [](segment::SessionOptions& o) {
         o.see_through_options.min_peeled_share = 0;
         o.consensus_on_peeled = true;
       }},
      {"- selection not peeled", [](segment::SessionOptions& o) { o.see_through_options.max_selection_peeled = 1.01; }},
      {"- negative clicks only remove", [](segment::SessionOptions& o) { o.negative_only_removes = false; }},
      {"- negative clicks one by one", [](segment::SessionOptions& o) { o.negatives_one_by_one = false; }},
      {"- no cut through the scene", [](segment::SessionOptions& o) { o.see_through_options.max_peeled_view_share = 1; }},
      {"- uncertain object", [](segment::SessionOptions& o) { o.min_uncertain_object_score = 2; }},
      {"- tiny part steps up", [](segment::SessionOptions& o) { o.tiny_step_up.enabled = false; }},
  };
  const std::string which = args.get("configs", "");
  if (!which.empty()) {  // a comma list of row numbers (0 = default)
    std::vector<EvalConfig> picked;
    size_t pos = 0;
    while (pos <= which.size()) {
      const size_t end = std::min(which.find(',', pos), which.size());
      const int k = std::stoi(which.substr(pos, end - pos));
      if (k < 0 || k >= int(configs.size())) throw Error("--configs: no configuration " + std::to_string(k));
      picked.push_back(configs[size_t(k)]);
      pos = end + 1;
    }
    configs = picked;
  }
  const std::vector<EvalScene> scenes = make_eval_scenes(opt);
  std::vector<std::pair<const EvalScene*, const EvalTaskSpec*>> tasks;
  for (const EvalScene& s : scenes)
    for (const EvalTaskSpec& t : s.tasks)
      if (only.empty() || t.name.find(only) != std::string::npos) tasks.push_back({&s, &t});
  // Tasks on the real fixture scenes (masks made by hand, eval/fixture_tasks): scored on
  // their masks; skipped with a message when the fixtures are not beside the project.
  std::vector<segment::EvalTask> fixture_tasks;
  std::map<std::string, SceneBundle> fixture_scenes;
  {
    namespace fs = std::filesystem;
    const std::string task_dir = args.get("fixture-tasks", "eval/fixture_tasks");
    const std::string fixtures = args.get("fixtures", "../shared/fixtures");
    std::error_code ec;
    if (task_dir == "none") {
    } else if (!fs::is_directory(task_dir, ec)) {
      std::printf("fixture tasks skipped: no folder %s (--fixture-tasks DIR)\n", task_dir.c_str());
    } else if (!fs::is_directory(fixtures, ec)) {
      std::printf("fixture tasks skipped: no fixtures at %s (--fixtures DIR)\n", fixtures.c_str());
    } else {
      for (auto& t : segment::find_tasks(task_dir, fixtures))
        if (only.empty() || t.name.find(only) != std::string::npos) fixture_tasks.push_back(std::move(t));
      for (const auto& t : fixture_tasks)
        if (!fixture_scenes.count(t.scene_dir)) {
          SceneBundle b = load_scene(t.scene_dir);
          put_in_space_order(b.gaussians);  // as `segment` works on it
          fixture_scenes.emplace(t.scene_dir, std::move(b));
        }
    }
  }
  if (tasks.empty() && fixture_tasks.empty()) throw Error("--only '" + only + "' matches no task");
  if (args.has("preview")) {  // the clicked view of every task: the object tinted, the click in red
    namespace fs = std::filesystem;
    const fs::path dir = args.get("preview");
    fs::create_directories(dir);
    for (const auto& [s, t] : tasks) {
      const Camera& cam = s->scene.bundle.cameras[size_t(t->camera)];
      Image rgb = render(s->scene.bundle.gaussians, cam).color;
      std::string plain = t->name;
      std::replace(plain.begin(), plain.end(), '/', '_');
      write_png((dir / (plain + "_render.png")).string(), rgb);
      const Image gt = segment::selection_mask(s->scene.bundle.gaussians, cam, demo_object_mask(s->scene, t->object),
                                               cam.width, cam.height);
      for (int y = 0; y < rgb.height; ++y)
        for (int x = 0; x < rgb.width; ++x) {
          if (gt.at(x, y) > 0.5f) rgb.at(x, y, 2) = 0.5f * rgb.at(x, y, 2) + 0.5f;
          if (std::abs(x - t->x) <= 2 && std::abs(y - t->y) <= 2) {
            rgb.at(x, y, 0) = 1;
            rgb.at(x, y, 1) = rgb.at(x, y, 2) = 0;
          }
        }
      std::string name = t->name;
      std::replace(name.begin(), name.end(), '/', '_');
      write_png((dir / (name + ".png")).string(), rgb);
    }
    std::printf("wrote %zu previews to %s\n", tasks.size(), dir.string().c_str());
    return 0;
  }
  std::printf("evaluation set: %zu tasks in %zu scenes at %dx%d, one click each; IoU %% per task (mean over the "
              "cameras that see the object)\n\n",
              tasks.size(), scenes.size(), opt.width, opt.height);
  std::printf("| task | kind | Gaussians | cameras |\n|---|---|---|---|\n");
  for (const auto& [s, t] : tasks)
    std::printf("| %s | %s | %zu | %zu |\n", t->name.c_str(), t->kind.c_str(), s->scene.bundle.gaussians.size(),
                s->scene.bundle.cameras.size());
  for (const auto& t : fixture_tasks)
    std::printf("| %s | %s (real capture, %zu hand-made masks) | %zu | %zu |\n", t.name.c_str(), t.kind.c_str(),
                t.masks.size(), fixture_scenes.at(t.scene_dir).gaussians.size(),
                fixture_scenes.at(t.scene_dir).cameras.size());
  for (const auto& t : fixture_tasks) {  // the headroom each real task leaves (evaluation.h)
    const SceneBundle& b = fixture_scenes.at(t.scene_dir);
    const segment::TaskResult r = segment::score_task(t, b, segment::mask_majority_selection(t, b));
    std::printf("%s: the Gaussians mostly inside its masks score %.1f (what any selection of whole Gaussians nears)\n",
                t.name.c_str(), 100 * r.iou);
  }
  std::printf("\n| configuration | mIoU | min | mAcc | interaction |");
  for (const auto& [s, t] : tasks) std::printf(" %s |", t->name.c_str());
  for (const auto& t : fixture_tasks) std::printf(" %s |", t.name.c_str());
  std::printf("\n|---|---|---|---|---|");
  for (size_t i = 0; i < tasks.size() + fixture_tasks.size(); ++i) std::printf("---|");
  std::printf("\n");
  std::fflush(stdout);
  // truth (synthetic tasks): the true object's Gaussians of `scene`, outlined in each view; null for real tasks.
  auto write_overlays = [&](const segment::Session& session, const std::string& name, const GaussianScene* scene,
                            const std::vector<bool>* truth) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::path(overlays) / name;
    fs::create_directories(dir);
    std::string table = "view status candidate sam_score mask_px overlap selection_inside iou prompted depth_layers background surface_offset surface_tolerance whole_px beyond_part_px\n";
    for (size_t k = 0; k < session.views().size(); ++k) {
      const segment::ViewState& v = session.view_states()[k];
      const Camera& cam = session.views()[k].camera;
      const Image truth_mask = truth ? segment::selection_mask(*scene, cam, *truth, cam.width, cam.height) : Image{};
      write_png((dir / (session.views()[k].name + ".png")).string(),
                segment::make_overlay(session.views()[k].rgb_image(), v, session.selection_coverage(int(k)), truth_mask));
      char line[256];
      std::snprintf(line, sizeof line, "%s %s %d %.3f %d %.3f %.3f %.3f %d %d %zu %.4f %.4f %d %d\n", session.views()[k].name.c_str(),
                    status_word(v.status),
                    v.candidate, v.sam_score, v.mask_pixels, v.overlap, v.selection_inside, v.iou, int(v.from_selection),
                    v.depth_layers, v.background_gaussians, v.background_offset, v.background_tolerance, v.whole_pixels,
                    v.beyond_part_pixels);
      table += line;
    }
    write_file_atomic((dir / "views.txt").string(), table);  // the per-view evidence as figures
  };
  // Each task's clicks (the same for every configuration).
  std::vector<std::vector<Click>> clicks_of;
  for (const auto& [s, t] : tasks) clicks_of.push_back(task_clicks(*s, *t, clicks_per_task));
  // Every camera of a synthetic scene votes, as in the paper, unless --views says otherwise
  // (auto: the K views segment chooses, as for a capture of many photos).
  const std::string synthetic_views = args.has("views") ? setup.views_spec : "all";
  // Each real task's prompts: its own, then single clicks drawn on its mask of the clicked
  // view, 3 px in from the outline (the masks were made on the photos, whose outlines the
  // renders follow to a pixel or two). A task without a mask of that view keeps its own.
  std::vector<std::vector<std::vector<Click>>> fixture_prompts;
  for (const auto& t : fixture_tasks) {
    std::vector<std::vector<Click>> prompts = {t.clicks};
    const auto m = std::find_if(t.masks.begin(), t.masks.end(), [&](const auto& vm) { return vm.first == t.view; });
    if (clicks_per_task > 1 && m != t.masks.end()) {
      const Image mask = read_image(m->second);
      const Camera& cam = *find_camera(fixture_scenes.at(t.scene_dir).cameras, t.view);
      const std::vector<Click> drawn = clicks_drawn_on(mask, t.name, t.clicks.front(), clicks_per_task, 3);
      for (size_t k = 1; k < drawn.size(); ++k) {
        Click c = rescaled(drawn[k], mask.width, mask.height, cam.width, cam.height);
        c = pixel_centre_click(std::floor(c.x), std::floor(c.y), 1);
        prompts.push_back(second_clicks ? std::vector<Click>{t.clicks.front(), c} : std::vector<Click>{c});
      }
    }
    if (prompts.size() > 1) {  // so that any of them can be repeated with `isegman segment`
      std::printf("%s: drawn clicks in %s:", t.name.c_str(), t.view.c_str());
      for (size_t k = 1; k < prompts.size(); ++k) std::printf(" %d,%d", int(prompts[k].back().x), int(prompts[k].back().y));
      std::printf("\n");
    }
    fixture_prompts.push_back(std::move(prompts));
  }
  if (clicks_per_task > 1)
    std::printf("each task: its own click and %d drawn on the object in its clicked view (real tasks: on its mask of "
                "that view)%s; the mean IoU over them (the rows below each configuration: the task's own click alone, "
                "the worst click)\n\n",
                clicks_per_task - 1, second_clicks ? ", each as a second click after its own" : "");
  for (size_t ci = 0; ci < configs.size(); ++ci) {
    segment::SessionOptions so = setup.session;
    configs[ci].apply(so);
    double miou = 0, macc = 0, ms = 0, worst = 1;
    std::vector<double> per, per_worst, per_own;
    std::vector<std::vector<double>> per_after(static_cast<size_t>(corrective + 1));  // [k]: after k + 1 clicks
    // One task's clicks, scored one by one (the first is its own), then its mean into the row.
    struct TaskClicks {
      double iou = 0, acc = 0, ms = 0, worst = 1;
      int n = 0;
      double granularity = 0;  // the best IoU over each click's granularities, summed
    };
    auto add_click = [&](TaskClicks& tc, double iou, double acc, double click_ms) {
      if (tc.n == 0) per_own.push_back(iou);
      tc.iou += iou;
      tc.acc += acc;
      tc.ms += click_ms;
      tc.worst = std::min(tc.worst, iou);
      ++tc.n;
    };
    // The best IoU over the click's granularities, the session left as the click made it.
    std::vector<double> per_granularity;
    auto best_granularity = [&](TaskClicks& tc, segment::Session& session, const std::function<double()>& iou) {
      double best = iou();
      for (int step : {1, -1}) {
        int taken = 0;
        for (; taken < 2 && !session.change_granularity(step).no_granularity; ++taken) best = std::max(best, iou());
        for (; taken > 0; --taken) session.undo();
      }
      tc.granularity += best;
    };
    auto close_task = [&](const TaskClicks& tc) {
      const double n = double(tc.n), iou = tc.iou / n;
      per.push_back(iou);
      per_worst.push_back(tc.worst);
      miou += iou;
      macc += tc.acc / n;
      worst = std::min(worst, iou);
      ms += tc.ms / n;
      if (granularity_choice) per_granularity.push_back(tc.granularity / n);
    };
    for (size_t ti = 0; ti < tasks.size(); ++ti) {
      const auto& [s, t] = tasks[ti];
      TaskClicks tc;
      for (size_t k = 0; k < clicks_of[ti].size(); ++k) {
        segment::PipelineTimings tm;
        std::vector<Click> clicks{clicks_of[ti][k]};
        if (second_clicks && k > 0) clicks.insert(clicks.begin(), clicks_of[ti][0]);
        auto session =
            segment::segment_from_prompts(s->scene.bundle, t->camera, clicks, sam, so, setup.views, synthetic_views, &tm);
        const std::vector<bool> truth = demo_object_mask(s->scene, t->object);
        auto score = [&] {
          return segment::score_selection(s->scene.bundle.gaussians, s->scene.bundle.cameras, truth, session->selection());
        };
        // The configuration's row reports the click itself; corrective clicks have rows of their own.
        const segment::MaskScore first = score();
        segment::MaskScore sc = first;
        if (corrective > 0) {
          const int view = segment::view_of_camera(*session, t->camera);
          // By value: a click may add a view (see_through.h), which moves the session's views.
          const Camera cam = session->views()[size_t(view)].camera;
          const Image truth_mask = segment::selection_mask(s->scene.bundle.gaussians, cam, truth, cam.width, cam.height);
          for (auto& after : per_after) after.push_back(sc.iou);  // the later counts replaced as clicks come
          for (int c = 0; c < corrective; ++c) {
            const auto next = segment::corrective_click(
                truth_mask, segment::selection_mask(s->scene.bundle.gaussians, cam, session->selection(), cam.width, cam.height));
            if (!next) break;  // nothing left to correct: the later counts keep this score
            session->click(view, *next);  // (the interaction time stays the first click's)
            sc = score();
            for (int later = c + 1; later <= corrective; ++later) per_after[size_t(later)].back() = sc.iou;
          }
        }
        if (granularity_choice) best_granularity(tc, *session, [&] { return score().iou; });
        add_click(tc, first.iou, first.accuracy, tm.ms_interaction());
        if (!overlays.empty() && ci == 0) {  // the first configuration's evidence, per task (and click) and view
          std::string name = s->name + "_" + s->scene.objects[size_t(t->object)].name;
          if (k > 0) name += "_click" + std::to_string(k);
          write_overlays(*session, name, &s->scene.bundle.gaussians, &truth);
        }
      }
      close_task(tc);
    }
    for (size_t fi = 0; fi < fixture_tasks.size(); ++fi) {
      const segment::EvalTask& t = fixture_tasks[fi];
      const SceneBundle& b = fixture_scenes.at(t.scene_dir);
      const Camera* cam = find_camera(b.cameras, t.view);
      if (!cam) throw Error(t.dir + "/prompts.json", "view '" + t.view + "' is not a camera of the scene");
      TaskClicks tc;
      const std::vector<std::vector<Click>>& prompts = fixture_prompts[fi];
      for (size_t k = 0; k < prompts.size(); ++k) {
        segment::PipelineTimings tm;
        auto session = segment::segment_from_prompts(b, int(cam - b.cameras.data()), prompts[k], sam, so, setup.views,
                                                     setup.views_spec, &tm);
        const segment::TaskResult r = segment::score_task(t, b, session->selection(), so.threads);
        if (granularity_choice)
          best_granularity(tc, *session, [&] { return segment::score_task(t, b, session->selection(), so.threads).iou; });
        add_click(tc, r.iou, r.accuracy, tm.ms_interaction());
        if (!overlays.empty() && ci == 0) write_overlays(*session, k ? t.name + "_click" + std::to_string(k) : t.name, nullptr, nullptr);
      }
      close_task(tc);
    }
    const double k = double(tasks.size() + fixture_tasks.size());
    std::printf("| %s | %.2f | %.1f | %.2f | %.2f s |", configs[ci].label.c_str(), 100 * miou / k, 100 * worst,
                100 * macc / k, ms / k / 1000);
    for (double p : per) std::printf(" %.1f |", 100 * p);
    std::printf("\n");
    if (clicks_per_task > 1) {
      auto row = [](const char* label, const std::vector<double>& v) {
        double mean = 0, least = 1;
        for (double p : v) {
          mean += p;
          least = std::min(least, p);
        }
        std::printf("| %s | %.2f | %.1f | | |", label, 100 * mean / double(v.size()), 100 * least);
        for (double p : v) std::printf(" %.1f |", 100 * p);
        std::printf("\n");
      };
      row("... the task's own click", per_own);
      row("... its worst click per task", per_worst);
    }
    if (granularity_choice) {
      double mean = 0, least = 1;
      for (double p : per_granularity) {
        mean += p;
        least = std::min(least, p);
      }
      std::printf("| ... and the best granularity | %.2f | %.1f | | |", 100 * mean / double(per_granularity.size()),
                  100 * least);
      for (double p : per_granularity) std::printf(" %.1f |", 100 * p);
      std::printf("\n");
    }
    if (corrective > 0 && !tasks.empty()) {
      for (int c = 0; c <= corrective; ++c) {
        const std::vector<double>& v = per_after[size_t(c)];
        double mean = 0, least = 1;
        for (double p : v) {
          mean += p;
          least = std::min(least, p);
        }
        std::printf("| ... after %d click%s (synthetic) | %.2f | %.1f | | |", c + 1, c ? "s" : "", 100 * mean / double(v.size()),
                    100 * least);
        for (double p : v) std::printf(" %.1f |", 100 * p);
        std::printf("\n");
      }
      std::printf("\nclicks needed (synthetic, at most %d; NoC): ", corrective + 1);
      for (double target : {0.85, 0.90}) {
        const segment::ClicksNeeded noc = segment::clicks_needed(per_after, target);
        std::printf("NoC@%d %.2f (%zu of %zu never reach it)%s", int(std::lround(100 * target)), noc.mean, noc.never,
                    per_after[0].size(), target < 0.9 ? "; " : "\n");
      }
    }
    std::fflush(stdout);
  }
  return 0;
}

int run_ablation(const std::vector<std::string>& argv) {
  std::set<std::string> values = segment_value_flags();
  values.insert({"density", "width", "height", "set", "only", "configs", "overlays", "preview", "fixtures",
                 "fixture-tasks", "clicks-per-task", "corrective-clicks", "camera-factor"});
  std::set<std::string> switches = segment_switch_flags();
  switches.insert({"second-clicks", "granularity-choice"});
  Args args(argv, values, switches);
  const std::string set = args.get("set", "eval");
  if (set == "eval") return run_eval_ablation(args);
  if (set != "demo") throw Error("--set must be eval or demo");
  DemoSceneOptions opt;
  opt.density = float(args.get_double("density", 1.0));
  opt.width = args.get_int("width", 480);
  opt.height = args.get_int("height", 360);
  if (!(opt.density > 0.01f && opt.density <= 50.f)) throw Error("--density must be in (0.01, 50]");
  DemoScene demo = make_demo_scene(opt);
  SegmentSetup setup = parse_segment_setup(args);
  auto sam = load_sam(setup);
  const std::vector<Config> configs = {
      {"hybrid, IIM, 100% views", segment::PropagationMode::Hybrid, true, "all"},
      {"epipolar, IIM, 100% views", segment::PropagationMode::Epipolar, true, "all"},
      {"depth, IIM, 100% views", segment::PropagationMode::Depth, true, "all"},
      {"hybrid, no IIM, 100% views", segment::PropagationMode::Hybrid, false, "all"},
      {"epipolar, no IIM, 100% views", segment::PropagationMode::Epipolar, false, "all"},
      {"hybrid, IIM, 50% views", segment::PropagationMode::Hybrid, true, "50%"},
      {"hybrid, IIM, 25% views", segment::PropagationMode::Hybrid, true, "25%"},
      {"hybrid, IIM, 10% views", segment::PropagationMode::Hybrid, true, "10%"},
  };
  // The clicks: one per object, in the first camera that sees its centre.
  std::vector<std::pair<int, Click>> clicks;
  for (size_t o = 0; o < demo.objects.size(); ++o) {
    int cam = 0;
    double x = 0, y = 0;  // a pixel
    if (!demo_click(demo, int(o), cam, x, y)) throw Error("ablation: no camera sees " + demo.objects[o].name);
    clicks.push_back({cam, pixel_centre_click(x, y, 1)});
  }
  std::printf("synthetic scene: %zu Gaussians, %zu objects, %zu cameras at %dx%d; one click per object\n\n",
              demo.bundle.gaussians.size(), demo.objects.size(), demo.bundle.cameras.size(), opt.width, opt.height);
  std::printf("| configuration | mIoU | mAcc |");
  for (const auto& o : demo.objects) std::printf(" %s |", o.name.c_str());
  std::printf(" interaction |\n|---|---|---|");
  for (size_t o = 0; o < demo.objects.size(); ++o) std::printf("---|");
  std::printf("---|\n");
  for (const Config& cfg : configs) {
    segment::SessionOptions so = setup.session;
    so.propagation.mode = cfg.mode;
    so.inspection = cfg.inspection;
    double miou = 0, macc = 0, ms = 0;
    std::vector<double> per;
    for (size_t o = 0; o < demo.objects.size(); ++o) {
      segment::PipelineTimings t;
      auto s = segment::segment_from_prompts(demo.bundle, clicks[o].first, {clicks[o].second}, sam, so, setup.views,
                                             cfg.views, &t);
      const segment::MaskScore sc = segment::score_selection(demo.bundle.gaussians, demo.bundle.cameras,
                                                             demo_object_mask(demo, int(o)), s->selection());
      per.push_back(sc.iou);
      miou += sc.iou;
      macc += sc.accuracy;
      ms += t.ms_interaction();
    }
    const double k = double(demo.objects.size());
    std::printf("| %s | %.2f | %.2f |", cfg.label.c_str(), 100 * miou / k, 100 * macc / k);
    for (double p : per) std::printf(" %.1f |", 100 * p);
    std::printf(" %.2f s |\n", ms / k / 1000);
    std::fflush(stdout);
  }
  return 0;
}

RegisterCommand reg("ablation", "measure the segmentation's design choices on synthetic scenes with known labels",
                    "usage: isegman ablation [--set eval|demo] [--only TEXT] [--configs 0,2,...] [--overlays DIR]\n"
                    "                        [--density D] [--width W --height H] [--fixtures DIR]\n"
                    "                        [--fixture-tasks DIR|none] [--clicks-per-task K [--second-clicks]]\n"
                    "                        [--corrective-clicks N] [--camera-factor F] [--granularity-choice]\n"
                    "                        [segment options]\n"
                    "  --set eval (default): the evaluation set of hard cases (gaps, occluders, thin, tiny and\n"
                    "  compound objects, coarse Gaussians, clean orbit objects), every addition beyond the paper\n"
                    "  switched off in turn; --set demo: the demo scene with propagation modes, inspection and\n"
                    "  view sampling. Prints Markdown tables: IoU of the rendered selection vs the true object in\n"
                    "  every camera that sees it, per task and averaged, and the time per interaction. The eval\n"
                    "  set also scores the tasks in --fixture-tasks (default eval/fixture_tasks) on the real scenes\n"
                    "  under --fixtures (default ../shared/fixtures) against their hand-made masks; skipped with a\n"
                    "  message when either folder is missing. --clicks-per-task K (eval set): each task from its\n"
                    "  own click and K-1 more drawn (fixed per task) on the object in its clicked view (a real\n"
                    "  task: on its mask of that view, 3 px in from the outline); the mean over them, and rows\n"
                    "  of each task's own click and of its worst click.\n"
                    "  --second-clicks: each drawn click is given after the task's own click, as a second\n"
                    "  positive click on the same object, instead of alone. --corrective-clicks N (eval set):\n"
                    "  after each synthetic task's own click, up to N clicks as a user corrects, at the most\n"
                    "  interior pixel of the larger error in the clicked view (positive where the selection\n"
                    "  misses the object, negative where it takes something else); rows per click count (the\n"
                    "  configuration's own row stays the first click's; --overlays show the last click's).\n"
                    "  --granularity-choice: after each click, the clicked view's granularity stepped up to\n"
                    "  twice larger and twice smaller (the web app's Larger/Smaller); a row of the best (per\n"
                    "  task, the mean over its clicks).\n"
                    "  --camera-factor F (eval set): F x the cameras of each synthetic capture, F - 1 more\n"
                    "  between each camera and the next along its path. Synthetic tasks vote with every camera\n"
                    "  unless --views is given (--views auto: the K views segment chooses, as for a capture of\n"
                    "  many photos).",
                    run_ablation);

}  // namespace
}  // namespace isegman::app
