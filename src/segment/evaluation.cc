#include "segment/evaluation.h"

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/spatial_order.h"
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/scene_loader.h"
#include "render/rasterizer.h"
#include "render/visibility.h"

namespace fs = std::filesystem;

namespace isegman::segment {

EvalTask read_task(const std::string& dir, const std::string& fixtures) {
  EvalTask t;
  t.dir = dir;
  t.name = fs::path(dir).filename().string();
  if (t.name.empty()) t.name = fs::path(dir).parent_path().filename().string();
  t.scene_dir = (fs::path(dir) / "scene").string();
  const std::string prompts = (fs::path(dir) / "prompts.json").string();
  std::vector<uint8_t> bytes = read_file_bytes(prompts);
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(bytes.begin(), bytes.end());
  } catch (const nlohmann::json::exception& e) {
    throw Error(prompts, std::string("invalid JSON: ") + e.what());
  }
  if (!j.is_object() || !j.contains("view") || !j["view"].is_string())
    throw Error(prompts, "needs a \"view\" string (the img_name of the clicked camera)");
  t.view = j["view"].get<std::string>();
  if (j.contains("kind")) {
    if (!j["kind"].is_string()) throw Error(prompts, "\"kind\" must be a string");
    t.kind = j["kind"].get<std::string>();
  }
  if (j.contains("fixture_scene")) {
    if (!j["fixture_scene"].is_string()) throw Error(prompts, "\"fixture_scene\" must be a path string");
    t.fixture_scene = j["fixture_scene"].get<std::string>();
    const fs::path rel(t.fixture_scene);
    if (rel.is_absolute() || t.fixture_scene.find("..") != std::string::npos)
      throw Error(prompts, "\"fixture_scene\" must be a relative path inside the fixtures root");
    std::error_code ec;
    if (fixtures.empty() || !fs::is_directory(fs::path(fixtures) / rel, ec))
      throw Error(prompts, "needs the fixture scene '" + t.fixture_scene + "' under the fixtures root " +
                               (fixtures.empty() ? std::string("(none given: --fixtures DIR)") : "'" + fixtures + "'"));
    t.scene_dir = (fs::path(fixtures) / rel).string();
  }
  for (const char* key : {"positive", "negative"}) {
    if (!j.contains(key)) continue;
    if (!j[key].is_array()) throw Error(prompts, std::string("\"") + key + "\" must be a list of [x, y]");
    for (const auto& p : j[key]) {
      if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
        throw Error(prompts, std::string("\"") + key + "\" must be a list of [x, y] pairs");
      // [x, y] names a pixel: the click is its centre (core/click.h).
      t.clicks.push_back(pixel_centre_click(p[0].get<double>(), p[1].get<double>(), std::string(key) == "positive" ? 1 : 0));
    }
  }
  // Positive clicks first: the first round must select something.
  std::stable_sort(t.clicks.begin(), t.clicks.end(), [](const Click& a, const Click& b) {
    return a.label > b.label;
  });
  if (t.clicks.empty() || t.clicks.front().label != 1) throw Error(prompts, "needs at least one positive click");
  const fs::path masks = fs::path(dir) / "masks";
  std::error_code ec;
  if (!fs::is_directory(masks, ec)) throw Error(masks.string(), "no masks/ folder with ground truth");
  for (const auto& e : fs::directory_iterator(masks)) {
    if (!e.is_regular_file()) continue;
    const std::string ext = e.path().extension().string();
    if (ext != ".png" && ext != ".jpg" && ext != ".jpeg") continue;
    t.masks.emplace_back(e.path().stem().string(), e.path().string());
  }
  std::sort(t.masks.begin(), t.masks.end());
  if (t.masks.empty()) throw Error(masks.string(), "contains no mask images");
  return t;
}

std::vector<EvalTask> find_tasks(const std::string& path, const std::string& fixtures) {
  std::error_code ec;
  if (fs::exists(fs::path(path) / "prompts.json", ec)) return {read_task(path, fixtures)};
  if (!fs::is_directory(path, ec)) throw Error(path, "not a task directory or a folder of task directories");
  std::vector<std::string> dirs;
  for (const auto& e : fs::directory_iterator(path))
    if (e.is_directory() && fs::exists(e.path() / "prompts.json")) dirs.push_back(e.path().string());
  std::sort(dirs.begin(), dirs.end());
  if (dirs.empty()) throw Error(path, "holds no task directories (each needs prompts.json, scene/ and masks/)");
  std::vector<EvalTask> tasks;
  for (const auto& d : dirs) tasks.push_back(read_task(d, fixtures));
  return tasks;
}

ClicksNeeded clicks_needed(const std::vector<std::vector<double>>& iou_after, double target) {
  ClicksNeeded out;
  if (iou_after.empty() || iou_after[0].empty()) return out;
  const size_t most = iou_after.size(), tasks = iou_after[0].size();
  for (const auto& row : iou_after)
    if (row.size() != tasks) throw Error("clicks_needed: every click count needs one IoU per task");
  double sum = 0;
  for (size_t t = 0; t < tasks; ++t) {
    size_t k = 0;
    while (k < most && iou_after[k][t] < target) ++k;
    out.never += k == most;
    sum += double(std::min(k + 1, most));
  }
  out.mean = sum / double(tasks);
  return out;
}

