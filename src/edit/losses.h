// Image losses for semantic editing, with their gradients: the INRIA trainer's
// (1 - lambda) L1 + lambda D-SSIM (lambda 0.2, 11x11 Gaussian window, sigma 1.5, zero
// padding, C1 = 0.01^2, C2 = 0.03^2), plus a pluggable perceptual term.
//
// The paper adds LPIPS. Its network weights cannot be obtained on these machines, so no
// LPIPS ships; PerceptualTerm is the hook a user implements (or an adapter to a service)
// and sets with LossSettings::perceptual.
//
// Losses are means over all pixels and channels of the full image. To keep an editing
// step cheap they can be evaluated on a region: the gradient is exact on `region` (the
// pixels whose colour can change), and the loss value covers only the pixels near it.
#pragma once

#include <string>

namespace isegman::edit {

struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // [x0, x1) x [y0, y1)
  bool empty() const { return x1 <= x0 || y1 <= y0; }
};

// A perceptual loss term on 3-channel interleaved float images in [0, 1].
class PerceptualTerm {
 public:
  virtual ~PerceptualTerm() = default;
  virtual std::string name() const = 0;
  // Returns the loss and adds dLoss/d(render) to `grad` (width * height * 3).
  virtual double evaluate(const float* render, const float* target, int width, int height, float* grad) = 0;
};

struct LossSettings {
  double lambda_dssim = 0.2;       // INRIA default
  double lambda_perceptual = 0.0;  // weight of `perceptual` (ignored when null)
  PerceptualTerm* perceptual = nullptr;
};

struct LossValue {
  double l1 = 0, dssim = 0, perceptual = 0, total = 0;
};

// Loss of `render` against `target` (width * height * 3 interleaved) and its gradient,
// ADDED to `grad` on `region` (the whole image when region is empty). Values outside
// [0, 1] are used as they are (as the trainers do).
LossValue image_loss(const float* render, const float* target, int width, int height, const LossSettings& settings,
                     float* grad, PixelRect region = {});

// Mean SSIM over the image (same window and constants), for tests and reports.
double ssim(const float* a, const float* b, int width, int height);

}  // namespace isegman::edit
