// Semantic editing (the paper's instruction-driven manipulation): render the selection's
// views, edit them with a 2D instruction-driven image editor, and optimise only the
// selected Gaussians toward the edited images (L1 + D-SSIM [+ perceptual], Adam with an
// annealed step size, no densification). Targets are re-edited from the current renders
// during optimisation (Instruct-NeRF2NeRF's iterative dataset update).
//
// Unselected Gaussians are never written: their parameters stay bit-identical. The input
// scene is never modified; an editor failure throws before anything is returned.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/image.h"
#include "core/scene.h"
#include "core/selection.h"
#include "edit/image_editor.h"
#include "edit/losses.h"
#include "edit/optimizer.h"

namespace isegman::edit {

struct SemanticProgress {
  int step = 0, steps = 0;
  double loss = 0;        // mean over the last reported steps (evaluated near the selection)
  double lr_factor = 0;   // schedule factor at this step
  double seconds = 0;     // optimisation time so far (editor calls excluded)
  int editor_calls = 0;
};

struct SemanticEditOptions {
  std::string instruction;
  int steps = 1500;
  int refresh_every = 10;   // steps between target refreshes (Instruct-NeRF2NeRF: 10); 0: never
  int refresh_views = 1;    // views re-edited per refresh (round robin)
  int max_views = 0;        // 0: every camera that sees the selection; else an even sample
  int width = 0;            // render width (height keeps the aspect); 0: the cameras' own
  int min_mask_pixels = 16; // a view is used when the selection covers at least this many pixels
  LossSettings loss;
  LearningRates rates;
  Schedule schedule = Schedule::kCosine;
  float background[3] = {0.f, 0.f, 0.f};
  int threads = 0;
  unsigned seed = 1;
  int progress_every = 100;                                // 0: no progress callbacks
  std::function<void(const SemanticProgress&)> progress;   // called every progress_every steps
  const std::atomic<bool>* stop = nullptr;                 // set to stop early (result is kept)
};

struct SemanticView {
  Camera camera;    // at the optimisation resolution
  Image original;   // render of the input scene
  Image mask;       // coverage of the selection in the input scene (1 channel)
  Image target;     // current edited target
};

struct SemanticEditResult {
  GaussianScene scene;
  std::vector<SemanticView> views;
  int steps_done = 0;
  bool interrupted = false;
  int editor_calls = 0;
  double seconds_optimising = 0, seconds_editing = 0;
  double mean_mask_psnr = 0;  // final render vs target inside mask > 0.5, mean over views
};

// Throws Error on an empty/mismatched selection, no usable view, or an editor failure.
SemanticEditResult semantic_edit(const GaussianScene& scene, const std::vector<Camera>& cameras,
                                 const Selection& selection, ImageEditor& editor, const SemanticEditOptions& options);

// PSNR of a and b (3 channels) over the pixels where mask > threshold; +inf when equal.
double masked_psnr(const Image& a, const Image& b, const Image& mask, float threshold = 0.5f);

}  // namespace isegman::edit
