#include "render/rasterizer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <type_traits>
#ifdef __AVX__
#include <immintrin.h>
#endif

#include "core/error.h"
#include "core/parallel.h"
#include "core/sh.h"
#include "render/projection.h"
#include "render/radix_sort.h"
#include "render/tile_kernel.h"
#include "render/visibility.h"

namespace isegman {
namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

constexpr float kMinAlpha = 1.f / 255.f;
constexpr float kMinTransmittance = 1e-4f;

// A Gaussian as projection leaves it: the splat, its colour and its tile rectangle
// (needed only for binning).
struct Projected {
  Splat splat;
  float depth;
  float rgb[3];
  uint16_t tx0, ty0, tx1, ty1;  // tile rect [tx0, tx1) x [ty0, ty1)
};

struct TileBuffers {
  float T[kTileSize * kTileSize];
  float C[3][kTileSize * kTileSize];
  float D[kTileSize * kTileSize];
  float V[kTileSize * kTileSize];
  int32_t done[kTileSize * kTileSize];
};

// Eight lanes of float / int32 (GCC/Clang vector extensions: AVX when the build has
// it, pairs of SSE registers otherwise).
typedef float v8f __attribute__((vector_size(32)));
typedef int32_t v8i __attribute__((vector_size(32)));
typedef double v8d __attribute__((vector_size(64)));
typedef int64_t v8q __attribute__((vector_size(64)));

inline v8f splat8(float v) { return v8f{v, v, v, v, v, v, v, v}; }

// exp(x) for x <= 0: Cody-Waite range reduction and a degree-6 Taylor polynomial (within
// 2 ulp of std::exp, exactly 1 at 0). Plain arithmetic, so it runs on all lanes at once.
inline v8f exp_nonpositive(v8f x) {
  x = x < splat8(-87.f) ? splat8(-87.f) : x;
  const v8f magic = splat8(12582912.f);  // 1.5 * 2^23: adding it rounds to an integer
  const v8f n = (x * splat8(1.44269504088896341f) + magic) - magic;
  const v8f r = (x - n * splat8(0.693145751953125f)) - n * splat8(1.428606765330187e-06f);
  v8f p = splat8(1.f / 720.f);
  p = p * r + splat8(1.f / 120.f);
  p = p * r + splat8(1.f / 24.f);
  p = p * r + splat8(1.f / 6.f);
  p = p * r + splat8(0.5f);
  p = p * r + splat8(1.f);
  p = p * r + splat8(1.f);
  const v8i bits = (__builtin_convertvector(n, v8i) + 127) << 23;
  return p * (v8f)bits;  // vector casts reinterpret the bits
}

inline v8f select8(v8i mask, v8f a, v8f b) {
  return (v8f)(((v8i)a & mask) | ((v8i)b & ~mask));
}

// Lanes set in a comparison's result (every bit of a lane set or none): the sign bits'
// count, one instruction pair with AVX.
inline int lanes_set(v8i mask) {
#ifdef __AVX__
  return __builtin_popcount(unsigned(_mm256_movemask_ps(_mm256_castsi256_ps((__m256i)mask))));
#else
  int n = 0;
  for (int i = 0; i < 8; ++i) n -= mask[i];
  return n;
#endif
}

// Projects Gaussian i; false when it cannot contribute to any pixel. One compiled body
// (never inlined), so binned_tiles finds the very tile rect prepare_frame binned with.
__attribute__((noinline)) bool preprocess_one(const GaussianScene& scene, size_t i, const ProjectionCamera& cam,
                                              const RenderSettings& s, int degree, int grid_x, int grid_y,
                                              Projected& proj) {
  Splat& out = proj.splat;
  const float opacity = sigmoid(scene.opacity[i]);
  if (!(opacity >= kMinAlpha)) return false;  // can never reach alpha 1/255
  const float* p = &scene.positions[3 * i];
  if (cam.R[6] * p[0] + cam.R[7] * p[1] + cam.R[8] * p[2] + cam.t[2] <= s.near_plane) return false;  // cheap cull first
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
  const int px0 = std::max(0, int(std::ceil(f.mean_x - ex)));
  const int px1 = std::min(cam.width - 1, int(std::floor(f.mean_x + ex)));
  const int py0 = std::max(0, int(std::ceil(f.mean_y - ey)));
  const int py1 = std::min(cam.height - 1, int(std::floor(f.mean_y + ey)));
  if (px0 > px1 || py0 > py1) return false;
  const int tx0 = std::max(rx0, px0 / kTileSize), tx1 = std::min(rx1, px1 / kTileSize + 1);
  const int ty0 = std::max(ry0, py0 / kTileSize), ty1 = std::min(ry1, py1 / kTileSize + 1);
  if (tx0 >= tx1 || ty0 >= ty1) return false;
  // Rounded up, the half-widths give a box holding this one.
  out.hx = encode_half_width(ex);
  out.hy = encode_half_width(ey);
  proj.tx0 = uint16_t(tx0);
  proj.tx1 = uint16_t(tx1);
  proj.ty0 = uint16_t(ty0);
  proj.ty1 = uint16_t(ty1);
  out.mx = f.mean_x;
  out.my = f.mean_y;
  out.ca = f.conic_a;
  out.cb = f.conic_b;
  out.cc = f.conic_c;
  out.opacity = opacity;
  proj.depth = f.depth;
  out.index = uint32_t(i);
  if (s.color) {
    float dx = p[0] - cam.center[0], dy = p[1] - cam.center[1], dz = p[2] - cam.center[2];
    const float n = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (n > 0) { dx /= n; dy /= n; dz /= n; }
    // Coefficients are [coefficient][channel]; a lower render degree reads a prefix.
    sh_to_rgb(degree, scene.sh_of(i), dx, dy, dz, proj.rgb);
  } else {
    proj.rgb[0] = proj.rgb[1] = proj.rgb[2] = 0.f;
  }
  return true;
}

// Per-entry bookkeeping of a sums pass (TilePass::on_tile): the entry's summed weights
// over the pixels of `lanes` (8 bits per row group, bit i = column x_base + i), and
// whether it was blended at an open pixel.
struct EntrySum {
  uint32_t sum = 0;  // at most 256 pixels x fixed_weight(w < 1) < 2^32
  uint8_t blended = 0;
};

// Blends Gaussian g into the 8 pixels of one row group starting at column x_base, lanes
// outside [x0, x1] untouched. The INRIA per-pixel rules, branch-free. Returns the
// number of pixels that terminated.
template <bool kVisit, bool kSums, bool kShade>
inline int blend_group(const Splat& g, const float* rgb, float depth, float value, float dy, int k0, int x_base, int x0, int x1,
                       int y, float alpha_max, bool want_value, TileBuffers& b, uint64_t& evaluated,
                       uint64_t& contributed, ContributionVisitor* visitor, int worker, unsigned sum_lanes,
                       EntrySum& entry) {
  static const v8f lane = {0, 1, 2, 3, 4, 5, 6, 7};
  const v8f xs = splat8(float(x_base)) + lane;
  const v8i in_range = (xs >= splat8(float(x0))) & (xs <= splat8(float(x1)));
  v8f T, C0, C1, C2, D, V;
  v8i done;
  std::memcpy(&T, b.T + k0, sizeof T);
  std::memcpy(&done, b.done + k0, sizeof done);
  const v8f dx = splat8(g.mx) - xs;
  const v8f power = splat8(-0.5f * g.ca) * dx * dx + splat8(-0.5f * g.cc * dy * dy) + splat8(-g.cb * dy) * dx;
  v8f alpha = splat8(g.opacity) * exp_nonpositive(power);
  alpha = alpha < splat8(alpha_max) ? alpha : splat8(alpha_max);
  const v8f test_T = T * (splat8(1.f) - alpha);
  const v8i active = in_range & (done == 0);
  const v8i valid = active & (power <= splat8(0.f)) & (alpha >= splat8(kMinAlpha));
  const v8i term = valid & (test_T < splat8(kMinTransmittance));
  const v8i contrib = valid & ~term;
  const v8f w = select8(contrib, alpha * T, splat8(0.f));
  if constexpr (kShade) {  // colour and depth (value and vote passes need neither)
    std::memcpy(&C0, b.C[0] + k0, sizeof C0);
    std::memcpy(&C1, b.C[1] + k0, sizeof C1);
    std::memcpy(&C2, b.C[2] + k0, sizeof C2);
    std::memcpy(&D, b.D + k0, sizeof D);
    C0 += w * splat8(rgb[0]);
    C1 += w * splat8(rgb[1]);
    C2 += w * splat8(rgb[2]);
    D += w * splat8(depth);
    std::memcpy(b.C[0] + k0, &C0, sizeof C0);
    std::memcpy(b.C[1] + k0, &C1, sizeof C1);
    std::memcpy(b.C[2] + k0, &C2, sizeof C2);
    std::memcpy(b.D + k0, &D, sizeof D);
  }
  T = select8(contrib, test_T, T);
  done |= term;
  std::memcpy(b.T + k0, &T, sizeof T);
  std::memcpy(b.done + k0, &done, sizeof done);
  if (want_value) {
    std::memcpy(&V, b.V + k0, sizeof V);
    V += w * splat8(value);
    std::memcpy(b.V + k0, &V, sizeof V);
  }
  evaluated += uint64_t(lanes_set(active));
  const int added = lanes_set(contrib);
  contributed += uint64_t(added);
  if constexpr (kVisit) {
    if (added > 0) {
      unsigned lanes = 0;
      float weights[kLanes];
      for (int i = 0; i < kLanes; ++i) {
        lanes |= contrib[i] ? 1u << i : 0u;
        weights[i] = w[i];
      }
      visitor->visit_row8(worker, x_base, y, g.index, weights, lanes);
    }
  }
  if constexpr (kSums) {
    entry.blended |= uint8_t(lanes_set(valid) > 0);
    if (added > 0) {
      // fixed_weight() on every lane at once (w is 0 where nothing contributed), kept in the
      // summed lanes: the same integers as lane by lane.
      static const v8i kBit = {1, 2, 4, 8, 16, 32, 64, 128};
      const v8i summed = (kBit & int32_t(sum_lanes)) != 0;
      const v8q fixed = __builtin_convertvector(__builtin_convertvector(w, v8d) * kWeightScale + 0.5, v8q) &
                        __builtin_convertvector(summed, v8q);
      int64_t total = 0;
      for (int i = 0; i < kLanes; ++i) total += fixed[i];
      entry.sum += uint32_t(total);
    }
  }
  return lanes_set(term);
}

// Lane bits (one byte per row group: row * 2 + half) of the tile's pixels where
// mask > 0.5; every bit without a mask.
void tile_lanes(const Image* mask, int x_begin, int y_begin, int x_end, int y_end, uint8_t out[2 * kTileSize]) {
  for (int r = 0; r < kTileSize; ++r)
    for (int h = 0; h < 2; ++h) {
      uint8_t bits = 0;
      const int y = y_begin + r;
      for (int i = 0; i < kLanes; ++i) {
        const int x = x_begin + h * kLanes + i;
        if (y < y_end && x < x_end && (!mask || mask->data[size_t(y) * mask->width + x] > 0.5f)) bits |= uint8_t(1u << i);
      }
      out[r * 2 + h] = bits;
    }
}

// A tile's list is in depth order, so its splats (and their values, by Gaussian) are read
// at random from arrays far larger than the cache in a large scene; the loop asks for
// them this many entries ahead (the splat) and half as many (its value, once the splat has
// arrived). A mask's sums over a 6M-Gaussian view: ~42 -> ~33 ms (BM_VotePass).
constexpr size_t kTileListPrefetchAhead = 32;
template <bool kVisit, bool kSums, bool kShade>
void raster_tile(int tile_x, int tile_y, const Splat* splats, const float* rgb, const float* depths,
                 const uint32_t* list, size_t count,
                 int width, int height, const RenderSettings& s, const float* values, ContributionVisitor* visitor,
                 int worker, TileBuffers& b, uint64_t& evaluated_out, uint64_t& contributed_out,
                 const uint8_t* lanes, EntrySum* entries, bool lanes_only) {
  // Counted locally: the per-worker totals share a cache line, and bumping them in the
  // pixel loop from two threads would serialise the workers (false sharing).
  uint64_t evaluated = 0, contributed = 0;
  struct Flush {
    uint64_t &from_e, &from_c, &to_e, &to_c;
    ~Flush() { to_e += from_e; to_c += from_c; }
  } flush{evaluated, contributed, evaluated_out, contributed_out};
  static const float kBlack[3] = {0.f, 0.f, 0.f};
  const bool want_value = values != nullptr;
  const int x_begin = tile_x * kTileSize, y_begin = tile_y * kTileSize;
  const int x_end = std::min(width, x_begin + kTileSize), y_end = std::min(height, y_begin + kTileSize);
  const int pixels = (x_end - x_begin) * (y_end - y_begin);
  constexpr int kPx = kTileSize * kTileSize;
  std::fill(b.T, b.T + kPx, 1.f);
  if (kShade) {
    for (auto& c : b.C) std::fill(c, c + kPx, 0.f);
    std::fill(b.D, b.D + kPx, 0.f);
  }
  std::fill(b.V, b.V + kPx, 0.f);
  std::fill(b.done, b.done + kPx, 0);
  int finished = 0;
  if (lanes_only) {  // pixels outside the lanes start (and count as) ended
    for (int r = 0; r < kTileSize; ++r)
      for (int i = 0; i < kTileSize; ++i)
        if (!((lanes[r * 2 + i / kLanes] >> (i % kLanes)) & 1u)) {
          b.done[r * kTileSize + i] = -1;
          finished += y_begin + r < y_end && x_begin + i < x_end;
        }
  }
  // Row groups with a pixel still open (bit r * 2 + half). A group whose every pixel has
  // ended changes nothing when blended, so it is skipped: pixels past the image's edge
  // count as ended here (no pass reads them) but not in `finished`.
  constexpr int kGroups = kTileSize * kTileSize / kLanes;
  static_assert(kGroups <= 32, "one bit per row group");
  uint32_t open = 0;
  for (int r = 0; r < kTileSize; ++r)
    for (int i = 0; i < kTileSize; ++i) {
      int32_t& d = b.done[r * kTileSize + i];
      if (y_begin + r >= y_end || x_begin + i >= x_end) d = -1;
      if (d == 0) open |= 1u << (r * 2 + i / kLanes);
    }
  auto group_ended = [&](int k0) {
    for (int i = 0; i < kLanes; ++i)
      if (b.done[k0 + i] == 0) return false;
    return true;
  };
  EntrySum unused;
  for (size_t n = 0; n < count && finished < pixels; ++n) {
    if (n + kTileListPrefetchAhead < count) __builtin_prefetch(&splats[list[n + kTileListPrefetchAhead]]);
    if (want_value && n + kTileListPrefetchAhead / 2 < count) __builtin_prefetch(&values[splats[list[n + kTileListPrefetchAhead / 2]].index]);
    const Splat& g = splats[list[n]];
    const float* col = rgb ? rgb + 3 * size_t(list[n]) : kBlack;
    const float depth = kShade ? depths[list[n]] : 0.f;
    const float value = want_value ? values[g.index] : 0.f;
    EntrySum& entry = kSums ? entries[n] : unused;
    // Pixel box of this Gaussian inside the tile; columns past the image edge never count.
    const float hx = decode_half_width(g.hx), hy = decode_half_width(g.hy);
    const int x0 = int(std::max(std::ceil(g.mx - hx), float(x_begin)));
    const int x1 = int(std::min(std::floor(g.mx + hx), float(x_end - 1)));
    const int y0 = int(std::max(std::ceil(g.my - hy), float(y_begin)));
    const int y1 = int(std::min(std::floor(g.my + hy), float(y_end - 1)));
    for (int y = y0; y <= y1; ++y) {
      const float dy = g.my - float(y);
      const int row = (y - y_begin) * kTileSize;
      for (int half = 0; half < kTileSize / kLanes; ++half) {
        const int xb = x_begin + half * kLanes;
        if (xb > x1 || xb + kLanes - 1 < x0) continue;
        const int group = (y - y_begin) * 2 + half;
        if (!((open >> group) & 1u)) continue;
        const unsigned sum_lanes = kSums ? lanes[group] : 0u;
        const int k0 = row + half * kLanes;
        const int ended = blend_group<kVisit, kSums, kShade>(g, col, depth, value, dy, k0, xb, x0, x1, y, s.alpha_max,
                                                             want_value, b, evaluated, contributed, visitor, worker,
                                                             sum_lanes, entry);
        if (ended > 0) {
          finished += ended;
          if (group_ended(k0)) open &= ~(1u << group);
        }
      }
    }
  }
}

}  // namespace

