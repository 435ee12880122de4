#include "segment/corrective_click.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"

namespace isegman::segment {
namespace {

// Chamfer (3-4) distance, in pixels, from each pixel of `in` to the nearest pixel outside
// it or outside the image; 0 outside `in`.
std::vector<float> inner_distance(const std::vector<uint8_t>& in, int w, int h) {
  constexpr float kFar = 1e9f;
  std::vector<float> d(in.size());
  for (size_t i = 0; i < in.size(); ++i) d[i] = in[i] ? kFar : 0.f;
  auto at = [&](int x, int y) { return x < 0 || y < 0 || x >= w || y >= h ? 0.f : d[size_t(y) * w + x]; };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float& v = d[size_t(y) * w + x];
      if (v == 0.f) continue;
      v = std::min({v, at(x - 1, y) + 3, at(x, y - 1) + 3, at(x - 1, y - 1) + 4, at(x + 1, y - 1) + 4});
    }
  for (int y = h - 1; y >= 0; --y)
    for (int x = w - 1; x >= 0; --x) {
      float& v = d[size_t(y) * w + x];
      if (v == 0.f) continue;
      v = std::min({v, at(x + 1, y) + 3, at(x, y + 1) + 3, at(x + 1, y + 1) + 4, at(x - 1, y + 1) + 4});
    }
  for (float& v : d) v /= 3.f;
  return d;
}

}  // namespace

std::optional<Click> corrective_click(const Image& truth, const Image& selection, double min_depth) {
  if (truth.width != selection.width || truth.height != selection.height || truth.channels != 1 ||
      selection.channels != 1)
    throw Error("corrective click: the truth and the selection masks differ in size");
  const int w = truth.width, h = truth.height;
  std::vector<uint8_t> missed(truth.data.size()), extra(truth.data.size());
  for (size_t i = 0; i < truth.data.size(); ++i) {
    const bool t = truth.data[i] > 0.5f, s = selection.data[i] > 0.5f;
    missed[i] = t && !s;
    extra[i] = s && !t;
  }
  const std::vector<float> dm = inner_distance(missed, w, h), de = inner_distance(extra, w, h);
  const auto im = std::max_element(dm.begin(), dm.end()), ie = std::max_element(de.begin(), de.end());
  const bool positive = *im >= *ie;
  const float depth = positive ? *im : *ie;
  if (!(depth >= min_depth)) return std::nullopt;
  const size_t i = size_t(positive ? im - dm.begin() : ie - de.begin());
  return Click{double(i % size_t(w)) + 0.5, double(i / size_t(w)) + 0.5, positive ? 1 : 0};
}

}  // namespace isegman::segment
