#include "render/rasterizer_backward.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "core/parallel.h"
#include "core/sh.h"
#include "render/projection.h"
#include "render/radix_sort.h"

namespace isegman {
namespace {

constexpr float kMinAlpha = 1.f / 255.f;
constexpr float kMinTransmittance = 1e-4f;
constexpr int kTilePixels = kTileSize * kTileSize;

// The camera constants of ProjectionCamera (projection.h) in the scalar type.
template <typename Real>
using DiffCamera = BasicProjectionCamera<Real>;

// ---------------------------------------------------------------------------------------
// Per-Gaussian maths. The forward pieces are the rasteriser's own (projection.h, and
// core/quat_rotation.h and core/sh.h with their derivatives beside them); what chains
// their gradients back is here.

// Everything the projection computes for one Gaussian (kept for the backward pass).
template <typename Real>
struct Projected {
  BasicCovariance3d<Real> cov;
  BasicFootprint<Real> fp;
  Real dir[3], dir_norm;  // unit view direction and the distance it was divided by
  Real raw_rgb[3];        // before the clamp at 0
  Real rgb[3];
  Real opacity;
};

// The rasteriser's projection (projection.h), opacity and SH in the scalar type. False
// when culled.
template <typename Real>
bool project_gaussian(const GaussianParams<Real>& P, size_t i, const DiffCamera<Real>& cam, Real near_plane, Real blur,
                      int degree, Projected<Real>& o) {
  o.opacity = sigmoid(P.opacity[i]);
  if (!(o.opacity >= Real(kMinAlpha))) return false;
  covariance_3d(P.scales + 3 * i, P.rotations + 4 * i, o.cov);
  const Real* p = P.positions + 3 * i;
  if (!project_footprint(cam, p, o.cov.cov, near_plane, blur, o.fp)) return false;

  Real dx = p[0] - cam.center[0], dy = p[1] - cam.center[1], dz = p[2] - cam.center[2];
  o.dir_norm = std::sqrt(dx * dx + dy * dy + dz * dz);
  if (o.dir_norm > 0) { dx /= o.dir_norm; dy /= o.dir_norm; dz /= o.dir_norm; }
  o.dir[0] = dx; o.dir[1] = dy; o.dir[2] = dz;
  Real basis[16];
  sh_basis(degree, dx, dy, dz, basis);
  const int K = (degree + 1) * (degree + 1);
  const Real* coeffs = P.sh + size_t(i) * sh_coeff_count(P.sh_degree) * 3;
  for (int ch = 0; ch < 3; ++ch) {
    Real sum = 0;
    for (int k = 0; k < K; ++k) sum += basis[k] * coeffs[3 * k + ch];
    sum += Real(0.5);
    o.raw_rgb[ch] = sum;
    o.rgb[ch] = sum > Real(0) ? sum : Real(0);
  }
  return true;
}

// Screen-space gradients of one Gaussian, as accumulated by the pixel pass.
template <typename Real>
struct ScreenGrad {
  Real mean[2] = {0, 0};
  Real conic[3] = {0, 0, 0};
  Real opacity = 0;
  Real rgb[3] = {0, 0, 0};
};

// Chains screen-space gradients back to the Gaussian's parameters (adds to the slot's rows).
template <typename Real>
void project_gaussian_backward(const GaussianParams<Real>& P, size_t i, const DiffCamera<Real>& cam, int degree,
                               const Projected<Real>& o, const ScreenGrad<Real>& g, GaussianGrads<Real>& out,
                               size_t slot) {
  const Real* R = cam.R;
  Real dp[3] = {0, 0, 0};  // dL/d(world position)
  Real dt[3] = {0, 0, 0};  // dL/d(camera-space position tx0, ty0, tz)

  // Opacity: o = sigmoid(logit).
  out.opacity[slot] += g.opacity * o.opacity * (Real(1) - o.opacity);

  // Colour: rgb = max(sum_k b_k(dir) c_k + 0.5, 0).
  {
    Real basis[16], bx[16], by[16], bz[16];
    sh_basis(degree, o.dir[0], o.dir[1], o.dir[2], basis);
    sh_basis_grad(degree, o.dir[0], o.dir[1], o.dir[2], bx, by, bz);
    const int K = (degree + 1) * (degree + 1);
    const int K_all = sh_coeff_count(P.sh_degree);
    const Real* coeffs = P.sh + size_t(i) * K_all * 3;
    Real* dsh = out.sh.data() + slot * size_t(K_all) * 3;
    Real ddir[3] = {0, 0, 0};
    for (int ch = 0; ch < 3; ++ch) {
      const Real gc = o.raw_rgb[ch] > Real(0) ? g.rgb[ch] : Real(0);
      if (gc == Real(0)) continue;
      for (int k = 0; k < K; ++k) {
        dsh[3 * k + ch] += basis[k] * gc;
        ddir[0] += bx[k] * coeffs[3 * k + ch] * gc;
        ddir[1] += by[k] * coeffs[3 * k + ch] * gc;
        ddir[2] += bz[k] * coeffs[3 * k + ch] * gc;
      }
    }
    if (o.dir_norm > 0) {
      // dir = v / |v|: d dir / dv = (I - dir dir^T) / |v|.
      const Real d = ddir[0] * o.dir[0] + ddir[1] * o.dir[1] + ddir[2] * o.dir[2];
      for (int k = 0; k < 3; ++k) dp[k] += (ddir[k] - o.dir[k] * d) / o.dir_norm;
    }
  }

  // Mean: mean_x = fx tx0 / tz + cx, mean_y = fy ty0 / tz + cy.
  const BasicFootprint<Real>& fp = o.fp;
  const Real inv_z = Real(1) / fp.depth;
  dt[0] += g.mean[0] * cam.fx * inv_z;
  dt[1] += g.mean[1] * cam.fy * inv_z;
  dt[2] -= (g.mean[0] * cam.fx * fp.tx0 + g.mean[1] * cam.fy * fp.ty0) * inv_z * inv_z;

  // Conic = inverse of V = [[a, b], [b, c]]: dL/dV = -Q Gq Q with Gq the symmetric matrix
  // gradient of Q (its off-diagonal entry appears twice, hence the halves).
  const Real Q[4] = {fp.conic_a, fp.conic_b, fp.conic_b, fp.conic_c};
  const Real Gq[4] = {g.conic[0], Real(0.5) * g.conic[1], Real(0.5) * g.conic[1], g.conic[2]};
  Real QG[4], GV[4];
  QG[0] = Q[0] * Gq[0] + Q[1] * Gq[2]; QG[1] = Q[0] * Gq[1] + Q[1] * Gq[3];
  QG[2] = Q[2] * Gq[0] + Q[3] * Gq[2]; QG[3] = Q[2] * Gq[1] + Q[3] * Gq[3];
  GV[0] = -(QG[0] * Q[0] + QG[1] * Q[2]); GV[1] = -(QG[0] * Q[1] + QG[1] * Q[3]);
  GV[2] = -(QG[2] * Q[0] + QG[3] * Q[2]); GV[3] = -(QG[2] * Q[1] + QG[3] * Q[3]);
  // V = T Sigma T^T + blur I: dL/dSigma = T^T GV T, dL/dT = 2 GV T Sigma.
  const Real* Tm[2] = {fp.T0, fp.T1};
  Real GS[9];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      Real s = 0;
      for (int u = 0; u < 2; ++u)
        for (int v = 0; v < 2; ++v) s += Tm[u][r] * GV[2 * u + v] * Tm[v][c];
      GS[3 * r + c] = s;
    }
  const Real S[9] = {o.cov.cov[0], o.cov.cov[1], o.cov.cov[2], o.cov.cov[1], o.cov.cov[3], o.cov.cov[4], o.cov.cov[2], o.cov.cov[4], o.cov.cov[5]};
  Real TS[2][3];
  for (int u = 0; u < 2; ++u)
    for (int c = 0; c < 3; ++c) TS[u][c] = Tm[u][0] * S[c] + Tm[u][1] * S[3 + c] + Tm[u][2] * S[6 + c];
  Real dT[2][3];
  for (int u = 0; u < 2; ++u)
    for (int c = 0; c < 3; ++c) dT[u][c] = 2 * (GV[2 * u] * TS[0][c] + GV[2 * u + 1] * TS[1][c]);
  // T0 = j00 W0 + j02 W2, T1 = j11 W1 + j12 W2 (W = camera rotation rows).
  const Real dj00 = dT[0][0] * R[0] + dT[0][1] * R[1] + dT[0][2] * R[2];
  const Real dj02 = dT[0][0] * R[6] + dT[0][1] * R[7] + dT[0][2] * R[8];
  const Real dj11 = dT[1][0] * R[3] + dT[1][1] * R[4] + dT[1][2] * R[5];
  const Real dj12 = dT[1][0] * R[6] + dT[1][1] * R[7] + dT[1][2] * R[8];
  const Real iz2 = inv_z * inv_z, iz3 = iz2 * inv_z;
  // j00 = fx / tz, j11 = fy / tz.
  dt[2] += -(cam.fx * dj00 + cam.fy * dj11) * iz2;
  // j02 = -fx tx / tz^2 with tx = tx0 (free) or lim * tz (clamped: j02 = -fx lim / tz).
  if (fp.clamp_x) {
    dt[2] += dj02 * cam.fx * fp.txtz * iz2;
  } else {
    dt[0] += -dj02 * cam.fx * iz2;
    dt[2] += dj02 * 2 * cam.fx * fp.tx0 * iz3;
  }
  if (fp.clamp_y) {
    dt[2] += dj12 * cam.fy * fp.tytz * iz2;
  } else {
    dt[1] += -dj12 * cam.fy * iz2;
    dt[2] += dj12 * 2 * cam.fy * fp.ty0 * iz3;
  }
  // t = R p + t_cam.
  for (int k = 0; k < 3; ++k) dp[k] += R[k] * dt[0] + R[3 + k] * dt[1] + R[6 + k] * dt[2];
  for (int k = 0; k < 3; ++k) out.positions[3 * slot + k] += dp[k];

