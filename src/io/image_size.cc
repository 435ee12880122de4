#include "io/image_size.h"

#include <cstring>
#include <fstream>
#include <vector>

namespace isegman {

namespace {

uint32_t be32(const uint8_t* p) { return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | p[3]; }
uint16_t be16(const uint8_t* p) { return uint16_t(p[0] << 8 | p[1]); }

bool plausible(uint32_t w, uint32_t h) { return w > 0 && h > 0 && w <= (1u << 20) && h <= (1u << 20); }

// Whether the file's first 16 bytes are a PNG signature followed by its IHDR chunk (whose
// data, from byte 16 on, holds width, height, bit depth and colour type).
bool png_header(const uint8_t* b) {
  static const uint8_t kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  return std::memcmp(b, kPng, 8) == 0 && std::memcmp(b + 12, "IHDR", 4) == 0;
}

// Walks JPEG segments up to the first start-of-frame marker. `read` fills `n` bytes at
// `offset` and returns false past the end.
template <typename Read>
bool jpeg_size(Read read, int& width, int& height) {
  uint8_t b[9];
  size_t pos = 2;  // after FF D8
  for (int segments = 0; segments < 10000; ++segments) {
    if (!read(pos, b, 2)) return false;
    if (b[0] != 0xFF) return false;
    uint8_t marker = b[1];
    if (marker == 0xFF) {  // fill byte
      ++pos;
      continue;
    }
    pos += 2;
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD8)) continue;  // no length
    if (marker == 0xD9 || marker == 0xDA) return false;  // end of image / scan before a frame
    if (!read(pos, b, 2)) return false;
    uint16_t len = be16(b);
    if (len < 2) return false;
    bool sof = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (sof) {
      if (len < 7 || !read(pos, b, 7)) return false;
      uint32_t h = be16(b + 3), w = be16(b + 5);
      if (!plausible(w, h)) return false;
      width = int(w);
      height = int(h);
      return true;
    }
    pos += len;
  }
  return false;
}

template <typename Read>
bool image_size(Read read, int& width, int& height) {
  uint8_t b[24];
  if (!read(0, b, 3)) return false;
  if (b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) return jpeg_size(read, width, height);
  if (!read(0, b, 24) || !png_header(b)) return false;
  uint32_t w = be32(b + 16), h = be32(b + 20);
  if (!plausible(w, h)) return false;
  width = int(w);
  height = int(h);
  return true;
}

}  // namespace

bool parse_image_size(const uint8_t* data, size_t size, int& width, int& height) {
  auto read = [&](size_t off, uint8_t* out, size_t n) {
    if (off > size || n > size - off) return false;
    std::memcpy(out, data + off, n);
    return true;
  };
  return image_size(read, width, height);
}

bool read_image_size(const std::string& path, int& width, int& height) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return false;
  auto read = [&](size_t off, uint8_t* out, size_t n) {
    f.clear();
    f.seekg(std::streamoff(off));
    f.read(reinterpret_cast<char*>(out), std::streamsize(n));
    return bool(f) && size_t(f.gcount()) == n;
  };
  return image_size(read, width, height);
}

bool png_has_alpha(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  uint8_t b[26];
  if (!f.read(reinterpret_cast<char*>(b), sizeof b) || !png_header(b)) return false;
  const uint8_t colour_type = b[25];  // after width, height (4 bytes each) and bit depth
  return colour_type == 4 || colour_type == 6;
}

}  // namespace isegman
