#include "io/image_io.h"

#include <jpeglib.h>
#include <png.h>

#include <algorithm>
#include <csetjmp>
#include <cstdio>
#include <cstring>

#include "core/error.h"
#include "io/atomic_file.h"

namespace isegman {
namespace {

uint8_t to_u8(float v) { return uint8_t(std::clamp(v, 0.f, 1.f) * 255.f + 0.5f); }

Image convert_channels(Image img, int channels) {
  if (channels == 0 || channels == img.channels) return img;
  Image out(img.width, img.height, channels);
  for (size_t i = 0; i < size_t(img.width) * img.height; ++i) {
    const float* s = &img.data[i * img.channels];
    float* d = &out.data[i * channels];
    if (channels == 1) d[0] = img.channels >= 3 ? 0.299f * s[0] + 0.587f * s[1] + 0.114f * s[2] : s[0];
    else for (int c = 0; c < channels; ++c) d[c] = img.channels >= 3 ? s[std::min(c, 2)] : s[0];
  }
  return out;
}

Image decode_png(const uint8_t* data, size_t size, const std::string& src) {
  png_image img;
  std::memset(&img, 0, sizeof img);
  img.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&img, data, size))
    throw Error(src, std::string("invalid PNG: ") + img.message);
  if (img.width == 0 || img.height == 0) {
    png_image_free(&img);
    throw Error(src, "image has zero size");
  }
  const bool colour = (img.format & PNG_FORMAT_FLAG_COLOR) != 0;
  img.format = colour ? PNG_FORMAT_RGB : PNG_FORMAT_GRAY;
  const int ch = colour ? 3 : 1;
  std::vector<uint8_t> buf(PNG_IMAGE_SIZE(img));
  if (!png_image_finish_read(&img, nullptr, buf.data(), 0, nullptr)) {
    std::string msg = img.message;
    png_image_free(&img);
    throw Error(src, "corrupt PNG: " + msg);
  }
  Image out(int(img.width), int(img.height), ch);
  for (size_t i = 0; i < buf.size(); ++i) out.data[i] = buf[i] / 255.f;
  return out;
}

struct JpegErr {
  jpeg_error_mgr mgr;
  jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};
void jpeg_fail(j_common_ptr cinfo) {
  auto* err = reinterpret_cast<JpegErr*>(cinfo->err);
  (*cinfo->err->format_message)(cinfo, err->message);
  longjmp(err->jump, 1);
}

Image decode_jpeg(const uint8_t* data, size_t size, const std::string& src) {
  jpeg_decompress_struct cinfo;
  JpegErr err;
  cinfo.err = jpeg_std_error(&err.mgr);
  err.mgr.error_exit = jpeg_fail;
  std::vector<uint8_t> pixels;
  int w = 0, h = 0, ch = 0;
  if (setjmp(err.jump)) {
    jpeg_destroy_decompress(&cinfo);
    throw Error(src, std::string("corrupt JPEG: ") + err.message);
  }
  jpeg_create_decompress(&cinfo);
  jpeg_mem_src(&cinfo, data, static_cast<unsigned long>(size));
  jpeg_read_header(&cinfo, TRUE);
  cinfo.out_color_space = cinfo.num_components == 1 ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_start_decompress(&cinfo);
  w = int(cinfo.output_width);
  h = int(cinfo.output_height);
  ch = int(cinfo.output_components);
  if (w == 0 || h == 0) longjmp(err.jump, 1);
  pixels.resize(size_t(w) * h * ch);
  while (cinfo.output_scanline < cinfo.output_height) {
    JSAMPROW row = pixels.data() + size_t(cinfo.output_scanline) * w * ch;
    jpeg_read_scanlines(&cinfo, &row, 1);
  }
  jpeg_finish_decompress(&cinfo);
  jpeg_destroy_decompress(&cinfo);
  Image out(w, h, ch);
  for (size_t i = 0; i < pixels.size(); ++i) out.data[i] = pixels[i] / 255.f;
  return out;
}

void check_encodable(const Image& image, const char* what) {
  if (image.width <= 0 || image.height <= 0 || image.empty()) throw Error(std::string(what) + ": image has zero size");
  if (image.channels != 1 && image.channels != 3 && image.channels != 4)
    throw Error(std::string(what) + ": unsupported channel count " + std::to_string(image.channels));
}

}  // namespace

Image decode_image(const uint8_t* data, size_t size, const std::string& src, int channels) {
  if (size == 0) throw Error(src, "empty file");
  Image img;
  if (size >= 8 && std::memcmp(data, "\x89PNG\r\n\x1a\n", 8) == 0) img = decode_png(data, size, src);
  else if (size >= 3 && data[0] == 0xFF && data[1] == 0xD8 && data[2] == 0xFF) img = decode_jpeg(data, size, src);
  else throw Error(src, "not a PNG or JPEG image");
  return convert_channels(std::move(img), channels);
}