  // Sigma = M M^T, M = Rq diag(s): dL/dM = (GS + GS^T) M.
  Real dM[9];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      Real s = 0;
      for (int k = 0; k < 3; ++k) s += (GS[3 * r + k] + GS[3 * k + r]) * o.cov.M[3 * k + c];
      dM[3 * r + c] = s;
    }
  Real dR[9];
  for (int c = 0; c < 3; ++c) {
    Real ds = 0;
    for (int r = 0; r < 3; ++r) {
      ds += dM[3 * r + c] * o.cov.rot[3 * r + c];
      dR[3 * r + c] = dM[3 * r + c] * o.cov.s[c];
    }
    out.scales[3 * slot + c] += ds * o.cov.s[c];  // d/d(log s) = s d/ds
  }
  Real dq[4];
  quat_to_rotmat_vjp(o.cov.qn, o.cov.qnorm, dR, dq);
  for (int k = 0; k < 4; ++k) out.rotations[4 * slot + k] += dq[k];
}

// A projected Gaussian as the pixel pass reads it.
template <typename Real>
struct DSplat {
  Real mx, my, A, B, C, opacity, rgb[3];
  uint32_t index;
  int32_t slot;
  int px0, py0, px1, py1;  // pixel box outside which alpha < 1/255 (inclusive)
  int tx0, ty0, tx1, ty1;  // tile rectangle
};

