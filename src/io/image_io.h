// PNG and JPEG images (detected by content) to and from float images in [0, 1].
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/image.h"

namespace isegman {

// Reads a PNG or JPEG. channels = 0 keeps the file's own (1 grey, 3 colour; alpha is
// dropped); 1 or 3 converts. Throws Error naming the file on any problem.
Image read_image(const std::string& path, int channels = 0);
Image decode_image(const uint8_t* data, size_t size, const std::string& source, int channels = 0);

// 8-bit PNG (1, 3 or 4 channels; values clamped to [0, 1]).
std::vector<uint8_t> encode_png(const Image& image);
// 16-bit greyscale PNG of a 1-channel image scaled so that `max_value` maps to 65535.
std::vector<uint8_t> encode_png16(const Image& image, float max_value);
std::vector<uint8_t> encode_jpeg(const Image& image, int quality = 90);
void write_png(const std::string& path, const Image& image);
void write_jpeg(const std::string& path, const Image& image, int quality = 90);

}  // namespace isegman
