#include "edit/losses.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace isegman::edit {
namespace {

std::vector<float> random_image(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<float> v(size_t(w) * h * 3);
  for (float& x : v) x = std::uniform_real_distribution<float>(0.1f, 0.9f)(rng);
  return v;
}

TEST(Losses, SsimOfIdenticalImagesIsOneAndLossIsZero) {
  auto a = random_image(23, 17, 1);
  EXPECT_NEAR(ssim(a.data(), a.data(), 23, 17), 1.0, 1e-6);
  LossValue L = image_loss(a.data(), a.data(), 23, 17, {}, nullptr);
  EXPECT_NEAR(L.total, 0.0, 1e-6);
}

TEST(Losses, GradientMatchesFiniteDifferences) {
  const int w = 19, h = 14;
  auto a = random_image(w, h, 2), b = random_image(w, h, 3);
  std::vector<float> g(a.size(), 0.f);
  const LossSettings s;  // 0.8 L1 + 0.2 D-SSIM
  image_loss(a.data(), b.data(), w, h, s, g.data());
  // The loss is piecewise smooth (L1 kinks only where a == b, which random images avoid).
  int checked = 0;
  for (size_t p = 0; p < a.size(); p += 7) {
    if (std::abs(a[p] - b[p]) < 2e-3f) continue;  // L1 kink inside the difference interval
    const float keep = a[p], e = 1e-3f;
    a[p] = keep + e;
    const double lp = image_loss(a.data(), b.data(), w, h, s, nullptr).total;
    a[p] = keep - e;
    const double lm = image_loss(a.data(), b.data(), w, h, s, nullptr).total;
    a[p] = keep;
    const double fd = (lp - lm) / (2 * e);
    // Tolerance: 2 % of the value plus 2e-6 (float maps, float filtering).
    EXPECT_NEAR(g[p], fd, 0.02 * std::abs(fd) + 2e-6) << "pixel value " << p;
    ++checked;
  }
  EXPECT_GT(checked, 100);
}

TEST(Losses, RegionGradientEqualsFullGradientInsideTheRegion) {
  const int w = 64, h = 48;
  auto a = random_image(w, h, 4), b = random_image(w, h, 5);
  std::vector<float> full(a.size(), 0.f), part(a.size(), 0.f);
  image_loss(a.data(), b.data(), w, h, {}, full.data());
  const PixelRect r{16, 16, 48, 32};
  image_loss(a.data(), b.data(), w, h, {}, part.data(), r);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        const size_t p = (size_t(y) * w + x) * 3 + c;
        if (x >= r.x0 && x < r.x1 && y >= r.y0 && y < r.y1)
          ASSERT_NEAR(part[p], full[p], 1e-9 + 1e-5 * std::abs(full[p])) << x << "," << y;
        else
          ASSERT_EQ(part[p], 0.f);
      }
}

class ConstantPerceptual : public PerceptualTerm {
 public:
  std::string name() const override { return "test"; }
  double evaluate(const float*, const float*, int w, int h, float* grad) override {
    ++calls;
    for (size_t i = 0; i < size_t(w) * h * 3; ++i) grad[i] += 1.f;
    return 2.0;
  }
  int calls = 0;
};

TEST(Losses, PerceptualHookIsWeightedIn) {
  const int w = 12, h = 9;
  auto a = random_image(w, h, 6), b = random_image(w, h, 7);
  ConstantPerceptual term;
  LossSettings s;
  s.perceptual = &term;
  s.lambda_perceptual = 0.5;
  std::vector<float> g0(a.size(), 0.f), g1(a.size(), 0.f);
  const LossValue base = image_loss(a.data(), b.data(), w, h, {}, g0.data());
  const LossValue with = image_loss(a.data(), b.data(), w, h, s, g1.data());
  EXPECT_EQ(term.calls, 1);
  EXPECT_NEAR(with.total, base.total + 1.0, 1e-9);
  EXPECT_NEAR(g1[5] - g0[5], 0.5f, 1e-6);
}

}  // namespace
}  // namespace isegman::edit