// Screen footprint and pixel/tile boxes exactly as the forward rasteriser computes them.
template <typename Real>
bool make_splat(const Projected<Real>& f, size_t i, int32_t slot, int width, int height, int grid_x, int grid_y,
                DSplat<Real>& out) {
  const float r = float(f.fp.radius);
  const float mxf = float(f.fp.mean_x), myf = float(f.fp.mean_y);
  const int rx0 = std::min(grid_x, std::max(0, int((mxf - r) / kTileSize)));
  const int ry0 = std::min(grid_y, std::max(0, int((myf - r) / kTileSize)));
  const int rx1 = std::min(grid_x, std::max(0, int((mxf + r + kTileSize - 1) / kTileSize)));
  const int ry1 = std::min(grid_y, std::max(0, int((myf + r + kTileSize - 1) / kTileSize)));
  if ((rx1 - rx0) * (ry1 - ry0) == 0) return false;
  const float level = 2.f * std::log(255.f * float(f.opacity));
  const float ex = std::sqrt(std::max(0.f, level * float(f.fp.cov_a))) * 1.001f + 0.01f;
  const float ey = std::sqrt(std::max(0.f, level * float(f.fp.cov_c))) * 1.001f + 0.01f;
  out.px0 = std::max(0, int(std::ceil(mxf - ex)));
  out.px1 = std::min(width - 1, int(std::floor(mxf + ex)));
  out.py0 = std::max(0, int(std::ceil(myf - ey)));
  out.py1 = std::min(height - 1, int(std::floor(myf + ey)));
  if (out.px0 > out.px1 || out.py0 > out.py1) return false;
  out.tx0 = std::max(rx0, out.px0 / kTileSize);
  out.tx1 = std::min(rx1, out.px1 / kTileSize + 1);
  out.ty0 = std::max(ry0, out.py0 / kTileSize);
  out.ty1 = std::min(ry1, out.py1 / kTileSize + 1);
  if (out.tx0 >= out.tx1 || out.ty0 >= out.ty1) return false;
  out.mx = f.fp.mean_x;
  out.my = f.fp.mean_y;
  out.A = f.fp.conic_a;
  out.B = f.fp.conic_b;
  out.C = f.fp.conic_c;
  out.opacity = f.opacity;
  for (int c = 0; c < 3; ++c) out.rgb[c] = f.rgb[c];
  out.index = uint32_t(i);
  out.slot = slot;
  return true;
}

