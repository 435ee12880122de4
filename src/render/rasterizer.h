// CPU tile rasteriser for 3D Gaussian splats that reproduces the INRIA CUDA rasteriser:
// 16x16 tiles, Gaussians depth-sorted per tile, alpha = min(0.99, o * exp(power)),
// alpha < 1/255 skipped, a pixel stops before its transmittance would fall below 1e-4.
// Tiles run in parallel; every pixel is computed by one thread in a fixed order, so the
// output does not depend on the thread count.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/camera.h"
#include "core/image.h"
#include "core/scene.h"

namespace isegman {

constexpr int kTileSize = 16;

struct RenderSettings {
  float background[3] = {0.f, 0.f, 0.f};
  int threads = 0;             // 0: all hardware threads
  int sh_degree = -1;          // -1: the scene's own degree; lower to cap it
  float alpha_max = 0.99f;     // INRIA: 0.99 (gsplat: 0.999)
  float near_plane = 0.2f;     // camera-space z below which Gaussians are culled
  float blur = 0.3f;           // added to the 2D covariance diagonal
  bool color = true;           // compute the RGB image
  bool depth = true;           // compute expected depth
};

// Receives every blending weight w = alpha * T that contributes to a pixel, front to
// back per pixel. Called concurrently from worker threads: each tile is handled by
// exactly one thread (`worker` in [0, workers)), and within a tile pixels are visited
// Gaussian by Gaussian. Implementations must make concurrent calls for different tiles
// safe (per-worker buffers, or order-independent accumulation).
class ContributionVisitor {
 public:
  virtual ~ContributionVisitor() = default;
  virtual void begin(int workers) {}
  virtual void visit(int worker, int x, int y, uint32_t gaussian, float weight) = 0;
  // The same contributions eight pixels at a time: pixels (x_base + i, y) for the lanes i
  // whose bit is set in `lanes`, with weights[i]. The rasteriser calls this; override it
  // to avoid a virtual call per pixel (the default forwards to visit()).
  virtual void visit_row8(int worker, int x_base, int y, uint32_t gaussian, const float* weights, unsigned lanes) {
    for (int i = 0; i < 8; ++i)
      if (lanes & (1u << i)) visit(worker, x_base + i, y, gaussian, weights[i]);
  }
};

struct RenderStats {
  size_t visible = 0;          // Gaussians that survived culling
  size_t tile_pairs = 0;       // (tile, Gaussian) pairs after binning
  uint64_t evaluated = 0;      // (pixel, Gaussian) pairs whose alpha was evaluated
  uint64_t contributed = 0;    // pairs that contributed a weight
  double ms_preprocess = 0, ms_sort = 0, ms_raster = 0;
};

struct RenderOutput {
  Image color;  // 3 channels, composited over the background
  Image alpha;  // 1 channel: accumulated opacity 1 - T
  Image depth;  // 1 channel: expected depth sum(w z) / sum(w); 0 where nothing is hit
  Image value;  // 1 channel: sum(w v) of per-Gaussian values, when given
  RenderStats stats;
};

// A camera's projected, depth-sorted and tile-binned Gaussians: everything of a render
// that does not depend on per-Gaussian values, so a view can be rasterised many times
// (selection masks, votes) for the cost of the tile pass alone.
class PreparedFrame {
 public:
  PreparedFrame();
  ~PreparedFrame();
  PreparedFrame(PreparedFrame&&) noexcept;
  PreparedFrame& operator=(PreparedFrame&&) noexcept;

  Camera camera;
  size_t gaussians = 0;  // size of the scene it was prepared from
  int grid_x = 0, grid_y = 0;  // tiles
  RenderStats stats;           // preprocessing and sorting figures

  struct Data;  // opaque: render/tile_kernel.h

 private:
  std::unique_ptr<Data> data_;
  friend struct PreparedFrameAccess;
};

// Projects, sorts and bins (uses settings.near_plane, blur, sh_degree, color, threads).
PreparedFrame prepare_frame(const GaussianScene& scene, const Camera& camera, const RenderSettings& settings = {});
// Tiles [x0, x1] x [y0, y1], inclusive (empty when x1 < x0).
struct TileBox {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
};
// The tiles prepare_frame binned these Gaussians' splats to in `frame` (the frame's tile
// lists name a Gaussian only there; compacted or not), by the same projection: one box per
// Gaussian, empty where the frame holds no splat of it (culled, or outside the view).
std::vector<TileBox> binned_tiles(const GaussianScene& scene, const PreparedFrame& frame,
                                  const std::vector<uint32_t>& gaussians);
// Blends a prepared frame. `tile_mask` (optional, grid_x * grid_y flags) limits the work
// to the flagged tiles; other tiles come out empty (background, alpha 0). A frame prepared
// with settings.color off renders black; one compacted for value and vote passes only
// (render/visibility.h) refuses colour and depth. Per-Gaussian values must be finite.
RenderOutput rasterize(const PreparedFrame& frame, const RenderSettings& settings = {},
                       const std::vector<float>* values = nullptr, ContributionVisitor* visitor = nullptr,
                       const std::vector<uint8_t>* tile_mask = nullptr);

// Renders `scene` from `camera`. `values` (optional, one float per Gaussian) adds the
// `value` image: with 1 for selected Gaussians and 0 otherwise it is the selection's
// coverage, occlusion by unselected Gaussians included. `visitor` (optional) sees
// every contributing weight.
RenderOutput render(const GaussianScene& scene, const Camera& camera, const RenderSettings& settings = {},
                    const std::vector<float>* values = nullptr, ContributionVisitor* visitor = nullptr);

// Coverage of a per-Gaussian selection (bool or weights) as a 1-channel image in [0, 1].
Image render_selection(const GaussianScene& scene, const Camera& camera, const std::vector<float>& selection,
                       const RenderSettings& settings = {});
Image render_selection(const GaussianScene& scene, const Camera& camera, const std::vector<bool>& selection,
                       const RenderSettings& settings = {});

}  // namespace isegman
