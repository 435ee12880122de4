// A binary mask at an image's size, one byte a pixel (0 or 1): a quarter of a one-channel
// float Image. SAM's candidate masks take this form; a session keeps every round's answers
// for undo, so their size is what a long session grows by with each click.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/image.h"

namespace isegman {

struct Mask {
  int width = 0, height = 0;
  std::vector<uint8_t> data;

  Mask() = default;
  Mask(int w, int h) : width(w), height(h), data(size_t(w) * h, 0) {}
  bool empty() const { return data.empty(); }
  bool at(int x, int y) const { return data[size_t(y) * width + x] != 0; }
};

// Pixels on (non-zero) in mask bytes.
inline size_t mask_area(const std::vector<uint8_t>& bytes) {
  size_t n = 0;
  for (uint8_t v : bytes) n += v != 0;
  return n;
}
inline size_t mask_area(const Mask& m) { return mask_area(m.data); }

// Bytes (non-zero: on) of a w x h mask as a one-channel image of 0 and 1, for the
// rasteriser's masked votes and PNGs.
inline Image mask_image(const std::vector<uint8_t>& bytes, int w, int h) {
  Image img(w, h, 1);
  for (size_t i = 0; i < bytes.size(); ++i) img.data[i] = bytes[i] ? 1.f : 0.f;
  return img;
}
inline Image to_image(const Mask& m) { return mask_image(m.data, m.width, m.height); }

}  // namespace isegman