PreparedFrame::PreparedFrame() = default;
PreparedFrame::~PreparedFrame() = default;
PreparedFrame::PreparedFrame(PreparedFrame&&) noexcept = default;
PreparedFrame& PreparedFrame::operator=(PreparedFrame&&) noexcept = default;

PreparedFrame prepare_frame(const GaussianScene& scene, const Camera& camera, const RenderSettings& s) {
  if (camera.width <= 0 || camera.height <= 0) throw Error("render: camera has zero image size");
  PreparedFrame frame;
  frame.camera = camera;
  frame.gaussians = scene.size();
  auto data = std::make_unique<PreparedFrame::Data>();
  PreparedFrame::Data& d = *data;
  RenderStats& stats = frame.stats;
  const int W = camera.width, H = camera.height;
  const int grid_x = (W + kTileSize - 1) / kTileSize, grid_y = (H + kTileSize - 1) / kTileSize;
  const int degree = s.sh_degree < 0 ? scene.sh_degree : std::min(s.sh_degree, scene.sh_degree);
  const ProjectionCamera cam(camera);
  const size_t N = scene.size();

  // 1. Project every Gaussian. Chunks run in parallel and keep only what survives, so
  //    the concatenation (in chunk order) lists the visible Gaussians by index.
  auto t0 = Clock::now();
  constexpr size_t kChunk = 32768;
  const size_t chunks = (N + kChunk - 1) / kChunk;
  // Reused between renders on the same thread: fresh buffers of this size cost more in
  // page faults than the projection itself.
  thread_local std::vector<std::vector<Projected>> scratch;
  // A plain reference: lambdas running on worker threads must see this thread's buffers.
  std::vector<std::vector<Projected>>& chunk_out = scratch;
  if (chunk_out.size() < chunks) chunk_out.resize(chunks);
  for (auto& v : chunk_out) v.clear();  // stale entries past `chunks` stay empty
  parallel_for(chunks, s.threads, [&](int, size_t c) {
    // Grown as a local (the chunks' vectors share cache lines) and moved back.
    std::vector<Projected> v = std::move(chunk_out[c]);
    Projected sp;
    for (size_t i = c * kChunk, e = std::min(N, (c + 1) * kChunk); i < e; ++i)
      if (preprocess_one(scene, i, cam, s, degree, grid_x, grid_y, sp)) v.push_back(sp);
    chunk_out[c] = std::move(v);
  });
  size_t visible = 0;
  for (const auto& v : chunk_out) visible += v.size();
  std::vector<uint32_t> order(visible);
  for (size_t k = 0; k < visible; ++k) order[k] = uint32_t(k);
  stats.visible = visible;
  stats.ms_preprocess = ms_since(t0);

  // 2. Sort by depth (stable: ties keep index order, as the CUDA radix sort does), then
  //    bin into tiles in that order so every tile list is already depth-sorted.
  t0 = Clock::now();
  {
    // Depths are > near_plane > 0, so their IEEE bits sort like the values.
    std::vector<uint32_t> depth_keys(visible);
    size_t k = 0;
    for (const auto& v : chunk_out)
      for (const Projected& p : v) std::memcpy(&depth_keys[k++], &p.depth, 4);
    radix_sort_pairs(depth_keys, order, s.threads);
  }
  std::vector<Splat>& splats = d.splats;
  splats.resize(visible);
  if (s.color) d.rgb.resize(3 * visible);
  d.depth.resize(visible);
  struct Rect {
    uint16_t tx0, ty0, tx1, ty1;
  };
  std::vector<Rect> rects(visible);
  {
    std::vector<const Projected*> flat(visible);
    size_t k = 0;
    for (const auto& v : chunk_out)
      for (const Projected& sp : v) flat[k++] = &sp;
    parallel_chunks(visible, 65536, s.threads, [&](size_t, size_t a, size_t e) {
      for (size_t j = a; j < e; ++j) {
        const Projected& p = *flat[order[j]];
        splats[j] = p.splat;
        d.depth[j] = p.depth;
        rects[j] = {p.tx0, p.ty0, p.tx1, p.ty1};
        if (s.color)
          for (int c = 0; c < 3; ++c) d.rgb[3 * j + c] = p.rgb[c];
      }
    });
  }
  std::vector<uint32_t>().swap(order);
  // Kept for the next frame only while small: a large scene's would hold ~60 bytes per
  // Gaussian for as long as the thread lives.
  if (visible > (size_t(1) << 20)) std::vector<std::vector<Projected>>().swap(chunk_out);
  // Counting sort into tiles, in parallel over contiguous (depth-ordered) slices: slice c
  // writes after slices < c in every tile, so each tile list stays depth-sorted and the
  // result does not depend on the thread count.
  const size_t tiles = size_t(grid_x) * grid_y;
  const size_t slices = std::max<size_t>(1, std::min<size_t>(size_t(resolve_threads(s.threads)) * 2,
                                                              (visible + 65535) / 65536));
  const size_t per_slice = (visible + slices - 1) / std::max<size_t>(slices, 1);
  std::vector<std::vector<uint32_t>> slice_count(slices, std::vector<uint32_t>(tiles, 0));
  parallel_for(slices, s.threads, [&](int, size_t c) {
    std::vector<uint32_t>& cnt = slice_count[c];
    for (size_t k = c * per_slice, e = std::min(visible, (c + 1) * per_slice); k < e; ++k) {
      const Rect& g = rects[k];
      for (int ty = g.ty0; ty < g.ty1; ++ty)
        for (int tx = g.tx0; tx < g.tx1; ++tx) ++cnt[size_t(ty) * grid_x + tx];
    }
  });
  std::vector<uint32_t>& tile_start = d.tile_start;
  tile_start.assign(tiles + 1, 0);
  for (size_t t = 0; t < tiles; ++t) {
    uint64_t sum = tile_start[t];
    for (size_t c = 0; c < slices; ++c) sum += slice_count[c][t];
    if (sum > UINT32_MAX) throw Error("render: more than 2^32 (tile, Gaussian) pairs in one frame");
    tile_start[t + 1] = uint32_t(sum);
  }
  // slice_count becomes each slice's write cursor per tile.
  for (size_t t = 0; t < tiles; ++t) {
    uint32_t cursor = tile_start[t];
    for (size_t c = 0; c < slices; ++c) {
      const uint32_t n = slice_count[c][t];
      slice_count[c][t] = cursor;
      cursor += n;
    }
  }
  std::vector<uint32_t>& tile_list = d.tile_list;
  tile_list.resize(tile_start[tiles]);
  parallel_for(slices, s.threads, [&](int, size_t c) {
    std::vector<uint32_t>& fill = slice_count[c];
    for (size_t k = c * per_slice, e = std::min(visible, (c + 1) * per_slice); k < e; ++k) {
      const Rect& g = rects[k];
      for (int ty = g.ty0; ty < g.ty1; ++ty)
        for (int tx = g.tx0; tx < g.tx1; ++tx) tile_list[fill[size_t(ty) * grid_x + tx]++] = uint32_t(k);
    }
  });
  stats.tile_pairs = tile_list.size();
  stats.ms_sort = ms_since(t0);

  d.near_plane = s.near_plane;
  d.blur = s.blur;
  frame.grid_x = grid_x;
  frame.grid_y = grid_y;
  PreparedFrameAccess::adopt(frame, std::move(data));
  return frame;
}