MaskScore score_mask(const Image& pred, const Image& truth) {
  if (pred.width != truth.width || pred.height != truth.height) throw Error("score_mask: sizes differ");
  size_t inter = 0, uni = 0, correct = 0;
  const size_t n = size_t(pred.width) * pred.height;
  for (size_t i = 0; i < n; ++i) {
    const bool p = pred.data[i * pred.channels] > 0.5f;
    bool t = false;
    for (int c = 0; c < truth.channels; ++c) t |= truth.data[i * truth.channels + c] > 0.f;
    inter += p && t;
    uni += p || t;
    correct += p == t;
  }
  MaskScore s;
  s.iou = uni ? double(inter) / double(uni) : 1.0;
  s.accuracy = double(correct) / double(n);
  return s;
}

MaskScore score_selection(const GaussianScene& scene, const std::vector<Camera>& cameras,
                          const std::vector<bool>& truth, const std::vector<bool>& selection, int min_pixels) {
  MaskScore mean;
  int n = 0;
  for (const Camera& cam : cameras) {
    const Image gt = selection_mask(scene, cam, truth, cam.width, cam.height);
    if (std::count(gt.data.begin(), gt.data.end(), 1.f) < min_pixels) continue;
    const MaskScore s = score_mask(selection_mask(scene, cam, selection, cam.width, cam.height), gt);
    mean.iou += s.iou;
    mean.accuracy += s.accuracy;
    ++n;
  }
  if (n) {
    mean.iou /= n;
    mean.accuracy /= n;
  }
  return mean;
}

Image selection_mask(const GaussianScene& scene, const Camera& camera, const std::vector<bool>& selection, int width,
                     int height, int threads) {
  const Camera c = (width == camera.width && height == camera.height) ? camera : camera.resized(width, height);
  RenderSettings s;
  s.threads = threads;
  Image m = render_selection(scene, c, selection, s);
  for (float& v : m.data) v = v > 0.5f ? 1.f : 0.f;
  return m;
}

TaskResult evaluate_task(const EvalTask& task, std::shared_ptr<const models::SamModel> sam,
                         const SessionOptions& so, const ViewOptions& vo, const std::string& views_spec,
                         const Progress& progress) {
  SceneBundle b = load_scene(task.scene_dir);
  put_in_space_order(b.gaussians);  // as `segment` works on it
  const Camera* cam = find_camera(b.cameras, task.view);
  if (!cam) throw Error(task.dir + "/prompts.json", "view '" + task.view + "' is not a camera of the scene");
  PipelineTimings timings;
  auto session = segment_from_prompts(b, int(cam - b.cameras.data()), task.clicks, sam, so, vo, views_spec,
                                      &timings, progress);
  TaskResult r = score_task(task, b, session->selection(), so.threads);
  r.timings = timings;
  return r;
}

TaskResult score_task(const EvalTask& task, const SceneBundle& b, const std::vector<bool>& sel, int threads) {
  TaskResult r;
  r.name = task.name;
  r.selected = size_t(std::count(sel.begin(), sel.end(), true));
  for (const auto& [view, path] : task.masks) {
    const Camera* c = find_camera(b.cameras, view);
    if (!c) throw Error(path, "mask for '" + view + "', which is not a camera of the scene");
    Image truth = read_image(path);
    MaskScore s = score_mask(selection_mask(b.gaussians, *c, sel, truth.width, truth.height, threads), truth);
    s.view = view;
    r.masks.push_back(s);
    r.iou += s.iou;
    r.accuracy += s.accuracy;
  }
  r.iou /= double(r.masks.size());
  r.accuracy /= double(r.masks.size());
  return r;
}

std::vector<bool> mask_majority_selection(const EvalTask& task, const SceneBundle& b, int threads) {
  const size_t n = b.gaussians.size();
  std::vector<int64_t> inside(n, 0), total(n, 0);
  RenderSettings rs;
  rs.threads = threads;
  rs.color = rs.depth = false;
  for (const auto& [view, path] : task.masks) {
    const Camera* c = find_camera(b.cameras, view);
    if (!c) throw Error(path, "mask for '" + view + "', which is not a camera of the scene");
    const Image truth = read_image(path);
    Image mask(truth.width, truth.height, 1);
    for (size_t i = 0; i < mask.data.size(); ++i)
      for (int ch = 0; ch < truth.channels; ++ch) mask.data[i] += truth.data[i * truth.channels + ch] > 0.f ? 1.f : 0.f;
    const Camera cam = (truth.width == c->width && truth.height == c->height) ? *c : c->resized(truth.width, truth.height);
    const PreparedFrame frame = prepare_frame(b.gaussians, cam, rs);
    const GaussianWeights in = weight_sums(frame, &mask, rs), all = weight_sums(frame, nullptr, rs);
    for (size_t k = 0; k < in.index.size(); ++k) inside[in.index[k]] += in.weight[k];
    for (size_t k = 0; k < all.index.size(); ++k) total[all.index[k]] += all.weight[k];
  }
  std::vector<bool> sel(n, false);
  for (size_t i = 0; i < n; ++i) sel[i] = total[i] > 0 && 2 * inside[i] > total[i];
  return sel;
}

}  // namespace isegman::segment
