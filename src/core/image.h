// A float image, row-major, interleaved channels, values nominally in [0, 1].
#pragma once

#include <cstddef>
#include <vector>

namespace isegman {

struct Image {
  int width = 0, height = 0, channels = 0;
  std::vector<float> data;

  Image() = default;
  Image(int w, int h, int c, float fill = 0.f) : width(w), height(h), channels(c), data(size_t(w) * h * c, fill) {}
  bool empty() const { return data.empty(); }
  float& at(int x, int y, int c = 0) { return data[(size_t(y) * width + x) * channels + c]; }
  float at(int x, int y, int c = 0) const { return data[(size_t(y) * width + x) * channels + c]; }
};

// Peak signal-to-noise ratio (dB) of two images of equal shape, both clamped to [0, 1]
// first (renders may exceed 1 before they are stored).
double psnr(const Image& a, const Image& b);
// Bilinear resize (box-filtered when shrinking by more than 2x).
Image resize_image(const Image& src, int width, int height);

}  // namespace isegman
