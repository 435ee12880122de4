#include "edit/optimizer.h"

#include <cmath>

#include "core/error.h"

namespace isegman::edit {

Schedule parse_schedule(const std::string& text) {
  if (text == "cosine") return Schedule::kCosine;
  if (text == "linear") return Schedule::kLinear;
  if (text == "constant") return Schedule::kConstant;
  throw Error("--schedule", "unknown schedule '" + text + "' (cosine, linear or constant)");
}

const char* schedule_name(Schedule s) {
  switch (s) {
    case Schedule::kCosine: return "cosine";
    case Schedule::kLinear: return "linear";
    case Schedule::kConstant: return "constant";
  }
  return "?";
}

double schedule_factor(Schedule s, int step, int total) {
  if (s == Schedule::kConstant) return 1.0;
  if (total <= 1) return step <= 0 ? 1.0 : 0.0;
  const double t = std::min(1.0, std::max(0.0, double(step) / double(total - 1)));
  if (s == Schedule::kLinear) return 1.0 - t;
  return 0.5 * (1.0 + std::cos(M_PI * t));
}

SelectionAdam::SelectionAdam(const GaussianScene& scene, std::vector<uint32_t> selected, const LearningRates& rates,
                             double extent)
    : selected_(std::move(selected)), slot_(scene.size(), -1), rates_(rates), extent_(extent),
      sh_coeffs_(scene.coeffs()) {
  for (size_t s = 0; s < selected_.size(); ++s) {
    if (selected_[s] >= scene.size()) throw Error("optimiser: selected Gaussian index outside the scene");
    if (slot_[selected_[s]] >= 0) throw Error("optimiser: a Gaussian is selected twice");
    slot_[selected_[s]] = int32_t(s);
  }
  const size_t n = selected_.size();
  pos_ = {std::vector<float>(3 * n, 0.f), std::vector<float>(3 * n, 0.f)};
  sh_ = {std::vector<float>(n * sh_coeffs_ * 3, 0.f), std::vector<float>(n * sh_coeffs_ * 3, 0.f)};
  op_ = {std::vector<float>(n, 0.f), std::vector<float>(n, 0.f)};
  sc_ = {std::vector<float>(3 * n, 0.f), std::vector<float>(3 * n, 0.f)};
  rot_ = {std::vector<float>(4 * n, 0.f), std::vector<float>(4 * n, 0.f)};
}

void SelectionAdam::update(float* param, const float* grad, Moments& mom, size_t offset, size_t n, double lr,
                           double bc1, double bc2) {
  constexpr double b1 = 0.9, b2 = 0.999, eps = 1e-15;
  for (size_t k = 0; k < n; ++k) {
    const double g = grad[k];
    float& m = mom.m[offset + k];
    float& v = mom.v[offset + k];
    m = float(b1 * m + (1 - b1) * g);
    v = float(b2 * v + (1 - b2) * g * g);
    if (lr == 0) continue;
    const double step = lr * (m / bc1) / (std::sqrt(v / bc2) + eps);
    param[k] = float(param[k] - step);
  }
}

void SelectionAdam::step(GaussianScene& scene, const GaussianGrads<float>& g, double lr_factor) {
  if (scene.size() != slot_.size() || scene.coeffs() != sh_coeffs_)
    throw Error("optimiser: the scene changed shape during optimisation");
  if (g.slots() != selected_.size()) throw Error("optimiser: gradient buffers do not match the selection");
  ++t_;
  const double bc1 = 1 - std::pow(0.9, t_), bc2 = 1 - std::pow(0.999, t_);
  const size_t K3 = size_t(sh_coeffs_) * 3;
  for (size_t s = 0; s < selected_.size(); ++s) {
    const size_t i = selected_[s];
    update(&scene.positions[3 * i], &g.positions[3 * s], pos_, 3 * s, 3, rates_.position * extent_ * lr_factor, bc1,
           bc2);
    float* sh = scene.sh_of(i);
    update(sh, &g.sh[K3 * s], sh_, K3 * s, 3, rates_.sh_dc * lr_factor, bc1, bc2);
    if (K3 > 3) update(sh + 3, &g.sh[K3 * s + 3], sh_, K3 * s + 3, K3 - 3, rates_.sh_rest * lr_factor, bc1, bc2);
    update(&scene.opacity[i], &g.opacity[s], op_, s, 1, rates_.opacity * lr_factor, bc1, bc2);
    update(&scene.scales[3 * i], &g.scales[3 * s], sc_, 3 * s, 3, rates_.scale * lr_factor, bc1, bc2);
    update(&scene.rotations[4 * i], &g.rotations[4 * s], rot_, 4 * s, 4, rates_.rotation * lr_factor, bc1, bc2);
  }
}

}  // namespace isegman::edit
