#include "edit/losses.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"

namespace isegman::edit {
namespace {

constexpr int kRadius = 5;  // 11x11 window
constexpr double kC1 = 0.01 * 0.01, kC2 = 0.03 * 0.03;

struct Window {
  float w[2 * kRadius + 1];
  Window() {
    double sum = 0, v[2 * kRadius + 1];
    for (int i = -kRadius; i <= kRadius; ++i) sum += v[i + kRadius] = std::exp(-double(i * i) / (2 * 1.5 * 1.5));
    for (int i = 0; i < 2 * kRadius + 1; ++i) w[i] = float(v[i] / sum);
  }
};
const Window& window() {
  static const Window w;
  return w;
}

// A single-channel float plane covering `rect` of the image; zero outside it.
struct Plane {
  PixelRect r;
  std::vector<float> v;
  explicit Plane(PixelRect rect) : r(rect), v(size_t(rect.x1 - rect.x0) * (rect.y1 - rect.y0), 0.f) {}
  float& at(int x, int y) { return v[size_t(y - r.y0) * (r.x1 - r.x0) + (x - r.x0)]; }
  float get(int x, int y) const {
    if (x < r.x0 || x >= r.x1 || y < r.y0 || y >= r.y1) return 0.f;
    return v[size_t(y - r.y0) * (r.x1 - r.x0) + (x - r.x0)];
  }
};

// Separable Gaussian filter of `in` (zero outside its rect) evaluated on `out_rect`.
Plane blur(const Plane& in, PixelRect out_rect) {
  const Window& g = window();
  PixelRect mid{out_rect.x0, in.r.y0, out_rect.x1, in.r.y1};
  Plane h(mid);
  for (int y = mid.y0; y < mid.y1; ++y)
    for (int x = mid.x0; x < mid.x1; ++x) {
      float s = 0;
      for (int k = -kRadius; k <= kRadius; ++k) s += g.w[k + kRadius] * in.get(x + k, y);
      h.at(x, y) = s;
    }
  Plane out(out_rect);
  for (int y = out_rect.y0; y < out_rect.y1; ++y)
    for (int x = out_rect.x0; x < out_rect.x1; ++x) {
      float s = 0;
      for (int k = -kRadius; k <= kRadius; ++k) s += g.w[k + kRadius] * h.get(x, y + k);
      out.at(x, y) = s;
    }
  return out;
}

PixelRect grow(PixelRect r, int by, int width, int height) {
  return {std::max(0, r.x0 - by), std::max(0, r.y0 - by), std::min(width, r.x1 + by), std::min(height, r.y1 + by)};
}

// Sum of SSIM over `map_rect` for one channel; when grad is given, adds
// d(sum SSIM)/d(a) * scale on `grad_rect`.
double ssim_channel(const float* a, const float* b, int width, int height, int channel, PixelRect grad_rect,
                    PixelRect map_rect, float* grad, double scale) {
  const PixelRect in_rect = grow(map_rect, kRadius, width, height);
  Plane x(in_rect), y(in_rect), xx(in_rect), yy(in_rect), xy(in_rect);
  for (int j = in_rect.y0; j < in_rect.y1; ++j)
    for (int i = in_rect.x0; i < in_rect.x1; ++i) {
      const size_t p = (size_t(j) * width + i) * 3 + channel;
      const float va = a[p], vb = b[p];
      x.at(i, j) = va;
      y.at(i, j) = vb;
      xx.at(i, j) = va * va;
      yy.at(i, j) = vb * vb;
      xy.at(i, j) = va * vb;
    }
  const Plane mx = blur(x, map_rect), my = blur(y, map_rect), sxx = blur(xx, map_rect), syy = blur(yy, map_rect),
              sxy = blur(xy, map_rect);
  Plane dA(map_rect), dB(map_rect), dC(map_rect);
  double sum = 0;
  for (int j = map_rect.y0; j < map_rect.y1; ++j)
    for (int i = map_rect.x0; i < map_rect.x1; ++i) {
      const double ux = mx.get(i, j), uy = my.get(i, j);
      const double vx = sxx.get(i, j) - ux * ux, vy = syy.get(i, j) - uy * uy, cxy = sxy.get(i, j) - ux * uy;
      const double N1 = 2 * ux * uy + kC1, N2 = 2 * cxy + kC2, D1 = ux * ux + uy * uy + kC1, D2 = vx + vy + kC2;
      const double s = N1 * N2 / (D1 * D2);
      sum += s;
      if (!grad) continue;
      // s(mu_x, var_x, cov_xy): partial derivatives, then through mu/var/cov to pixels.
      const double ds_dux = 2 * uy * N2 / (D1 * D2) - s * 2 * ux / D1;
      const double ds_dvx = -s / D2;
      const double ds_dcxy = 2 * N1 / (D1 * D2);
      // var_x = E[x^2] - mu_x^2, cov = E[xy] - mu_x mu_y.
      dA.at(i, j) = float(scale * (ds_dux - 2 * ux * ds_dvx - uy * ds_dcxy));
      dB.at(i, j) = float(scale * ds_dvx);
      dC.at(i, j) = float(scale * ds_dcxy);
    }
  if (grad) {
    // The window is symmetric, so the transposed filter is the same filter.
    const Plane gA = blur(dA, grad_rect), gB = blur(dB, grad_rect), gC = blur(dC, grad_rect);
    for (int j = grad_rect.y0; j < grad_rect.y1; ++j)
      for (int i = grad_rect.x0; i < grad_rect.x1; ++i) {
        const size_t p = (size_t(j) * width + i) * 3 + channel;
        grad[p] += gA.get(i, j) + 2.f * a[p] * gB.get(i, j) + b[p] * gC.get(i, j);
      }
  }
  return sum;
}

}  // namespace

LossValue image_loss(const float* render, const float* target, int width, int height, const LossSettings& settings,
                     float* grad, PixelRect region) {
  if (width <= 0 || height <= 0) throw Error("image loss: empty image");
  PixelRect g = region.empty() ? PixelRect{0, 0, width, height}
                               : PixelRect{std::max(0, region.x0), std::max(0, region.y0), std::min(width, region.x1),
                                           std::min(height, region.y1)};
  LossValue out;
  if (g.empty()) return out;
  const PixelRect map_rect = grow(g, kRadius, width, height);
  const double n = double(width) * height * 3;
  const double w_l1 = 1.0 - settings.lambda_dssim;
  double l1 = 0;
  for (int y = map_rect.y0; y < map_rect.y1; ++y)
    for (int x = map_rect.x0; x < map_rect.x1; ++x)
      for (int c = 0; c < 3; ++c) {
        const size_t p = (size_t(y) * width + x) * 3 + c;
        const float d = render[p] - target[p];
        l1 += std::abs(d);
        if (grad && x >= g.x0 && x < g.x1 && y >= g.y0 && y < g.y1)
          grad[p] += float(w_l1 / n * (d > 0 ? 1 : (d < 0 ? -1 : 0)));
      }
  out.l1 = l1 / n;
  double ssim_sum = 0;
  if (settings.lambda_dssim != 0)
    for (int c = 0; c < 3; ++c)
      ssim_sum += ssim_channel(render, target, width, height, c, g, map_rect, grad, -settings.lambda_dssim / n);
  // D-SSIM over the evaluated pixels: 1 - mean SSIM (pixels outside count as identical).
  const double map_n = double(map_rect.x1 - map_rect.x0) * (map_rect.y1 - map_rect.y0) * 3;
  out.dssim = (map_n - ssim_sum) / n;
  out.total = w_l1 * out.l1 + settings.lambda_dssim * out.dssim;
  if (settings.perceptual && settings.lambda_perceptual != 0) {
    std::vector<float> pg(size_t(width) * height * 3, 0.f);
    out.perceptual = settings.perceptual->evaluate(render, target, width, height, pg.data());
    out.total += settings.lambda_perceptual * out.perceptual;
    if (grad)
      for (int y = g.y0; y < g.y1; ++y)
        for (int x = g.x0; x < g.x1; ++x)
          for (int c = 0; c < 3; ++c) {
            const size_t p = (size_t(y) * width + x) * 3 + c;
            grad[p] += float(settings.lambda_perceptual) * pg[p];
          }
  }
  return out;
}

double ssim(const float* a, const float* b, int width, int height) {
  const PixelRect all{0, 0, width, height};
  double s = 0;
  for (int c = 0; c < 3; ++c) s += ssim_channel(a, b, width, height, c, all, all, nullptr, 0);
  return s / (double(width) * height * 3);
}

}  // namespace isegman::edit
