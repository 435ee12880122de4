#include "core/image.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace isegman {

double psnr(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height || a.channels != b.channels)
    throw Error("psnr: images differ in shape");
  double se = 0;
  for (size_t i = 0; i < a.data.size(); ++i) {
    // Compared as displayable images: both clamped to [0, 1], as a saved render is.
    double d = std::clamp(double(a.data[i]), 0.0, 1.0) - std::clamp(double(b.data[i]), 0.0, 1.0);
    se += d * d;
  }
  double mse = se / double(a.data.size());
  if (mse <= 0) return std::numeric_limits<double>::infinity();
  return -10.0 * std::log10(mse);
}

Image resize_image(const Image& src, int width, int height) {
  if (width <= 0 || height <= 0) throw Error("resize_image: zero-size target");
  Image cur = src;
  // Halve with a box filter while more than 2x too large: keeps thin details stable.
  while (cur.width >= 2 * width * 2 && cur.height >= 2 * height * 2) {
    Image half(cur.width / 2, cur.height / 2, cur.channels);
    for (int y = 0; y < half.height; ++y)
      for (int x = 0; x < half.width; ++x)
        for (int c = 0; c < cur.channels; ++c)
          half.at(x, y, c) = 0.25f * (cur.at(2 * x, 2 * y, c) + cur.at(2 * x + 1, 2 * y, c) +
                                      cur.at(2 * x, 2 * y + 1, c) + cur.at(2 * x + 1, 2 * y + 1, c));
    cur = std::move(half);
  }
  Image out(width, height, cur.channels);
  const double sx = double(cur.width) / width, sy = double(cur.height) / height;
  for (int y = 0; y < height; ++y) {
    double fy = std::clamp((y + 0.5) * sy - 0.5, 0.0, double(cur.height - 1));
    int y0 = int(fy), y1 = std::min(y0 + 1, cur.height - 1);
    float wy = float(fy - y0);
    for (int x = 0; x < width; ++x) {
      double fx = std::clamp((x + 0.5) * sx - 0.5, 0.0, double(cur.width - 1));
      int x0 = int(fx), x1 = std::min(x0 + 1, cur.width - 1);
      float wx = float(fx - x0);
      for (int c = 0; c < cur.channels; ++c)
        out.at(x, y, c) = (1 - wy) * ((1 - wx) * cur.at(x0, y0, c) + wx * cur.at(x1, y0, c)) +
                          wy * ((1 - wx) * cur.at(x0, y1, c) + wx * cur.at(x1, y1, c));
    }
  }
  return out;
}

}  // namespace isegman
