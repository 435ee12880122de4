#include "edit/colorize.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/sh.h"
#include "edit/test_scenes.h"

namespace isegman::edit {
namespace {

using testing::random_scene;

TEST(Colorize, ParsesColours) {
  Rgb c = parse_color("#FF8000");
  EXPECT_EQ(c.r, 1.0);
  EXPECT_EQ(c.g, 128 / 255.0);
  EXPECT_EQ(c.b, 0.0);
  c = parse_color("0a0B0c");
  EXPECT_EQ(c.r, 10 / 255.0);
  EXPECT_EQ(c.b, 12 / 255.0);
  c = parse_color("#f00");
  EXPECT_EQ(c.r, 1.0);
  c = parse_color("0.25,0.5,1");
  EXPECT_EQ(c.g, 0.5);
  for (const char* bad : {"#12345", "#GG0000", "red", "1,2,3", "0.1,0.2", "0.1,0.2,0.3,0.4", "nan,0,0", ""})
    EXPECT_THROW(parse_color(bad), Error) << bad;
  EXPECT_EQ(parse_colorize_mode("balanced"), ColorizeMode::kBalanced);
  EXPECT_THROW(parse_colorize_mode("blend"), Error);
}

TEST(Colorize, ReplaceShowsTheTargetFromEveryDirection) {
  GaussianScene s = random_scene(50, 3, 1);
  std::vector<bool> m(50, false);
  for (size_t i = 0; i < 50; i += 3) m[i] = true;
  const GaussianScene before = s;
  const Rgb target = parse_color("#3366CC");
  const Delta d = plan_colorize(s, Selection::from_mask(s, m), target, ColorizeMode::kReplace);
  apply_delta(d, s, m);
  const double t[3] = {target.r, target.g, target.b};
  for (size_t i = 0; i < 50; ++i) {
    const float* c = s.sh_of(i);
    if (!m[i]) {
      for (int k = 0; k < 48; ++k) EXPECT_EQ(c[k], before.sh_of(i)[k]);
      continue;
    }
    for (int ch = 0; ch < 3; ++ch) EXPECT_EQ(c[ch], float((t[ch] - 0.5) / double(kShC0)));
    for (int k = 3; k < 48; ++k) EXPECT_EQ(c[k], 0.f);
    for (const Vec3& dir : {Vec3{1, 0, 0}, Vec3{0, -1, 0}, normalized(Vec3{0.3, 0.4, -0.8})}) {
      float rgb[3];
      sh_to_rgb(3, c, float(dir.x), float(dir.y), float(dir.z), rgb);
      for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(rgb[ch], t[ch], 1e-6);
    }
  }
}

TEST(Colorize, BalancedShiftsTheMeanAndKeepsTexture) {
  GaussianScene s = random_scene(80, 2, 2);
  std::vector<bool> m(80, false);
  for (size_t i = 0; i < 80; i += 2) m[i] = true;
  const GaussianScene before = s;
  const Rgb mean0 = mean_base_color(s, m);
  const Rgb target{0.9, 0.1, 0.4};
  apply_delta(plan_colorize(s, Selection::from_mask(s, m), target, ColorizeMode::kBalanced), s, m);
  const Rgb mean1 = mean_base_color(s, m);
  EXPECT_NEAR(mean1.r, 0.9, 1e-6);
  EXPECT_NEAR(mean1.g, 0.1, 1e-6);
  EXPECT_NEAR(mean1.b, 0.4, 1e-6);
  // Every selected DC moved by exactly (target - mean) / C0; bands >= 1 untouched.
  const double shift[3] = {(0.9 - mean0.r) / kShC0, (0.1 - mean0.g) / kShC0, (0.4 - mean0.b) / kShC0};
  for (size_t i = 0; i < 80; ++i) {
    for (int ch = 0; ch < 3; ++ch) {
      const float want = m[i] ? before.sh_of(i)[ch] + float(shift[ch]) : before.sh_of(i)[ch];
      EXPECT_EQ(s.sh_of(i)[ch], want);
    }
    for (int k = 3; k < 27; ++k) EXPECT_EQ(s.sh_of(i)[k], before.sh_of(i)[k]);
  }
}

TEST(Colorize, RejectsBadInput) {
  GaussianScene s = random_scene(10, 0, 3);
  const Selection all = Selection::all_of(s);
  EXPECT_THROW(plan_colorize(s, Selection::none_of(s), {1, 0, 0}, ColorizeMode::kReplace), Error);
  EXPECT_THROW(plan_colorize(s, all, {std::numeric_limits<double>::quiet_NaN(), 0, 0}, ColorizeMode::kReplace), Error);
  EXPECT_THROW(plan_colorize(s, all, {1.5, 0, 0}, ColorizeMode::kBalanced), Error);
  GaussianScene other = random_scene(10, 0, 4);
  EXPECT_THROW(plan_colorize(other, all, {1, 0, 0}, ColorizeMode::kReplace), Error);
}

}  // namespace
}  // namespace isegman::edit
