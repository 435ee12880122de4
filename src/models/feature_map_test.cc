#include "models/feature_map.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"

using namespace isegman::models;

namespace {
// A 4-channel 8x8 grid whose cell (x, y) points along a direction that depends on x and y.
std::vector<float> grid_data(int c, int g) {
  std::vector<float> d(size_t(c) * g * g);
  for (int y = 0; y < g; ++y)
    for (int x = 0; x < g; ++x)
      for (int k = 0; k < c; ++k) d[(size_t(k) * g + y) * g + x] = float((k == 0 ? 2 * x + 1 : 0) + (k == 1 ? y + 1 : 0) + (k == 2 ? 3 : 0));
  return d;
}
}  // namespace

TEST(FeatureMap, GeometryAccountsForResizeAndPadding) {
  // A 504 x 378 image in a 128-pixel frame of 8 x 8 cells of 16 pixels: resized to 128 x 96.
  FeatureMap fm(grid_data(4, 8), 4, 8, 8, 504, 378, 128, 96, 16.0);
  EXPECT_EQ(fm.valid_columns(), 8);
  EXPECT_EQ(fm.valid_rows(), 6);
  double gx, gy, px, py;
  fm.pixel_to_grid(504, 378, gx, gy);
  EXPECT_NEAR(gx, 8.0, 1e-9);
  EXPECT_NEAR(gy, 6.0, 1e-9);
  fm.pixel_to_grid(0, 0, gx, gy);
  EXPECT_EQ(gx, 0.0);
  fm.grid_to_pixel(3.25, 1.5, px, py);
  fm.pixel_to_grid(px, py, gx, gy);
  EXPECT_NEAR(gx, 3.25, 1e-9);
  EXPECT_NEAR(gy, 1.5, 1e-9);
  fm.cell_centre(0, 0, px, py);
  EXPECT_NEAR(px, 0.5 * 504 / 8, 1e-9);
  EXPECT_NEAR(py, 0.5 * 378 / 6, 1e-9);
  int cx, cy;
  fm.pixel_to_cell(503.9, 377.9, cx, cy);
  EXPECT_EQ(cx, 7);
  EXPECT_EQ(cy, 5);
  fm.pixel_to_cell(-10, 1000, cx, cy);  // clamped to valid cells, never into the padding
  EXPECT_EQ(cx, 0);
  EXPECT_EQ(cy, 5);
}

TEST(FeatureMap, PortraitPaddingIsOnTheRight) {
  FeatureMap fm(grid_data(4, 8), 4, 8, 8, 300, 400, 96, 128, 16.0);
  EXPECT_EQ(fm.valid_columns(), 6);
  EXPECT_EQ(fm.valid_rows(), 8);
  int cx, cy;
  fm.pixel_to_cell(299, 0, cx, cy);
  EXPECT_EQ(cx, 5);
}

TEST(FeatureMap, CellsAreUnitVectorsAndSamplingInterpolates) {
  FeatureMap fm(grid_data(4, 8), 4, 8, 8, 128, 128, 128, 128, 16.0);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const std::vector<float> c = fm.cell(x, y);
      double n = 0;
      for (int k = 0; k < 4; ++k) n += c[k] * c[k];
      EXPECT_NEAR(n, 1.0, 1e-5);
    }
  // At a cell centre, the sample is that cell's vector; affinity with itself is 1.
  double px, py;
  fm.cell_centre(3, 5, px, py);
  std::vector<float> s = fm.sample(px, py);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(s[k], fm.cell(3, 5)[k], 1e-6);
  EXPECT_NEAR(fm.affinity(s, 3, 5), 1.0f, 1e-5);
  EXPECT_LT(fm.affinity(s, 7, 0), 0.999f);
  // Between two centres the (re-normalised) sample lies between the two cells.
  std::vector<float> mid = fm.sample(px + 8, py);
  EXPECT_GT(fm.affinity(mid, 3, 5), fm.affinity(s, 4, 5) - 1e-6f);
  EXPECT_GT(fm.affinity(mid, 4, 5), fm.affinity(s, 4, 5) - 1e-6f);
}

TEST(FeatureMap, RejectsInconsistentData) {
  EXPECT_THROW(FeatureMap(std::vector<float>(10), 4, 8, 8, 10, 10, 10, 10, 16.0), isegman::Error);
}
