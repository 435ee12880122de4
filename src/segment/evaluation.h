// Scoring segmentations against ground-truth masks, in a generic task layout:
//   <task>/scene/               a scene directory (PLY + cameras.json)
//   <task>/prompts.json         {"view": "<img_name>", "positive": [[x, y], ...], "negative": [...]}
//   <task>/masks/<img_name>.png ground truth (non-zero = object), any resolution
// Instead of scene/, prompts.json may name a scene under a fixtures root ("fixture_scene":
// "fern/scene"), so tasks on shared scenes need no copy of them; "kind" says what the task
// tests. The selection is made from the prompts alone; masks are read only to score it.
#pragma once

#include <string>
#include <vector>

#include "core/image.h"
#include "segment/pipeline.h"

namespace isegman::segment {

struct EvalTask {
  std::string name, dir, scene_dir, view, kind;
  std::string fixture_scene;  // the scene's path under the fixtures root, when it is not <task>/scene
  std::vector<Click> clicks;  // pixel centres of prompts.json's [x, y]
  std::vector<std::pair<std::string, std::string>> masks;  // (camera name, mask file)
};

// A task directory, or a folder whose sub-directories are tasks (sorted by name).
// `fixtures` is the root that "fixture_scene" paths are resolved against; a task naming one
// under an empty or missing root is an error that names the task and the root.
std::vector<EvalTask> find_tasks(const std::string& path, const std::string& fixtures = "");
EvalTask read_task(const std::string& dir, const std::string& fixtures = "");

struct MaskScore {
  std::string view;
  double iou = 0, accuracy = 0;
};

struct TaskResult {
  std::string name;
  std::vector<MaskScore> masks;
  double iou = 0, accuracy = 0;  // means over the task's masks
  size_t selected = 0;
  PipelineTimings timings;
};

// IoU and pixel accuracy of a predicted binary mask (> 0.5) against ground truth (> 0).
MaskScore score_mask(const Image& predicted, const Image& truth);

// Interactive segmentation's usual summary (NoC, as RITM and SAM report it): `iou_after[k][t]`
// is task t's IoU after k + 1 clicks. Per task, the clicks until its IoU first reaches
// `target`, counted as the most clicks run (iou_after.size()) where it never does; the mean
// over tasks, and how many never reach it.
struct ClicksNeeded {
  double mean = 0;
  size_t never = 0;
};
ClicksNeeded clicks_needed(const std::vector<std::vector<double>>& iou_after, double target);

// The selection's mask in a camera at the given resolution: coverage > 0.5.
Image selection_mask(const GaussianScene& scene, const Camera& camera, const std::vector<bool>& selection, int width,
                     int height, int threads = 0);

// A selection against the true one (both per Gaussian), as the synthetic evaluations score
// it: mean IoU and pixel accuracy of their rendered masks over the cameras where the truth
// covers at least `min_pixels`.
MaskScore score_selection(const GaussianScene& scene, const std::vector<Camera>& cameras,
                          const std::vector<bool>& truth, const std::vector<bool>& selection, int min_pixels = 50);

// Scores a selection already made on the task's scene against its masks (ground truth).
TaskResult score_task(const EvalTask& task, const SceneBundle& scene, const std::vector<bool>& selection,
                      int threads = 0);

// What a selection of whole Gaussians can reach against the task's masks, as near as a
// per-Gaussian rule gets: a Gaussian is taken when more of its blending weight, summed over
// every mask's view, falls inside the masks than outside. Large Gaussians whose weight lies
// mostly beside a thin object cannot be taken without the pixels around it: the gap between
// this score and a method's is what the method could still gain.
std::vector<bool> mask_majority_selection(const EvalTask& task, const SceneBundle& scene, int threads = 0);

TaskResult evaluate_task(const EvalTask& task, std::shared_ptr<const models::SamModel> sam,
                         const SessionOptions& session_options, const ViewOptions& view_options,
                         const std::string& views_spec, const Progress& progress = nullptr);

}  // namespace isegman::segment
