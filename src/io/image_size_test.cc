#include "io/image_size.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "core/test_dirs.h"
#include "io/image_io.h"

namespace isegman {
namespace {

TEST(ImageSize, PngHasAlphaOnlyWhereItsColourTypeCarriesIt) {
  const std::filesystem::path dir = testing::fresh_temp_dir("isegman-size-", "alpha");
  write_png((dir / "rgb.png").string(), Image(5, 4, 3, 0.5f));
  write_png((dir / "rgba.png").string(), Image(5, 4, 4, 0.5f));
  write_png((dir / "grey.png").string(), Image(5, 4, 1, 0.5f));
  write_jpeg((dir / "photo.jpg").string(), Image(5, 4, 3, 0.5f));
  EXPECT_FALSE(png_has_alpha((dir / "rgb.png").string()));
  EXPECT_TRUE(png_has_alpha((dir / "rgba.png").string()));
  EXPECT_FALSE(png_has_alpha((dir / "grey.png").string()));
  EXPECT_FALSE(png_has_alpha((dir / "photo.jpg").string()));
  EXPECT_FALSE(png_has_alpha((dir / "missing.png").string()));
  int w = 0, h = 0;
  ASSERT_TRUE(read_image_size((dir / "rgba.png").string(), w, h));
  EXPECT_EQ(w, 5);
  EXPECT_EQ(h, 4);
}

}  // namespace
}  // namespace isegman
