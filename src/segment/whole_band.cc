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
  // Everything below happens inside the part's bounding box: no pixel outside it is inner,
  // near or a gap, and a window's part pixels all lie inside it.
  int bx0 = W, by0 = H, bx1 = -1, by1 = -1;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      if (part.data[size_t(y) * W + x] > 0.5f) {
        bx0 = std::min(bx0, x);
        bx1 = std::max(bx1, x);
        by0 = std::min(by0, y);
        by1 = std::max(by1, y);
      }
  if (bx1 < 0) return kNone;
  const int bw = bx1 - bx0 + 1, bh = by1 - by0 + 1;
  auto pixel = [&](int x, int y) { return size_t(y) * W + x; };
  auto in_part = [&](size_t i) { return part.data[i] > 0.5f && alpha.data[i] > 0.5f; };
  // Part pixels per window by a summed-area table over the box: inner pixels have the whole
  // (2 erosion + 1)^2 window (clipped at the image's edge) in the part.
  const size_t stride = size_t(bw) + 1;
  std::vector<int> sat(stride * (size_t(bh) + 1), 0);
  for (int y = 0; y < bh; ++y)
    for (int x = 0; x < bw; ++x)
      sat[(size_t(y) + 1) * stride + x + 1] = sat[size_t(y) * stride + x + 1] + sat[(size_t(y) + 1) * stride + x] -
                                              sat[size_t(y) * stride + x] + (part.data[pixel(bx0 + x, by0 + y)] > 0.5f);
  auto box_count = [&](int x0, int y0, int x1, int y1) {  // image coordinates, clipped to the box
    x0 = std::clamp(x0, bx0, bx1 + 1) - bx0, x1 = std::clamp(x1, bx0, bx1 + 1) - bx0;
    y0 = std::clamp(y0, by0, by1 + 1) - by0, y1 = std::clamp(y1, by0, by1 + 1) - by0;
    return sat[size_t(y1) * stride + x1] - sat[size_t(y0) * stride + x1] - sat[size_t(y1) * stride + x0] +
           sat[size_t(y0) * stride + x0];
  };
  const int e = std::max(0, o.erosion);
  std::vector<uint8_t> inner(size_t(bw) * bh, 0);  // box-local
  std::vector<float> depths;
  for (int y = by0; y <= by1; ++y)
    for (int x = bx0; x <= bx1; ++x) {
      const size_t i = pixel(x, y);
      if (!in_part(i)) continue;
      const int x0 = std::max(0, x - e), x1 = std::min(W, x + e + 1), y0 = std::max(0, y - e), y1 = std::min(H, y + e + 1);
      if (box_count(x0, y0, x1, y1) == (x1 - x0) * (y1 - y0)) {
        inner[size_t(y - by0) * bw + (x - bx0)] = 1;
        depths.push_back(depth.data[i]);
      }
    }
  if (depths.empty()) return kNone;
  // The quantile is the k-th smallest: nth_element finds the value a full sort puts there.
  const size_t k = size_t(std::clamp(o.quantile, 0.0, 1.0) * double(depths.size() - 1));
  std::nth_element(depths.begin(), depths.begin() + std::ptrdiff_t(k), depths.end());
  const float far = depths[k] * float(1 + o.margin);
  // A gap: an inner pixel beyond the far side with the part's nearer pixels on both sides
  // within max_gap along its row or its column. A surface beside the object that the part
  // takes in (the wall by a post) is beyond it on one side only.
  const int reach = std::max(1, int(std::lround(o.max_gap * double(std::max(W, H)))));
  std::vector<uint8_t> near(size_t(bw) * bh, 0), candidate(size_t(bw) * bh, 0);
  for (int y = 0; y < bh; ++y)
    for (int x = 0; x < bw; ++x) {
      const size_t i = pixel(bx0 + x, by0 + y), b = size_t(y) * bw + x;
      near[b] = in_part(i) && depth.data[i] <= far;
      candidate[b] = inner[b] && depth.data[i] > far;
    }
  std::vector<uint8_t> gap(size_t(bw) * bh, 0);
  // Along rows: the distance back to the last near pixel and on to the next one ("none"
  // counts as beyond reach).
  std::vector<int> to_prev(size_t(std::max(bw, 1)));
  for (int y = 0; y < bh; ++y) {
    const uint8_t* nr = &near[size_t(y) * bw];
    int last = -reach - 1 - bw;
    for (int x = 0; x < bw; ++x) {
      if (nr[x]) last = x;
      to_prev[size_t(x)] = x - last;
    }
    last = 2 * bw + reach + 1;
    for (int x = bw - 1; x >= 0; --x) {
      if (nr[x]) last = x;
      const size_t b = size_t(y) * bw + x;
      if (candidate[b] && to_prev[size_t(x)] <= reach && last - x <= reach) gap[b] = 1;
    }
  }
  // Along columns, every column at once so the sweeps read rows in memory order.
  std::vector<int> last_row(size_t(bw), -reach - 1 - bh), up(size_t(bw) * bh);
  for (int y = 0; y < bh; ++y)
    for (int x = 0; x < bw; ++x) {
      const size_t b = size_t(y) * bw + x;
      if (near[b]) last_row[size_t(x)] = y;
      up[b] = y - last_row[size_t(x)];
    }
  std::fill(last_row.begin(), last_row.end(), 2 * bh + reach + 1);
  for (int y = bh - 1; y >= 0; --y)
    for (int x = 0; x < bw; ++x) {
      const size_t b = size_t(y) * bw + x;
      if (near[b]) last_row[size_t(x)] = y;
      if (candidate[b] && up[b] <= reach && last_row[size_t(x)] - y <= reach) gap[b] = 1;
    }
  std::vector<float> seen;
  for (int y = 0; y < bh; ++y)
    for (int x = 0; x < bw; ++x)
      if (gap[size_t(y) * bw + x]) seen.push_back(depth.data[pixel(bx0 + x, by0 + y)]);
  if (seen.empty() || double(seen.size()) < o.min_share * double(depths.size())) return kNone;
  const size_t q = size_t(std::clamp(o.background_quantile, 0.0, 1.0) * double(seen.size() - 1));
  std::nth_element(seen.begin(), seen.begin() + std::ptrdiff_t(q), seen.end());
  return seen[q];
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
