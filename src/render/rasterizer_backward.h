// Differentiable version of the tile rasteriser: a forward pass that reproduces
// render() (same projection, SH, 16x16 tiles, depth order, INRIA per-pixel rules) and
// keeps what the backward pass needs (per-pixel final transmittance and last
// contributor, as the INRIA backward does), and a backward pass that turns dL/d(pixel
// colour) into gradients of each differentiated Gaussian's mean, log-scale, rotation
// quaternion (unnormalised, w x y z), logit opacity and SH coefficients.
//
// Only the Gaussians given a "slot" are differentiated; the others are frozen but still
// occlude and blend exactly as in the forward pass. The maths is templated on the scalar
// type: float for editing, double for finite-difference checks.
//
// Determinism: tiles run in parallel; each tile accumulates its Gaussians' screen-space
// gradients in its own buffer and the buffers are summed in tile order, so gradients
// are bit-identical for any thread count.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/camera.h"
#include "core/scene.h"
#include "render/rasterizer.h"

namespace isegman {

// Read-only views of n Gaussians' parameters in the GaussianScene layout.
template <typename Real>
struct GaussianParams {
  size_t count = 0;
  int sh_degree = 0;
  const Real* positions = nullptr;  // 3n
  const Real* sh = nullptr;         // n * (d+1)^2 * 3, [gaussian][coefficient][channel]
  const Real* opacity = nullptr;    // n logits
  const Real* scales = nullptr;     // 3n log-scales
  const Real* rotations = nullptr;  // 4n quaternions w x y z (any length > 0)
};

GaussianParams<float> params_of(const GaussianScene& scene);

// Gradients of the differentiated Gaussians, indexed by slot (not by Gaussian index).
template <typename Real>
struct GaussianGrads {
  int sh_degree = 0;
  std::vector<Real> positions, sh, opacity, scales, rotations;
  void resize(size_t slots, int degree);  // zero-filled
  void zero();
  size_t slots() const { return opacity.size(); }
};

struct DiffRenderSettings {
  float background[3] = {0.f, 0.f, 0.f};
  int threads = 0;           // 0: all hardware threads
  int sh_degree = -1;        // -1: the scene's own degree
  float alpha_max = 0.99f;
  float near_plane = 0.2f;
  float blur = 0.3f;
  // Rasterise only the tiles that some differentiated Gaussian touches (others hold the
  // background and alpha 0; their pixels do not depend on the differentiated Gaussians).
  bool only_diff_tiles = false;
};

// A differentiable render and the state the backward pass reads.
template <typename Real>
class DiffRender {
 public:
  DiffRender();
  ~DiffRender();
  DiffRender(DiffRender&&) noexcept;
  DiffRender& operator=(DiffRender&&) noexcept;

  int width = 0, height = 0, grid_x = 0, grid_y = 0;
  std::vector<Real> color;          // width * height * 3, interleaved, over the background
  std::vector<Real> transmittance;  // width * height: final T (1 - alpha)
  std::vector<uint8_t> tile_active; // grid_x * grid_y: tile was rasterised
  size_t visible = 0;               // Gaussians that survived culling
  size_t diff_visible = 0;          // of which differentiated

  struct State;
  std::unique_ptr<State> state;
};

// Forward pass. `slot` has one entry per Gaussian: -1 frozen, otherwise the index of its
// row in the gradient arrays (each slot used once).
template <typename Real>
void diff_render_forward(const GaussianParams<Real>& params, const Camera& camera, const std::vector<int32_t>& slot,
                         const DiffRenderSettings& settings, DiffRender<Real>& out);

// Backward pass: adds dL/dparameters of every slotted Gaussian to `grads` (sized for the
// slot count beforehand) given dL/d(colour) (width * height * 3, same layout as color).
// `params`, `camera`, `slot` and `settings` must be the forward pass's.
template <typename Real>
void diff_render_backward(const GaussianParams<Real>& params, const Camera& camera, const std::vector<int32_t>& slot,
                          const DiffRenderSettings& settings, const DiffRender<Real>& forward, const Real* dL_dcolor,
                          GaussianGrads<Real>& grads);

}  // namespace isegman