// Alpha of splat g at pixel (x, y); false when the pixel is skipped (the INRIA rules:
// power > 0 or alpha < 1/255). `G` receives exp(power), `clamped` whether alpha_max hit.
template <typename Real>
inline bool pixel_alpha(const DSplat<Real>& g, int x, int y, Real alpha_max, Real& alpha, Real& G, Real& dx, Real& dy,
                        bool& clamped) {
  dx = g.mx - Real(x);
  dy = g.my - Real(y);
  const Real power = Real(-0.5) * g.A * dx * dx + Real(-0.5) * g.C * dy * dy - g.B * dx * dy;
  if (power > Real(0)) return false;
  G = std::exp(power);
  const Real a = g.opacity * G;
  clamped = !(a < alpha_max);
  alpha = clamped ? alpha_max : a;
  return alpha >= Real(kMinAlpha);
}

}  // namespace

template <typename Real>
struct DiffRender<Real>::State {
  std::vector<DSplat<Real>> splats;   // visible Gaussians in depth order
  std::vector<uint32_t> tile_start;   // tiles + 1
  std::vector<uint32_t> tile_list;    // per tile: indices into splats, front to back
  std::vector<uint32_t> last;         // per pixel: 1 + position (in its tile list) of the last contributor
  std::vector<uint32_t> diff_splats;  // indices into splats of the slotted Gaussians
};

template <typename Real>
DiffRender<Real>::DiffRender() = default;
template <typename Real>
DiffRender<Real>::~DiffRender() = default;
template <typename Real>
DiffRender<Real>::DiffRender(DiffRender&&) noexcept = default;
template <typename Real>
DiffRender<Real>& DiffRender<Real>::operator=(DiffRender&&) noexcept = default;

GaussianParams<float> params_of(const GaussianScene& scene) {
  GaussianParams<float> p;
  p.count = scene.size();
  p.sh_degree = scene.sh_degree;
  p.positions = scene.positions.data();
  p.sh = scene.sh.data();
  p.opacity = scene.opacity.data();
  p.scales = scene.scales.data();
  p.rotations = scene.rotations.data();
  return p;
}

