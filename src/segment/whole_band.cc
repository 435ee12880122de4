#include "segment/whole_band.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <string>
#include <limits>

#include "core/error.h"

namespace isegman::segment {
namespace {

void check_sizes(std::initializer_list<const Image*> images, const char* what) {
  const Image& first = **images.begin();
  for (const Image* im : images)
    if (im->width != first.width || im->height != first.height || im->channels != 1)
      throw Error(std::string(what) + ": masks, depth and alpha must be one channel at one size");
}

}  // namespace

Image whole_band(const models::SegmentResult& r, int c, const Mask* cut, double max_growth, double min_score) {
  if (r.candidates.size() < 2) return {};
  const Mask& m = r.candidates[size_t(c)];
  const size_t a = mask_area(m);
  Image band;
  for (size_t o = 0; o < r.candidates.size(); ++o) {
    const Mask& w = r.candidates[o];
    if (int(o) == c || r.candidate_scores[o] < min_score || w.data.size() != m.data.size()) continue;
    const size_t wa = mask_area(w);
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

float seen_through_depth(const Image& part, const Image& depth, const Image& alpha, const BeyondPart& o) {
  check_sizes({&part, &depth, &alpha}, "seen_through_depth");
  const int W = part.width, H = part.height;
  constexpr float kNone = std::numeric_limits<float>::infinity();
  auto in_part = [&](size_t i) { return part.data[i] > 0.5f && alpha.data[i] > 0.5f; };
  // Part pixels per window by a summed-area table: inner pixels have the whole
  // (2 erosion + 1)^2 window (clipped at the image's edge) in the part.
  const size_t stride = size_t(W) + 1;
  std::vector<int> sat(stride * (size_t(H) + 1), 0);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      sat[(size_t(y) + 1) * stride + x + 1] = sat[size_t(y) * stride + x + 1] + sat[(size_t(y) + 1) * stride + x] -
                                              sat[size_t(y) * stride + x] + (part.data[size_t(y) * W + x] > 0.5f);
  const int e = std::max(0, o.erosion);
  std::vector<uint8_t> inner(part.data.size(), 0);
  std::vector<float> depths;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const size_t i = size_t(y) * W + x;
      if (!in_part(i)) continue;
      const int x0 = std::max(0, x - e), x1 = std::min(W, x + e + 1), y0 = std::max(0, y - e), y1 = std::min(H, y + e + 1);
      const int n = sat[size_t(y1) * stride + x1] - sat[size_t(y0) * stride + x1] - sat[size_t(y1) * stride + x0] +
                    sat[size_t(y0) * stride + x0];
      if (n == (x1 - x0) * (y1 - y0)) {
        inner[i] = 1;
        depths.push_back(depth.data[i]);
      }
    }
  if (depths.empty()) return kNone;
  std::sort(depths.begin(), depths.end());
  const float far = depths[size_t(std::clamp(o.quantile, 0.0, 1.0) * double(depths.size() - 1))] * float(1 + o.margin);
  // A gap: an inner pixel beyond the far side with the part's nearer pixels on both sides
  // within max_gap along its row or its column. A surface beside the object that the part
  // takes in (the wall by a post) is beyond it on one side only.
  const int reach = std::max(1, int(std::lround(o.max_gap * double(std::max(W, H)))));
  auto near = [&](size_t i) { return in_part(i) && depth.data[i] <= far; };
  std::vector<uint8_t> gap(part.data.size(), 0);
  auto scan = [&](size_t first, size_t step, int count) {  // one row or column
    std::vector<int> to_prev(static_cast<size_t>(count)), to_next(static_cast<size_t>(count));
    int last = -reach - 1;
    for (int t = 0; t < count; ++t) {
      if (near(first + size_t(t) * step)) last = t;
      to_prev[size_t(t)] = t - last;
    }
    last = count + reach + 1;
    for (int t = count - 1; t >= 0; --t) {
      if (near(first + size_t(t) * step)) last = t;
      to_next[size_t(t)] = last - t;
    }
    for (int t = 0; t < count; ++t) {
      const size_t i = first + size_t(t) * step;
      if (inner[i] && depth.data[i] > far && to_prev[size_t(t)] <= reach && to_next[size_t(t)] <= reach) gap[i] = 1;
    }
  };
  for (int y = 0; y < H; ++y) scan(size_t(y) * W, 1, W);
  for (int x = 0; x < W; ++x) scan(size_t(x), size_t(W), H);
  std::vector<float> seen;
  for (size_t i = 0; i < gap.size(); ++i)
    if (gap[i]) seen.push_back(depth.data[i]);
  if (seen.empty() || double(seen.size()) < o.min_share * double(depths.size())) return kNone;
  std::sort(seen.begin(), seen.end());
  return seen[size_t(std::clamp(o.background_quantile, 0.0, 1.0) * double(seen.size() - 1))];
}

size_t clear_band_beyond_part(Image& band, const Image& mask, const Image& depth, const Image& alpha, const BeyondPart& o) {
  if (band.empty()) return 0;
  check_sizes({&band, &mask, &depth, &alpha}, "clear_band_beyond_part");
  const float from = seen_through_depth(mask, depth, alpha, o);
  size_t cleared = 0;
  for (size_t i = 0; i < band.data.size(); ++i)
    if (band.data[i] > 0.5f && alpha.data[i] > 0.5f && depth.data[i] >= from) {
      band.data[i] = 0.f;
      ++cleared;
    }
  return cleared;
}

size_t trim_beyond_part(std::vector<uint8_t>& mask, const models::SegmentResult& r, int chosen,
                        const std::vector<Click>& clicks, const Image& depth, const Image& alpha, const BeyondPart& o) {
  const size_t a = mask_area(mask);
  if (a == 0) return 0;
  if (mask.size() != depth.data.size() || mask.size() != alpha.data.size())
    throw Error("trim_beyond_part: the mask, depth and alpha must be of one size");
  std::vector<size_t> clicked;  // the positive clicks' pixels
  for (const Click& k : clicks) {
    if (k.label != 1) continue;
    const int x = int(std::floor(k.x)), y = int(std::floor(k.y));
    if (x < 0 || y < 0 || x >= depth.width || y >= depth.height) return 0;
    clicked.push_back(size_t(y) * size_t(depth.width) + size_t(x));
  }
  if (clicked.empty()) return 0;
  const Mask* part = nullptr;
  size_t part_area = 0;
  for (size_t c = 0; c < r.candidates.size(); ++c) {
    const Mask& p = r.candidates[c];
    if (int(c) == chosen || p.data.size() != mask.size() ||
        std::any_of(clicked.begin(), clicked.end(), [&](size_t i) { return !p.data[i]; }))
      continue;
    size_t pa = 0, inside = 0;
    for (size_t i = 0; i < mask.size(); ++i) {
      pa += p.data[i] != 0;
      inside += p.data[i] && mask[i];
    }
    if (double(pa) < o.min_part * double(a) || double(pa) > o.max_part * double(a) || double(inside) < 0.9 * double(pa) ||
        pa <= part_area)
      continue;
    part = &p;
    part_area = pa;
  }
  if (!part) return 0;
  const float from = seen_through_depth(to_image(*part), depth, alpha, o);
  size_t cleared = 0;
  for (size_t i = 0; i < mask.size(); ++i)
    if (mask[i] && !part->data[i] && alpha.data[i] > 0.5f && depth.data[i] >= from) {
      mask[i] = 0;
      ++cleared;
    }
  return cleared;
}

}  // namespace isegman::segment
