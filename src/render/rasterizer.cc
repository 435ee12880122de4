#include "render/rasterizer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "core/parallel.h"
#include "core/sh.h"
#include "render/projection.h"
#include "render/radix_sort.h"

namespace isegman {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

constexpr float kMinAlpha = 1.f / 255.f;
constexpr float kMinTransmittance = 1e-4f;

// A projected Gaussian, as the tile loop reads it.
struct Splat {
  float mx, my;          // centre, index coordinates
  float ca, cb, cc;      // conic
  float opacity;         // activated
  float rgb[3];
  float depth;
  float value;
  uint32_t index;        // Gaussian index in the scene
  int px0, py0, px1, py1;  // pixel box outside which alpha < 1/255 (inclusive, clipped)
  int tx0, ty0, tx1, ty1;  // tile rect [tx0, tx1) x [ty0, ty1)
};

struct TileBuffers {
  float T[kTileSize * kTileSize];
  float C[3 * kTileSize * kTileSize];
  float D[kTileSize * kTileSize];
  float V[kTileSize * kTileSize];
  uint8_t done[kTileSize * kTileSize];
};

// Projects Gaussian i; false when it cannot contribute to any pixel.
bool preprocess_one(const GaussianScene& scene, size_t i, const ProjectionCamera& cam, const RenderSettings& s,
                    int degree, int grid_x, int grid_y, const std::vector<float>* values, Splat& out) {
  const float opacity = 1.f / (1.f + std::exp(-scene.opacity[i]));
  if (!(opacity >= kMinAlpha)) return false;  // can never reach alpha 1/255
  float cov3[6];
  covariance_3d(&scene.scales[3 * i], &scene.rotations[4 * i], cov3);
  Footprint f;
  if (!project_footprint(cam, &scene.positions[3 * i], cov3, s.near_plane, s.blur, f)) return false;
  // INRIA's tile rectangle from the 3-sigma radius.
  const float r = float(f.radius);
  const int rx0 = std::min(grid_x, std::max(0, int((f.mean_x - r) / kTileSize)));
  const int ry0 = std::min(grid_y, std::max(0, int((f.mean_y - r) / kTileSize)));
  const int rx1 = std::min(grid_x, std::max(0, int((f.mean_x + r + kTileSize - 1) / kTileSize)));
  const int ry1 = std::min(grid_y, std::max(0, int((f.mean_y + r + kTileSize - 1) / kTileSize)));
  if ((rx1 - rx0) * (ry1 - ry0) == 0) return false;
  // Exact cut-off: alpha >= 1/255 needs d^T conic d <= 2 ln(255 o), an ellipse whose
  // half-widths are sqrt(2 ln(255 o) cov_xx) and sqrt(2 ln(255 o) cov_yy). Pixels outside
  // its (slightly padded) box are skipped by the alpha test anyway; skipping them early
  // is what makes a CPU rasteriser fast.
  const float level = 2.f * std::log(255.f * opacity);
  const float ex = std::sqrt(std::max(0.f, level * f.cov_a)) * 1.001f + 0.01f;
  const float ey = std::sqrt(std::max(0.f, level * f.cov_c)) * 1.001f + 0.01f;
  out.px0 = std::max(0, int(std::ceil(f.mean_x - ex)));
  out.px1 = std::min(cam.width - 1, int(std::floor(f.mean_x + ex)));
  out.py0 = std::max(0, int(std::ceil(f.mean_y - ey)));
  out.py1 = std::min(cam.height - 1, int(std::floor(f.mean_y + ey)));
  if (out.px0 > out.px1 || out.py0 > out.py1) return false;
  out.tx0 = std::max(rx0, out.px0 / kTileSize);
  out.tx1 = std::min(rx1, out.px1 / kTileSize + 1);
  out.ty0 = std::max(ry0, out.py0 / kTileSize);
  out.ty1 = std::min(ry1, out.py1 / kTileSize + 1);
  if (out.tx0 >= out.tx1 || out.ty0 >= out.ty1) return false;
  out.mx = f.mean_x;
  out.my = f.mean_y;
  out.ca = f.conic_a;
  out.cb = f.conic_b;
  out.cc = f.conic_c;
  out.opacity = opacity;
  out.depth = f.depth;
  out.index = uint32_t(i);
  out.value = values ? (*values)[i] : 0.f;
  if (s.color) {
    const float* p = &scene.positions[3 * i];
    float dx = p[0] - cam.center[0], dy = p[1] - cam.center[1], dz = p[2] - cam.center[2];
    const float n = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (n > 0) { dx /= n; dy /= n; dz /= n; }
    // Coefficients are [coefficient][channel]; a lower render degree reads a prefix.
    sh_to_rgb(degree, scene.sh_of(i), dx, dy, dz, out.rgb);
  } else {
    out.rgb[0] = out.rgb[1] = out.rgb[2] = 0.f;
  }
  return true;
}

template <bool kVisit>
void raster_tile(int tile_x, int tile_y, const Splat* splats, const uint32_t* list, size_t count, int width,
                 int height, const RenderSettings& s, bool want_value, ContributionVisitor* visitor, int worker,
                 TileBuffers& b, uint64_t& evaluated, uint64_t& contributed) {
  const int x_begin = tile_x * kTileSize, y_begin = tile_y * kTileSize;
  const int x_end = std::min(width, x_begin + kTileSize), y_end = std::min(height, y_begin + kTileSize);
  const int pixels = (x_end - x_begin) * (y_end - y_begin);
  std::fill(b.T, b.T + kTileSize * kTileSize, 1.f);
  std::fill(b.C, b.C + 3 * kTileSize * kTileSize, 0.f);
  std::fill(b.D, b.D + kTileSize * kTileSize, 0.f);
  std::fill(b.V, b.V + kTileSize * kTileSize, 0.f);
  std::memset(b.done, 0, sizeof b.done);
  int finished = 0;
  const float alpha_max = s.alpha_max;
  for (size_t n = 0; n < count && finished < pixels; ++n) {
    const Splat& g = splats[list[n]];
    const int x0 = std::max(g.px0, x_begin), x1 = std::min(g.px1, x_end - 1);
    const int y0 = std::max(g.py0, y_begin), y1 = std::min(g.py1, y_end - 1);
    for (int y = y0; y <= y1; ++y) {
      const float dy = g.my - float(y);
      const int row = (y - y_begin) * kTileSize - x_begin;
      for (int x = x0; x <= x1; ++x) {
        const int k = row + x;
        if (b.done[k]) continue;
        ++evaluated;
        const float dx = g.mx - float(x);
        const float power = -0.5f * (g.ca * dx * dx + g.cc * dy * dy) - g.cb * dx * dy;
        if (power > 0.f) continue;
        const float alpha = std::min(alpha_max, g.opacity * std::exp(power));
        if (alpha < kMinAlpha) continue;
        const float T = b.T[k];
        const float test_T = T * (1.f - alpha);
        if (test_T < kMinTransmittance) {
          b.done[k] = 1;
          ++finished;
          continue;
        }
        const float w = alpha * T;
        b.C[3 * k] += w * g.rgb[0];
        b.C[3 * k + 1] += w * g.rgb[1];
        b.C[3 * k + 2] += w * g.rgb[2];
        b.D[k] += w * g.depth;
        if (want_value) b.V[k] += w * g.value;
        b.T[k] = test_T;
        ++contributed;
        if constexpr (kVisit) visitor->visit(worker, x, y, g.index, w);
      }
    }
  }
}

}  // namespace