template <typename Real>
void GaussianGrads<Real>::resize(size_t slots, int degree) {
  sh_degree = degree;
  positions.assign(3 * slots, 0);
  sh.assign(slots * sh_coeff_count(degree) * 3, 0);
  opacity.assign(slots, 0);
  scales.assign(3 * slots, 0);
  rotations.assign(4 * slots, 0);
}

template <typename Real>
void GaussianGrads<Real>::zero() {
  std::fill(positions.begin(), positions.end(), Real(0));
  std::fill(sh.begin(), sh.end(), Real(0));
  std::fill(opacity.begin(), opacity.end(), Real(0));
  std::fill(scales.begin(), scales.end(), Real(0));
  std::fill(rotations.begin(), rotations.end(), Real(0));
}

namespace {

template <typename Real>
int degree_for(const GaussianParams<Real>& P, const DiffRenderSettings& s) {
  return s.sh_degree < 0 ? P.sh_degree : std::min(s.sh_degree, P.sh_degree);
}

}  // namespace

template <typename Real>
void diff_render_forward(const GaussianParams<Real>& P, const Camera& camera, const std::vector<int32_t>& slot,
                         const DiffRenderSettings& s, DiffRender<Real>& out) {
  if (camera.width <= 0 || camera.height <= 0) throw Error("diff render: camera has zero image size");
  if (slot.size() != P.count) throw Error("diff render: slot table does not match the Gaussian count");
  const int W = camera.width, H = camera.height;
  const int grid_x = (W + kTileSize - 1) / kTileSize, grid_y = (H + kTileSize - 1) / kTileSize;
  const size_t tiles = size_t(grid_x) * grid_y;
  const int degree = degree_for(P, s);
  const DiffCamera<Real> cam(camera);
  const size_t N = P.count;
  out.width = W;
  out.height = H;
  out.grid_x = grid_x;
  out.grid_y = grid_y;
  if (!out.state) out.state = std::make_unique<typename DiffRender<Real>::State>();
  auto& st = *out.state;

  // 1. Project (chunks in parallel, concatenated in index order).
  constexpr size_t kChunk = 16384;
  const size_t chunks = (N + kChunk - 1) / kChunk;
  std::vector<std::vector<DSplat<Real>>> chunk_out(chunks);
  parallel_for(chunks, s.threads, [&](int, size_t c) {
    std::vector<DSplat<Real>> v;  // a local, moved in at the end: the chunks' vectors share cache lines
    Projected<Real> f;
    DSplat<Real> sp;
    for (size_t i = c * kChunk, e = std::min(N, (c + 1) * kChunk); i < e; ++i)
      if (project_gaussian(P, i, cam, Real(s.near_plane), Real(s.blur), degree, f) &&
          make_splat(f, i, slot[i], W, H, grid_x, grid_y, sp))
        v.push_back(sp);
    chunk_out[c] = std::move(v);
  });
  size_t visible = 0;
  for (const auto& v : chunk_out) visible += v.size();
  // 2. Depth sort (stable radix sort of the float depth bits, as the rasteriser does).
  std::vector<uint32_t> keys(visible), order(visible);
  std::vector<const DSplat<Real>*> flat(visible);
  {
    size_t k = 0;
    for (const auto& v : chunk_out)
      for (const auto& sp : v) {
        // Recompute the depth key from the position (the splat does not keep it).
        const Real* p = P.positions + 3 * sp.index;
        const float depth = float(cam.R[6] * p[0] + cam.R[7] * p[1] + cam.R[8] * p[2] + cam.t[2]);
        std::memcpy(&keys[k], &depth, 4);
        order[k] = uint32_t(k);
        flat[k++] = &sp;
      }
  }
  radix_sort_pairs(keys, order);
  auto& splats = st.splats;
  splats.resize(visible);
  for (size_t j = 0; j < visible; ++j) splats[j] = *flat[order[j]];
  st.diff_splats.clear();
  for (size_t j = 0; j < visible; ++j)
    if (splats[j].slot >= 0) st.diff_splats.push_back(uint32_t(j));
  out.visible = visible;
  out.diff_visible = st.diff_splats.size();

  // 3. Active tiles and binning.
  out.tile_active.assign(tiles, s.only_diff_tiles ? 0 : 1);
  if (s.only_diff_tiles)
    for (uint32_t j : st.diff_splats) {
      const auto& g = splats[j];
      for (int ty = g.ty0; ty < g.ty1; ++ty)
        for (int tx = g.tx0; tx < g.tx1; ++tx) out.tile_active[size_t(ty) * grid_x + tx] = 1;
    }
  auto& tile_start = st.tile_start;
  tile_start.assign(tiles + 1, 0);
  for (const auto& g : splats)
    for (int ty = g.ty0; ty < g.ty1; ++ty)
      for (int tx = g.tx0; tx < g.tx1; ++tx) {
        const size_t t = size_t(ty) * grid_x + tx;
        if (out.tile_active[t]) ++tile_start[t + 1];
      }
  for (size_t t = 0; t < tiles; ++t) tile_start[t + 1] += tile_start[t];
  auto& tile_list = st.tile_list;
  tile_list.resize(tile_start[tiles]);
  {
    std::vector<uint32_t> fill(tile_start.begin(), tile_start.end() - 1);
    for (size_t k = 0; k < splats.size(); ++k) {
      const auto& g = splats[k];
      for (int ty = g.ty0; ty < g.ty1; ++ty)
        for (int tx = g.tx0; tx < g.tx1; ++tx) {
          const size_t t = size_t(ty) * grid_x + tx;
          if (out.tile_active[t]) tile_list[fill[t]++] = uint32_t(k);
        }
    }
  }

  // 4. Blend, tile by tile; Gaussian-major within a tile like the rasteriser.
  out.color.assign(size_t(W) * H * 3, Real(0));
  out.transmittance.assign(size_t(W) * H, Real(1));
  st.last.assign(size_t(W) * H, 0);
  const Real alpha_max = Real(s.alpha_max);
  parallel_for(tiles, s.threads, [&](int, size_t t) {
    const int tx = int(t % grid_x), ty = int(t / grid_x);
    const int x_begin = tx * kTileSize, y_begin = ty * kTileSize;
    const int x_end = std::min(W, x_begin + kTileSize), y_end = std::min(H, y_begin + kTileSize);
    if (!out.tile_active[t]) {
      for (int y = y_begin; y < y_end; ++y)
        for (int x = x_begin; x < x_end; ++x)
          for (int c = 0; c < 3; ++c) out.color[(size_t(y) * W + x) * 3 + c] = Real(s.background[c]);
      return;
    }
    Real T[kTilePixels], C[3][kTilePixels];
    uint32_t last[kTilePixels];
    uint8_t done[kTilePixels];
    std::fill(T, T + kTilePixels, Real(1));
    for (auto& c : C) std::fill(c, c + kTilePixels, Real(0));
    std::fill(last, last + kTilePixels, 0u);
    std::fill(done, done + kTilePixels, uint8_t(0));
    const int pixels = (x_end - x_begin) * (y_end - y_begin);
    int finished = 0;
    const uint32_t* list = tile_list.data() + tile_start[t];
    const size_t count = tile_start[t + 1] - tile_start[t];
    for (size_t n = 0; n < count && finished < pixels; ++n) {
      const auto& g = splats[list[n]];
      const int x0 = std::max(g.px0, x_begin), x1 = std::min(g.px1, x_end - 1);
      const int y0 = std::max(g.py0, y_begin), y1 = std::min(g.py1, y_end - 1);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const int k = (y - y_begin) * kTileSize + (x - x_begin);
          if (done[k]) continue;
          Real alpha, G, dx, dy;
          bool clamped;
          if (!pixel_alpha(g, x, y, alpha_max, alpha, G, dx, dy, clamped)) continue;
          const Real test_T = T[k] * (Real(1) - alpha);
          if (test_T < Real(kMinTransmittance)) {
            done[k] = 1;
            ++finished;
            continue;
          }
          const Real w = alpha * T[k];
          for (int c = 0; c < 3; ++c) C[c][k] += w * g.rgb[c];
          T[k] = test_T;
          last[k] = uint32_t(n + 1);
        }
    }
    for (int y = y_begin; y < y_end; ++y)
      for (int x = x_begin; x < x_end; ++x) {
        const int k = (y - y_begin) * kTileSize + (x - x_begin);
        const size_t p = size_t(y) * W + x;
        out.transmittance[p] = T[k];
        st.last[p] = last[k];
        for (int c = 0; c < 3; ++c) out.color[3 * p + c] = C[c][k] + T[k] * Real(s.background[c]);
      }
  });
}

