#include "core/sh.h"

#include <gtest/gtest.h>

#include <cmath>

namespace isegman {
namespace {

TEST(SphericalHarmonics, BasisMatchesHandComputedValues) {
  // Direction (x, y, z) = (2, 3, 6) / 7: a unit vector with simple fractions.
  const float x = 2.f / 7, y = 3.f / 7, z = 6.f / 7;
  float b[16];
  sh_basis(3, x, y, z, b);
  EXPECT_NEAR(b[0], 0.2820947918, 1e-7);
  EXPECT_NEAR(b[1], -0.4886025119 * 3 / 7, 1e-7);
  EXPECT_NEAR(b[2], 0.4886025119 * 6 / 7, 1e-7);
  EXPECT_NEAR(b[3], -0.4886025119 * 2 / 7, 1e-7);
  EXPECT_NEAR(b[4], 1.0925484306 * 6 / 49, 1e-7);             // xy
  EXPECT_NEAR(b[5], -1.0925484306 * 18 / 49, 1e-7);           // yz
  EXPECT_NEAR(b[6], 0.3153915653 * (72 - 4 - 9) / 49.0, 1e-7);  // 2zz - xx - yy
  EXPECT_NEAR(b[7], -1.0925484306 * 12 / 49, 1e-7);           // xz
  EXPECT_NEAR(b[8], 0.5462742153 * (4 - 9) / 49.0, 1e-7);     // xx - yy
  EXPECT_NEAR(b[9], -0.5900435899 * 3 * (12 - 9) / 343.0, 1e-7);
  EXPECT_NEAR(b[10], 2.8906114426 * 36 / 343.0, 1e-7);
  EXPECT_NEAR(b[11], -0.4570457995 * 3 * (144 - 4 - 9) / 343.0, 1e-7);
  EXPECT_NEAR(b[12], 0.3731763326 * 6 * (72 - 12 - 27) / 343.0, 1e-7);
  EXPECT_NEAR(b[13], -0.4570457995 * 2 * (144 - 4 - 9) / 343.0, 1e-7);
  EXPECT_NEAR(b[14], 1.4453057213 * 6 * (4 - 9) / 343.0, 1e-7);
  EXPECT_NEAR(b[15], -0.5900435899 * 2 * (4 - 27) / 343.0, 1e-7);
}

TEST(SphericalHarmonics, DcRoundTripAndClamp) {
  for (float c : {0.f, 0.25f, 0.5f, 1.f}) EXPECT_NEAR(sh_dc_to_rgb(rgb_to_sh_dc(c)), c, 1e-6);
  float coeffs[3] = {rgb_to_sh_dc(0.2f), rgb_to_sh_dc(-0.3f), rgb_to_sh_dc(0.9f)};
  float rgb[3];
  sh_to_rgb(0, coeffs, 0, 0, 1, rgb);
  EXPECT_NEAR(rgb[0], 0.2f, 1e-6);
  EXPECT_EQ(rgb[1], 0.f);  // clamped at zero like the trainers
  EXPECT_NEAR(rgb[2], 0.9f, 1e-6);
}

TEST(SphericalHarmonics, DegreeOneIsLinearInDirection) {
  // Only coefficient 3 (the -x term) set: colour = 0.5 - C1 * x * c.
  float coeffs[12] = {};
  coeffs[3 * 3 + 0] = 1.f;
  float rgb[3];
  sh_to_rgb(1, coeffs, 0.6f, 0.f, 0.8f, rgb);
  EXPECT_NEAR(rgb[0], 0.5f - kShC1 * 0.6f, 1e-6);
  EXPECT_NEAR(rgb[1], 0.5f, 1e-7);
}

}  // namespace
}  // namespace isegman
