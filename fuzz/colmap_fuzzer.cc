// libFuzzer harness: COLMAP cameras and images parsers (binary and text) and their join.
// Input layout: byte 0 selects binary (even) or text (odd); bytes 1-2 (little-endian)
// give the length of the cameras part; the images part is the rest.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "io/colmap.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 3) return 0;
  const bool text = data[0] & 1;
  size_t cam_len = std::min<size_t>(size_t(data[1]) | size_t(data[2]) << 8, size - 3);
  const uint8_t* cam = data + 3;
  const uint8_t* img = cam + cam_len;
  size_t img_len = size - 3 - cam_len;
  std::vector<isegman::ColmapCamera> cameras;
  std::vector<isegman::ColmapImage> images;
  bool have_cameras = false, have_images = false;
  try {
    cameras = text ? isegman::parse_colmap_cameras_txt(std::string(cam, cam + cam_len), "cameras.txt")
                   : isegman::parse_colmap_cameras_bin(cam, cam_len, "cameras.bin");
    have_cameras = true;
  } catch (const isegman::Error&) {
  }
  try {
    images = text ? isegman::parse_colmap_images_txt(std::string(img, img + img_len), "images.txt")
                  : isegman::parse_colmap_images_bin(img, img_len, "images.bin");
    have_images = true;
  } catch (const isegman::Error&) {
  }
  if (have_cameras && have_images) {
    try {
      std::vector<std::string> notes;
      isegman::colmap_to_cameras(cameras, images, "cameras", "images", "images", &notes);
    } catch (const isegman::Error&) {
    }
  }
  return 0;
}