template <typename Real>
void diff_render_backward(const GaussianParams<Real>& P, const Camera& camera, const std::vector<int32_t>& slot,
                          const DiffRenderSettings& s, const DiffRender<Real>& fwd, const Real* dL_dcolor,
                          GaussianGrads<Real>& grads) {
  if (!fwd.state) throw Error("diff render: backward pass without a forward pass");
  if (camera.width != fwd.width || camera.height != fwd.height)
    throw Error("diff render: backward camera does not match the forward pass");
  if (slot.size() != P.count) throw Error("diff render: slot table does not match the Gaussian count");
  if (grads.sh_degree != P.sh_degree) throw Error("diff render: gradient buffers have another SH degree");
  const auto& st = *fwd.state;
  const int W = fwd.width, H = fwd.height, grid_x = fwd.grid_x;
  const size_t tiles = size_t(fwd.grid_x) * fwd.grid_y;
  const Real alpha_max = Real(s.alpha_max);
  const Real bg[3] = {Real(s.background[0]), Real(s.background[1]), Real(s.background[2])};
  const auto& splats = st.splats;

  // 1. Pixel pass: per tile, back to front, screen-space gradients of slotted splats.
  struct TileGrad {
    uint32_t splat;
    ScreenGrad<Real> g;
  };
  std::vector<std::vector<TileGrad>> tile_grads(tiles);
  parallel_for(tiles, s.threads, [&](int, size_t t) {
    if (!fwd.tile_active[t]) return;
    const uint32_t* list = st.tile_list.data() + st.tile_start[t];
    const size_t count = st.tile_start[t + 1] - st.tile_start[t];
    size_t front = count;  // first slotted splat in the list
    for (size_t n = 0; n < count; ++n)
      if (splats[list[n]].slot >= 0) {
        front = n;
        break;
      }
    if (front == count) return;
    const int tx = int(t % grid_x), ty = int(t / grid_x);
    const int x_begin = tx * kTileSize, y_begin = ty * kTileSize;
    const int x_end = std::min(W, x_begin + kTileSize), y_end = std::min(H, y_begin + kTileSize);
    Real T[kTilePixels], S[3][kTilePixels], dC[3][kTilePixels], Tbg[3][kTilePixels];
    uint32_t last[kTilePixels];
    uint32_t max_last = 0;
    for (int k = 0; k < kTilePixels; ++k) last[k] = 0;
    for (int y = y_begin; y < y_end; ++y)
      for (int x = x_begin; x < x_end; ++x) {
        const int k = (y - y_begin) * kTileSize + (x - x_begin);
        const size_t p = size_t(y) * W + x;
        T[k] = fwd.transmittance[p];
        last[k] = st.last[p];
        max_last = std::max(max_last, last[k]);
        for (int c = 0; c < 3; ++c) {
          S[c][k] = 0;
          dC[c][k] = dL_dcolor[3 * p + c];
          Tbg[c][k] = T[k] * bg[c];
        }
      }
    auto out = std::move(tile_grads[t]);  // grown as a local: neighbouring tiles' lists share cache lines
    for (size_t n = max_last; n-- > front;) {
      const auto& g = splats[list[n]];
      const bool diff = g.slot >= 0;
      ScreenGrad<Real> acc;
      bool touched = false;
      const int x0 = std::max(g.px0, x_begin), x1 = std::min(g.px1, x_end - 1);
      const int y0 = std::max(g.py0, y_begin), y1 = std::min(g.py1, y_end - 1);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const int k = (y - y_begin) * kTileSize + (x - x_begin);
          if (n >= last[k]) continue;
          Real alpha, G, dx, dy;
          bool clamped;
          if (!pixel_alpha(g, x, y, alpha_max, alpha, G, dx, dy, clamped)) continue;
          const Real one_minus = Real(1) - alpha;
          const Real Tb = T[k] / one_minus;  // transmittance in front of this splat
          if (diff) {
            touched = true;
            const Real w = alpha * Tb;
            Real d_alpha = 0;
            for (int c = 0; c < 3; ++c) {
              acc.rgb[c] += w * dC[c][k];
              d_alpha += dC[c][k] * (Tb * g.rgb[c] - (S[c][k] + Tbg[c][k]) / one_minus);
            }
            if (!clamped) {
              acc.opacity += d_alpha * G;
              // alpha = o exp(power): d alpha / d power = alpha.
              const Real dp = d_alpha * alpha;
              acc.conic[0] += dp * Real(-0.5) * dx * dx;
              acc.conic[1] += -dp * dx * dy;
              acc.conic[2] += dp * Real(-0.5) * dy * dy;
              acc.mean[0] += -dp * (g.A * dx + g.B * dy);
              acc.mean[1] += -dp * (g.C * dy + g.B * dx);
            }
          }
          for (int c = 0; c < 3; ++c) S[c][k] += g.rgb[c] * alpha * Tb;
          T[k] = Tb;
        }
      if (diff && touched) out.push_back({list[n], acc});
    }
    tile_grads[t] = std::move(out);
  });

  // 2. Reduce per splat in tile order (deterministic), then chain to the parameters.
  std::vector<int32_t> pos_of_splat(splats.size(), -1);
  for (size_t j = 0; j < st.diff_splats.size(); ++j) pos_of_splat[st.diff_splats[j]] = int32_t(j);
  std::vector<ScreenGrad<Real>> screen(st.diff_splats.size());
  for (size_t t = 0; t < tiles; ++t)
    for (const auto& tg : tile_grads[t]) {
      ScreenGrad<Real>& d = screen[pos_of_splat[tg.splat]];
      for (int k = 0; k < 2; ++k) d.mean[k] += tg.g.mean[k];
      for (int k = 0; k < 3; ++k) d.conic[k] += tg.g.conic[k];
      d.opacity += tg.g.opacity;
      for (int k = 0; k < 3; ++k) d.rgb[k] += tg.g.rgb[k];
    }
  const DiffCamera<Real> cam(camera);
  const int degree = degree_for(P, s);
  parallel_for(st.diff_splats.size(), s.threads, [&](int, size_t j) {
    const auto& sp = splats[st.diff_splats[j]];
    Projected<Real> f;
    if (!project_gaussian(P, sp.index, cam, Real(s.near_plane), Real(s.blur), degree, f)) return;
    if (size_t(sp.slot) >= grads.slots()) throw Error("diff render: slot outside the gradient buffers");
    project_gaussian_backward(P, sp.index, cam, degree, f, screen[j], grads, size_t(sp.slot));
  });
}

template struct GaussianGrads<float>;
template struct GaussianGrads<double>;
template class DiffRender<float>;
template class DiffRender<double>;
template void diff_render_forward<float>(const GaussianParams<float>&, const Camera&, const std::vector<int32_t>&,
                                         const DiffRenderSettings&, DiffRender<float>&);
template void diff_render_forward<double>(const GaussianParams<double>&, const Camera&, const std::vector<int32_t>&,
                                          const DiffRenderSettings&, DiffRender<double>&);
template void diff_render_backward<float>(const GaussianParams<float>&, const Camera&, const std::vector<int32_t>&,
                                          const DiffRenderSettings&, const DiffRender<float>&, const float*,
                                          GaussianGrads<float>&);
template void diff_render_backward<double>(const GaussianParams<double>&, const Camera&, const std::vector<int32_t>&,
                                           const DiffRenderSettings&, const DiffRender<double>&, const double*,
                                           GaussianGrads<double>&);

}  // namespace isegman
