#include "io/image_io.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"

namespace isegman {
namespace {

Image gradient(int w, int h, int c) {
  Image img(w, h, c);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < c; ++k) img.at(x, y, k) = float((x * 7 + y * 3 + k * 50) % 256) / 255.f;
  return img;
}

TEST(ImageIo, PngRoundTripIsExactAt8Bits) {
  for (int c : {1, 3}) {
    Image img = gradient(37, 21, c);
    std::vector<uint8_t> png = encode_png(img);
    Image back = decode_image(png.data(), png.size(), "mem.png");
    ASSERT_EQ(back.channels, c);
    ASSERT_EQ(back.width, 37);
    for (size_t i = 0; i < img.data.size(); ++i) ASSERT_NEAR(back.data[i], img.data[i], 1e-6);
  }
}

TEST(ImageIo, JpegRoundTripIsClose) {
  Image img(64, 48, 3);  // smooth content: JPEG's home ground
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x)
      for (int k = 0; k < 3; ++k) img.at(x, y, k) = 0.2f + 0.6f * float(x + y * k) / 160.f;
  std::vector<uint8_t> jpg = encode_jpeg(img, 95);
  Image back = decode_image(jpg.data(), jpg.size(), "mem.jpg");
  ASSERT_EQ(back.width, 64);
  EXPECT_GT(psnr(img, back), 30.0);
}

TEST(ImageIo, ChannelConversion) {
  Image img = gradient(8, 8, 3);
  std::vector<uint8_t> png = encode_png(img);
  EXPECT_EQ(decode_image(png.data(), png.size(), "m", 1).channels, 1);
  Image grey = gradient(8, 8, 1);
  png = encode_png(grey);
  Image rgb = decode_image(png.data(), png.size(), "m", 3);
  EXPECT_EQ(rgb.channels, 3);
  EXPECT_EQ(rgb.at(3, 4, 2), rgb.at(3, 4, 0));
}

TEST(ImageIo, BadInputsGiveClearErrors) {
  const uint8_t junk[] = {1, 2, 3, 4};
  try {
    decode_image(junk, 4, "photo.png");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "photo.png: not a PNG or JPEG image");
  }
  std::vector<uint8_t> png = encode_png(gradient(16, 16, 3));
  png.resize(png.size() / 2);
  EXPECT_THROW(decode_image(png.data(), png.size(), "half.png"), Error);
  std::vector<uint8_t> jpg = encode_jpeg(gradient(16, 16, 3));
  jpg.resize(20);
  EXPECT_THROW(decode_image(jpg.data(), jpg.size(), "half.jpg"), Error);
  EXPECT_THROW(encode_png(Image()), Error);
  EXPECT_THROW(read_image("/nonexistent/x.png"), Error);
}

TEST(ImageIo, Png16KeepsDepthPrecision) {
  Image d(4, 1, 1);
  d.data = {0.f, 1.f, 2.5f, 10.f};
  std::vector<uint8_t> png = encode_png16(d, 10.f);
  EXPECT_GT(png.size(), 8u);
}

}  // namespace
}  // namespace isegman
