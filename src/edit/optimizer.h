// Adam over the selected Gaussians' parameters, with per-parameter learning rates in the
// spirit of the INRIA trainer (position 1.6e-4 x scene extent, opacity 0.05, log-scale
// 5e-3, rotation 1e-3; beta 0.9 / 0.999, eps 1e-15). Colour uses GaussianEditor's editing
// rate (SH DC 0.0125, higher SH / 20) instead of the trainer's 2.5e-3: an edit has 1500
// steps, not 30000, to move a colour across its range.
// and a step-size schedule that decays to zero at the last step. No densification: the
// set of Gaussians never changes, and only selected Gaussians are ever written.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/scene.h"
#include "render/rasterizer_backward.h"

namespace isegman::edit {

struct LearningRates {
  double position = 1.6e-4;  // multiplied by the scene extent
  double sh_dc = 0.0125;
  double sh_rest = 0.0125 / 20;
  double opacity = 0.05;
  double scale = 5e-3;
  double rotation = 1e-3;
};

enum class Schedule { kCosine, kLinear, kConstant };

// "cosine" | "linear" | "constant"; throws Error naming the text otherwise.
Schedule parse_schedule(const std::string& text);
const char* schedule_name(Schedule s);
// Step-size factor for step `step` of `total` (0-based): 1 at the first step, 0 at the
// last (cosine: 0.5 (1 + cos(pi t / (total - 1))); linear: 1 - t / (total - 1)).
double schedule_factor(Schedule s, int step, int total);

// The optimisation state of one selection: slot table (Gaussian -> row) and Adam moments.
class SelectionAdam {
 public:
  // `selected`: Gaussian indices, in slot order. `extent` scales the position rate.
  SelectionAdam(const GaussianScene& scene, std::vector<uint32_t> selected, const LearningRates& rates, double extent);

  const std::vector<int32_t>& slots() const { return slot_; }           // per Gaussian
  const std::vector<uint32_t>& selected() const { return selected_; }  // per slot
  int steps_taken() const { return t_; }

  // One Adam update of the selected Gaussians of `scene` with rates x `lr_factor`.
  void step(GaussianScene& scene, const GaussianGrads<float>& grads, double lr_factor);

 private:
  struct Moments {
    std::vector<float> m, v;
  };
  void update(float* param, const float* grad, Moments& mom, size_t offset, size_t n, double lr, double bc1,
              double bc2);

  std::vector<uint32_t> selected_;
  std::vector<int32_t> slot_;
  LearningRates rates_;
  double extent_;
  int sh_coeffs_;
  int t_ = 0;
  Moments pos_, sh_, op_, sc_, rot_;
};

}  // namespace isegman::edit