Image read_image(const std::string& path, int channels) {
  std::vector<uint8_t> bytes = read_file_bytes(path);
  return decode_image(bytes.data(), bytes.size(), path, channels);
}

std::vector<uint8_t> encode_png(const Image& image) {
  check_encodable(image, "encode_png");
  std::vector<uint8_t> px(image.data.size());
  for (size_t i = 0; i < px.size(); ++i) px[i] = to_u8(image.data[i]);
  png_image img;
  std::memset(&img, 0, sizeof img);
  img.version = PNG_IMAGE_VERSION;
  img.width = uint32_t(image.width);
  img.height = uint32_t(image.height);
  img.format = image.channels == 1 ? PNG_FORMAT_GRAY : (image.channels == 3 ? PNG_FORMAT_RGB : PNG_FORMAT_RGBA);
  png_alloc_size_t bytes = 0;
  if (!png_image_write_to_memory(&img, nullptr, &bytes, 0, px.data(), 0, nullptr))
    throw Error(std::string("encode_png: ") + img.message);
  std::vector<uint8_t> out(bytes);
  if (!png_image_write_to_memory(&img, out.data(), &bytes, 0, px.data(), 0, nullptr))
    throw Error(std::string("encode_png: ") + img.message);
  out.resize(bytes);
  return out;
}

std::vector<uint8_t> encode_png16(const Image& image, float max_value) {
  check_encodable(image, "encode_png16");
  if (image.channels != 1) throw Error("encode_png16: needs a 1-channel image");
  std::vector<uint16_t> px(image.data.size());
  const float scale = max_value > 0 ? 65535.f / max_value : 0.f;
  for (size_t i = 0; i < px.size(); ++i) px[i] = uint16_t(std::clamp(image.data[i] * scale, 0.f, 65535.f) + 0.5f);
  png_image img;
  std::memset(&img, 0, sizeof img);
  img.version = PNG_IMAGE_VERSION;
  img.width = uint32_t(image.width);
  img.height = uint32_t(image.height);
  img.format = PNG_FORMAT_LINEAR_Y;  // 16-bit, stored without gamma conversion
  png_alloc_size_t bytes = 0;
  if (!png_image_write_to_memory(&img, nullptr, &bytes, 0, px.data(), 0, nullptr))
    throw Error(std::string("encode_png16: ") + img.message);
  std::vector<uint8_t> out(bytes);
  if (!png_image_write_to_memory(&img, out.data(), &bytes, 0, px.data(), 0, nullptr))
    throw Error(std::string("encode_png16: ") + img.message);
  out.resize(bytes);
  return out;
}

std::vector<uint8_t> encode_jpeg(const Image& image, int quality) {
  check_encodable(image, "encode_jpeg");
  Image rgb = image.channels == 4 ? convert_channels(image, 3) : image;
  jpeg_compress_struct cinfo;
  jpeg_error_mgr jerr;
  cinfo.err = jpeg_std_error(&jerr);
  jpeg_create_compress(&cinfo);
  unsigned char* mem = nullptr;
  unsigned long mem_size = 0;
  jpeg_mem_dest(&cinfo, &mem, &mem_size);
  cinfo.image_width = uint32_t(rgb.width);
  cinfo.image_height = uint32_t(rgb.height);
  cinfo.input_components = rgb.channels;
  cinfo.in_color_space = rgb.channels == 1 ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_set_defaults(&cinfo);
  jpeg_set_quality(&cinfo, std::clamp(quality, 1, 100), TRUE);
  jpeg_start_compress(&cinfo, TRUE);
  std::vector<uint8_t> row(size_t(rgb.width) * rgb.channels);
  while (cinfo.next_scanline < cinfo.image_height) {
    const float* src = &rgb.data[size_t(cinfo.next_scanline) * row.size()];
    for (size_t i = 0; i < row.size(); ++i) row[i] = to_u8(src[i]);
    JSAMPROW r = row.data();
    jpeg_write_scanlines(&cinfo, &r, 1);
  }
  jpeg_finish_compress(&cinfo);
  std::vector<uint8_t> out(mem, mem + mem_size);
  jpeg_destroy_compress(&cinfo);
  std::free(mem);
  return out;
}

void write_png(const std::string& path, const Image& image) { write_file_atomic(path, encode_png(image)); }
void write_jpeg(const std::string& path, const Image& image, int quality) {
  write_file_atomic(path, encode_jpeg(image, quality));
}

}  // namespace isegman