std::vector<TileBox> binned_tiles(const GaussianScene& scene, const PreparedFrame& frame,
                                  const std::vector<uint32_t>& gaussians) {
  if (scene.size() != frame.gaussians) throw Error("binned_tiles: the frame was prepared from another scene");
  const PreparedFrame::Data& d = PreparedFrameAccess::data(frame);
  RenderSettings s;
  s.near_plane = d.near_plane;
  s.blur = d.blur;
  s.color = false;  // the rect does not depend on colour
  const ProjectionCamera cam(frame.camera);
  std::vector<TileBox> out(gaussians.size());
  Projected p;
  for (size_t k = 0; k < gaussians.size(); ++k) {
    if (gaussians[k] >= scene.size()) throw Error("binned_tiles: Gaussian index out of range");
    if (preprocess_one(scene, gaussians[k], cam, s, 0, frame.grid_x, frame.grid_y, p))
      out[k] = {p.tx0, p.ty0, p.tx1 - 1, p.ty1 - 1};
  }
  return out;
}

RenderOutput run_tiles(const PreparedFrame& frame, const RenderSettings& s, const TilePass& pass) {
  const std::vector<float>* values = pass.values;
  const std::vector<uint8_t>* tile_mask = pass.tile_mask;
  ContributionVisitor* visitor = pass.visitor;
  if (values && values->size() != frame.gaussians) throw Error("render: per-Gaussian values do not match the scene size");
  const int grid_x = frame.grid_x, grid_y = frame.grid_y;
  const size_t tiles = size_t(grid_x) * grid_y;
  if (tile_mask && tile_mask->size() != tiles) throw Error("render: tile mask does not match the frame");
  const int W = frame.camera.width, H = frame.camera.height;
  if (pass.sum_mask && (pass.sum_mask->width != W || pass.sum_mask->height != H || pass.sum_mask->channels != 1))
    throw Error("render: pixel mask does not match the frame");
  const PreparedFrame::Data& d = PreparedFrameAccess::data(frame);
  if (d.compact && s.alpha_max != d.alpha_max)
    throw Error("render: a compacted frame renders only with the alpha_max it was compacted for");
  const std::vector<Splat>& splats = d.splats;
  const float* rgb = d.rgb.empty() ? nullptr : d.rgb.data();
  const std::vector<uint32_t>& tile_start = d.tile_start;
  const std::vector<uint32_t>& tile_list = d.tile_list;
  const bool sums = bool(pass.on_tile);
  RenderOutput out;
  out.stats = frame.stats;
  auto t0 = Clock::now();
  // 3. Rasterise tiles in parallel (only the masked ones, when a tile mask is given).
  const bool want_value = values != nullptr;
  const float* vals = want_value ? values->data() : nullptr;
  if (s.color) out.color = Image(W, H, 3);
  out.alpha = Image(W, H, 1);
  if (s.depth) out.depth = Image(W, H, 1);
  if (want_value) out.value = Image(W, H, 1);
  const int workers = worker_count(tiles, s.threads);
  if (visitor) visitor->begin(workers);
  // A value-only pass over a compacted frame may take uniform tiles from its stored blends.
  const bool shade = s.color || s.depth;
  if (shade && d.depth.size() != splats.size())
    throw Error("render: this prepared frame was compacted for value and vote passes: it renders no colour or depth");
  const bool stored_values = want_value && !visitor && !s.color && !s.depth && !d.value_all.empty();
  std::vector<uint64_t> evaluated(workers, 0), contributed(workers, 0);
  std::vector<TileBuffers> buffers(workers);
  std::vector<std::vector<EntrySum>> entry_buffers(sums ? workers : 0);
  std::vector<std::vector<uint32_t>> sum_out(sums ? workers : 0);
  std::vector<std::vector<uint8_t>> blended_out(sums ? workers : 0);
  parallel_for(tiles, workers, [&](int w, size_t t) {
    const int tx = int(t % grid_x), ty = int(t / grid_x);
    if (tile_mask && !(*tile_mask)[t]) {
      if (s.color)
        for (int y = ty * kTileSize; y < std::min(H, (ty + 1) * kTileSize); ++y)
          for (int x = tx * kTileSize; x < std::min(W, (tx + 1) * kTileSize); ++x)
            for (int c = 0; c < 3; ++c) out.color.at(x, y, c) = s.background[c];
      return;
    }
    TileBuffers& b = buffers[w];
    const uint32_t* list = tile_list.data() + tile_start[t];
    const size_t count = tile_start[t + 1] - tile_start[t];
    const int x_begin = tx * kTileSize, y_begin = ty * kTileSize;
    const int x_end = std::min(W, x_begin + kTileSize), y_end = std::min(H, y_begin + kTileSize);
    const bool sums_here = sums && (!pass.sum_tiles || (*pass.sum_tiles)[t]);
    auto with_shade = [&](auto visit, auto sum, const uint8_t* lanes, EntrySum* entries) {
      constexpr bool kV = decltype(visit)::value, kS = decltype(sum)::value;
      const bool lanes_only = kS && pass.sum_pixels_only;
      if (shade)
        raster_tile<kV, kS, true>(tx, ty, splats.data(), rgb, d.depth.data(), list, count, W, H, s, vals, visitor, w, b, evaluated[w],
                                  contributed[w], lanes, entries, lanes_only);
      else
        raster_tile<kV, kS, false>(tx, ty, splats.data(), rgb, nullptr, list, count, W, H, s, vals, visitor, w, b,
                                   evaluated[w], contributed[w], lanes, entries, lanes_only);
    };
    if (stored_values && !sums_here) {
      // Every Gaussian of the tile carries 1, or every one 0: the stored blend is the answer.
      bool ones = true, zeros = true;
      for (size_t n = 0; n < count && (ones || zeros); ++n) {
        if (n + kTileListPrefetchAhead < count) __builtin_prefetch(&vals[splats[list[n + kTileListPrefetchAhead]].index]);  // read at random
        const float v = vals[splats[list[n]].index];
        ones &= v == 1.f;
        zeros &= v == 0.f;
      }
      if (ones || zeros) {
        for (int y = y_begin; y < y_end; ++y)
          for (int x = x_begin; x < x_end; ++x) {
            const size_t k = size_t(y) * W + x;
            out.alpha.data[k] = d.alpha_all[k];
            out.value.data[k] = ones ? d.value_all[k] : 0.f;
          }
        return;
      }
    }
    if (sums_here) {
      uint8_t lanes[2 * kTileSize];
      tile_lanes(pass.sum_mask, x_begin, y_begin, x_end, y_end, lanes);
      std::vector<EntrySum>& e = entry_buffers[w];
      e.assign(count, EntrySum{});
      if (visitor) with_shade(std::true_type{}, std::true_type{}, lanes, e.data());
      else with_shade(std::false_type{}, std::true_type{}, lanes, e.data());
      std::vector<uint32_t>& so = sum_out[w];
      std::vector<uint8_t>& bo = blended_out[w];
      so.resize(count);
      bo.resize(count);
      for (size_t n = 0; n < count; ++n) {
        so[n] = e[n].sum;
        bo[n] = e[n].blended;
      }
      pass.on_tile(w, t, so.data(), bo.data());
    } else if (visitor) {
      with_shade(std::true_type{}, std::false_type{}, nullptr, nullptr);
    } else {
      with_shade(std::false_type{}, std::false_type{}, nullptr, nullptr);
    }
    for (int y = y_begin; y < y_end; ++y)
      for (int x = x_begin; x < x_end; ++x) {
        const int k = (y - y_begin) * kTileSize + (x - x_begin);
        const float T = b.T[k];
        const float a = 1.f - T;
        out.alpha.at(x, y) = a;
        if (s.color)
          for (int c = 0; c < 3; ++c) out.color.at(x, y, c) = b.C[c][k] + T * s.background[c];
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

RenderOutput rasterize(const PreparedFrame& frame, const RenderSettings& s, const std::vector<float>* values,
                       ContributionVisitor* visitor, const std::vector<uint8_t>* tile_mask) {
  TilePass pass;
  pass.values = values;
  pass.visitor = visitor;
  pass.tile_mask = tile_mask;
  return run_tiles(frame, s, pass);
}
RenderOutput render(const GaussianScene& scene, const Camera& camera, const RenderSettings& s,
                    const std::vector<float>* values, ContributionVisitor* visitor) {
  if (values && values->size() != scene.size()) throw Error("render: per-Gaussian values do not match the scene size");
  return rasterize(prepare_frame(scene, camera, s), s, values, visitor);
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