RenderOutput render(const GaussianScene& scene, const Camera& camera, const RenderSettings& s,
                    const std::vector<float>* values, ContributionVisitor* visitor) {
  if (camera.width <= 0 || camera.height <= 0) throw Error("render: camera has zero image size");
  if (values && values->size() != scene.size()) throw Error("render: per-Gaussian values do not match the scene size");
  RenderOutput out;
  const int W = camera.width, H = camera.height;
  const int grid_x = (W + kTileSize - 1) / kTileSize, grid_y = (H + kTileSize - 1) / kTileSize;
  const int degree = s.sh_degree < 0 ? scene.sh_degree : std::min(s.sh_degree, scene.sh_degree);
  const ProjectionCamera cam(camera);
  const size_t N = scene.size();

  // 1. Project every Gaussian (parallel, each writes only its own slot).
  auto t0 = Clock::now();
  std::vector<Splat> projected(N);
  std::vector<uint8_t> visible(N, 0);
  parallel_chunks(N, 16384, s.threads, [&](int, size_t a, size_t e) {
    for (size_t i = a; i < e; ++i)
      visible[i] = preprocess_one(scene, i, cam, s, degree, grid_x, grid_y, values, projected[i]) ? 1 : 0;
  });
  std::vector<uint32_t> order;
  std::vector<uint32_t> keys;
  order.reserve(N);
  for (size_t i = 0; i < N; ++i)
    if (visible[i]) order.push_back(uint32_t(i));
  keys.resize(order.size());
  for (size_t k = 0; k < order.size(); ++k) {
    // Depths are > near_plane > 0, so their IEEE bits sort like the values.
    std::memcpy(&keys[k], &projected[order[k]].depth, 4);
  }
  out.stats.visible = order.size();
  out.stats.ms_preprocess = ms_since(t0);

  // 2. Sort by depth (stable: ties keep index order, as the CUDA radix sort does), then
  //    bin into tiles in that order so every tile list is already depth-sorted.
  t0 = Clock::now();
  radix_sort_pairs(keys, order);
  std::vector<Splat> splats(order.size());
  for (size_t k = 0; k < order.size(); ++k) splats[k] = projected[order[k]];
  std::vector<uint32_t>().swap(order);
  std::vector<Splat>().swap(projected);
  const size_t tiles = size_t(grid_x) * grid_y;
  std::vector<uint32_t> tile_start(tiles + 1, 0);
  for (const Splat& g : splats)
    for (int ty = g.ty0; ty < g.ty1; ++ty)
      for (int tx = g.tx0; tx < g.tx1; ++tx) ++tile_start[size_t(ty) * grid_x + tx + 1];
  for (size_t t = 0; t < tiles; ++t) tile_start[t + 1] += tile_start[t];
  std::vector<uint32_t> tile_list(tile_start[tiles]);
  {
    std::vector<uint32_t> fill(tile_start.begin(), tile_start.end() - 1);
    for (size_t k = 0; k < splats.size(); ++k) {
      const Splat& g = splats[k];
      for (int ty = g.ty0; ty < g.ty1; ++ty)
        for (int tx = g.tx0; tx < g.tx1; ++tx) tile_list[fill[size_t(ty) * grid_x + tx]++] = uint32_t(k);
    }
  }
  out.stats.tile_pairs = tile_list.size();
  out.stats.ms_sort = ms_since(t0);

  // 3. Rasterise tiles in parallel.
  t0 = Clock::now();
  const bool want_value = values != nullptr;
  if (s.color) out.color = Image(W, H, 3);
  out.alpha = Image(W, H, 1);
  if (s.depth) out.depth = Image(W, H, 1);
  if (want_value) out.value = Image(W, H, 1);
  const int workers = worker_count(tiles, s.threads);
  if (visitor) visitor->begin(workers);
  std::vector<uint64_t> evaluated(workers, 0), contributed(workers, 0);
  std::vector<TileBuffers> buffers(workers);
  parallel_for(tiles, workers, [&](int w, size_t t) {
    const int tx = int(t % grid_x), ty = int(t / grid_x);
    TileBuffers& b = buffers[w];
    const uint32_t* list = tile_list.data() + tile_start[t];
    const size_t count = tile_start[t + 1] - tile_start[t];
    if (visitor)
      raster_tile<true>(tx, ty, splats.data(), list, count, W, H, s, want_value, visitor, w, b, evaluated[w],
                        contributed[w]);
    else
      raster_tile<false>(tx, ty, splats.data(), list, count, W, H, s, want_value, nullptr, w, b, evaluated[w],
                         contributed[w]);
    const int x_begin = tx * kTileSize, y_begin = ty * kTileSize;
    const int x_end = std::min(W, x_begin + kTileSize), y_end = std::min(H, y_begin + kTileSize);
    for (int y = y_begin; y < y_end; ++y)
      for (int x = x_begin; x < x_end; ++x) {
        const int k = (y - y_begin) * kTileSize + (x - x_begin);
        const float T = b.T[k];
        const float a = 1.f - T;
        out.alpha.at(x, y) = a;
        if (s.color)
          for (int c = 0; c < 3; ++c) out.color.at(x, y, c) = b.C[3 * k + c] + T * s.background[c];
        if (s.depth) out.depth.at(x, y) = a > 0.f ? b.D[k] / a : 0.f;
        if (want_value) out.value.at(x, y) = b.V[k];
      }
  });
  for (int w = 0; w < workers; ++w) {
    out.stats.evaluated += evaluated[w];
    out.stats.contributed += contributed[w];
  }
  out.stats.ms_raster = ms_since(t0);
  return out;
}

Image render_selection(const GaussianScene& scene, const Camera& camera, const std::vector<float>& selection,
                       const RenderSettings& settings) {
  RenderSettings s = settings;
  s.color = false;
  s.depth = false;
  return render(scene, camera, s, &selection).value;
}

Image render_selection(const GaussianScene& scene, const Camera& camera, const std::vector<bool>& selection,
                       const RenderSettings& settings) {
  std::vector<float> v(selection.size());
  for (size_t i = 0; i < v.size(); ++i) v[i] = selection[i] ? 1.f : 0.f;
  return render_selection(scene, camera, v, settings);
}

}  // namespace isegman
