// Image dimensions from a PNG or JPEG header without decoding the pixels (used by the
// camera loaders to fill in missing image sizes cheaply), and whether a PNG has an alpha
// channel.
#pragma once

#include <cstdint>
#include <string>

namespace isegman {

// Returns false (and leaves width/height untouched) when the file cannot be opened or
// is not a PNG/JPEG with a readable size.
bool read_image_size(const std::string& path, int& width, int& height);
// The same on bytes in memory (the file's beginning is enough).
bool parse_image_size(const uint8_t* data, size_t size, int& width, int& height);
// Whether the file is a PNG whose colour type carries alpha (grey + alpha, RGBA); a
// transparency chunk on an opaque colour type is not looked for. False for a JPEG, a file
// that cannot be read, or anything else.
bool png_has_alpha(const std::string& path);

}  // namespace isegman
