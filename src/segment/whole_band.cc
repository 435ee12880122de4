#include "segment/whole_band.h"

#include <algorithm>
#include <vector>

#include "core/error.h"

namespace isegman::segment {
namespace {

size_t area(const Mask& m) {
  return size_t(std::count_if(m.data.begin(), m.data.end(), [](uint8_t v) { return v != 0; }));
}

}  // namespace

Image whole_band(const models::SegmentResult& r, int c, const Mask* cut, double max_growth, double min_score) {
  if (r.candidates.size() < 2) return {};
  const Mask& m = r.candidates[size_t(c)];
  const size_t a = area(m);
  Image band;
  for (size_t o = 0; o < r.candidates.size(); ++o) {
    const Mask& w = r.candidates[o];
    if (int(o) == c || r.candidate_scores[o] < min_score || w.data.size() != m.data.size()) continue;
    const size_t wa = area(w);
    if (wa <= a || double(wa) > max_growth * double(a)) continue;
    size_t inside = 0;
    for (size_t i = 0; i < m.data.size(); ++i) inside += m.data[i] && w.data[i];
    if (double(inside) < 0.9 * double(a)) continue;
    if (band.empty()) band = Image(m.width, m.height, 1);
    for (size_t i = 0; i < m.data.size(); ++i)
      if (w.data[i] && !m.data[i] && !(cut && cut->data[i])) band.data[i] = 1.f;
  }
  return band;
}

size_t clear_band_beyond_part(Image& band, const Image& mask, const Image& depth, const Image& alpha,
                              const BandBeyondPart& o) {
  if (band.empty()) return 0;
  const int W = band.width, H = band.height;
  for (const Image* im : {&mask, &depth, &alpha})
    if (im->width != W || im->height != H || im->channels != 1)
      throw Error("clear_band_beyond_part: mask, depth and alpha must be one channel at the band's size");
  // Mask pixels counted per window by a summed-area table: inner pixels have the whole
  // (2 erosion + 1)^2 window (clipped at the image's edge) in the mask.
  const size_t stride = size_t(W) + 1;
  std::vector<int> sat(stride * (size_t(H) + 1), 0);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      sat[(size_t(y) + 1) * stride + x + 1] = sat[size_t(y) * stride + x + 1] + sat[(size_t(y) + 1) * stride + x] -
                                              sat[size_t(y) * stride + x] + (mask.data[size_t(y) * W + x] > 0.5f);
  const int e = std::max(0, o.erosion);
  std::vector<float> inner;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const size_t i = size_t(y) * W + x;
      if (!(mask.data[i] > 0.5f && alpha.data[i] > 0.5f)) continue;
      const int x0 = std::max(0, x - e), x1 = std::min(W, x + e + 1), y0 = std::max(0, y - e), y1 = std::min(H, y + e + 1);
      const int n = sat[size_t(y1) * stride + x1] - sat[size_t(y0) * stride + x1] - sat[size_t(y1) * stride + x0] +
                    sat[size_t(y0) * stride + x0];
      if (n == (x1 - x0) * (y1 - y0)) inner.push_back(depth.data[i]);
    }
  if (inner.empty()) return 0;
  std::sort(inner.begin(), inner.end());
  const double q = std::clamp(o.quantile, 0.0, 1.0);
  const float far = inner[size_t(q * double(inner.size() - 1))] * float(1 + o.margin);
  const size_t beyond = size_t(inner.end() - std::upper_bound(inner.begin(), inner.end(), far));
  if (double(beyond) < o.min_share * double(inner.size())) return 0;
  size_t cleared = 0;
  for (size_t i = 0; i < band.data.size(); ++i)
    if (band.data[i] > 0.5f && alpha.data[i] > 0.5f && depth.data[i] > far) {
      band.data[i] = 0.f;
      ++cleared;
    }
  return cleared;
}

}  // namespace isegman::segment
