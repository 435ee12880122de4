// The differentiable rasteriser: its forward pass reproduces render(), and its gradients
// match finite differences (computed in double precision) for every parameter kind.
#include "render/rasterizer_backward.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "render/rasterizer.h"

namespace isegman {
namespace {

Camera test_camera(int w, int h, double f) {
  Camera c;  // at the origin looking along +z, slightly rotated so no axis is special
  c.width = w;
  c.height = h;
  c.fx = f;
  c.fy = f * 1.05;
  c.cx = w * 0.5 + 1.3;
  c.cy = h * 0.5 - 0.7;
  const double a = 0.07, b = -0.05;
  Mat3 rx = Mat3::from_rows({1, 0, 0}, {0, std::cos(a), -std::sin(a)}, {0, std::sin(a), std::cos(a)});
  Mat3 ry = Mat3::from_rows({std::cos(b), 0, std::sin(b)}, {0, 1, 0}, {-std::sin(b), 0, std::cos(b)});
  c.R = rx * ry;
  c.t = {0.05, -0.02, 0.1};
  return c;
}

// Overlapping Gaussians in front of the camera: anisotropic, rotated, SH of `degree`,
// depths interleaved so slotted and frozen Gaussians occlude each other. The last one
// sits outside the Jacobian clamp limit but is large enough to reach the image.
GaussianScene overlapping_scene(size_t n, int degree, unsigned seed) {
  std::mt19937 rng(seed);
  auto U = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  GaussianScene s;
  s.resize(n, degree);
  for (size_t i = 0; i < n; ++i) {
    const double z = U(2.0, 4.0);
    s.positions[3 * i] = float(U(-0.45, 0.45) * z);
    s.positions[3 * i + 1] = float(U(-0.35, 0.35) * z);
    s.positions[3 * i + 2] = float(z);
    for (int a = 0; a < 3; ++a) s.scales[3 * i + a] = float(std::log(U(0.06, 0.3)));
    for (int a = 0; a < 4; ++a) s.rotations[4 * i + a] = float(U(-1, 1));
    s.rotations[4 * i] += 1.2f;
    s.opacity[i] = float(U(-1.0, 2.5));
    float* c = s.sh_of(i);
    for (int ch = 0; ch < 3; ++ch) c[ch] = float(U(-0.8, 1.2));
    for (int k = 3; k < 3 * s.coeffs(); ++k) c[k] = float(U(-0.25, 0.25));
  }
  // Outside the clamp: x/z = 1.0 > 1.3 * tan(fov/2) for this camera, and large.
  const size_t last = n - 1;
  s.positions[3 * last] = 3.0f;
  s.positions[3 * last + 1] = 0.2f;
  s.positions[3 * last + 2] = 3.0f;
  for (int a = 0; a < 3; ++a) s.scales[3 * last + a] = float(std::log(0.9));
  s.opacity[last] = 1.0f;
  return s;
}

struct DoubleParams {
  int degree;
  std::vector<double> positions, sh, opacity, scales, rotations;
  explicit DoubleParams(const GaussianScene& s)
      : degree(s.sh_degree),
        positions(s.positions.begin(), s.positions.end()),
        sh(s.sh.begin(), s.sh.end()),
        opacity(s.opacity.begin(), s.opacity.end()),
        scales(s.scales.begin(), s.scales.end()),
        rotations(s.rotations.begin(), s.rotations.end()) {}
  GaussianParams<double> view() const {
    GaussianParams<double> p;
    p.count = opacity.size();
    p.sh_degree = degree;
    p.positions = positions.data();
    p.sh = sh.data();
    p.opacity = opacity.data();
    p.scales = scales.data();
    p.rotations = rotations.data();
    return p;
  }
};

// L = sum_p w_p . colour_p with fixed random weights.
double linear_loss(const DiffRender<double>& r, const std::vector<double>& w) {
  double L = 0;
  for (size_t i = 0; i < w.size(); ++i) L += w[i] * r.color[i];
  return L;
}

DiffRenderSettings test_settings() {
  DiffRenderSettings s;
  s.background[0] = 0.2f;
  s.background[1] = 0.7f;
  s.background[2] = 0.4f;
  s.threads = 2;
  return s;
}

struct Kind {
  const char* name;
  std::vector<double> DoubleParams::*param;
  std::vector<double> GaussianGrads<double>::*grad;
  int per_gaussian;  // values per Gaussian (SH: K * 3)
};

void check_gradients(const GaussianScene& scene, const Camera& cam, const std::vector<int32_t>& slot,
                     const DiffRenderSettings& settings, int* checked_out) {
  DoubleParams P(scene);
  size_t slots = 0;
  for (int32_t s : slot) slots += s >= 0;
  std::mt19937 rng(11);
  std::vector<double> w(size_t(cam.width) * cam.height * 3);
  for (double& v : w) v = std::uniform_real_distribution<double>(-1, 1)(rng);

  DiffRender<double> fwd;
  diff_render_forward(P.view(), cam, slot, settings, fwd);
  ASSERT_GT(fwd.diff_visible, 0u);
  GaussianGrads<double> g;
  g.resize(slots, scene.sh_degree);
  diff_render_backward(P.view(), cam, slot, settings, fwd, w.data(), g);

  const int K3 = scene.coeffs() * 3;
  const Kind kinds[] = {{"position", &DoubleParams::positions, &GaussianGrads<double>::positions, 3},
                        {"log-scale", &DoubleParams::scales, &GaussianGrads<double>::scales, 3},
                        {"rotation", &DoubleParams::rotations, &GaussianGrads<double>::rotations, 4},
                        {"opacity logit", &DoubleParams::opacity, &GaussianGrads<double>::opacity, 1},
                        {"SH", &DoubleParams::sh, &GaussianGrads<double>::sh, K3}};
  auto loss_at = [&](std::vector<double>& arr, size_t idx, double value) {
    const double keep = arr[idx];
    arr[idx] = value;
    DiffRender<double> r;
    diff_render_forward(P.view(), cam, slot, settings, r);
    arr[idx] = keep;
    return linear_loss(r, w);
  };
  int checked = 0, one_sided = 0;
  for (const Kind& kind : kinds) {
    const std::vector<double>& grad = g.*(kind.grad);
    double scale = 0;
    for (double v : grad) scale = std::max(scale, std::abs(v));
    ASSERT_GT(scale, 0) << kind.name << ": all gradients are zero";
    for (size_t i = 0; i < slot.size(); ++i) {
      if (slot[i] < 0) continue;
      for (int k = 0; k < kind.per_gaussian; ++k) {
        std::vector<double>& arr = P.*(kind.param);
        const size_t idx = i * kind.per_gaussian + k;
        const double x = arr[idx], h = 1e-7 * std::max(1.0, std::abs(x));
        const double Lp = loss_at(arr, idx, x + h), Lm = loss_at(arr, idx, x - h), L0 = loss_at(arr, idx, x);
        const double central = (Lp - Lm) / (2 * h);
        const double analytic = grad[size_t(slot[i]) * kind.per_gaussian + k];
        // Tolerance: 1e-4 relative, plus 1e-5 of the largest gradient of this kind.
        auto ok = [&](double fd) { return std::abs(fd - analytic) <= 1e-4 * std::abs(fd) + 1e-5 * scale; };
        bool pass = ok(central);
        if (!pass) {
          // A pixel whose alpha crosses 1/255 inside [x - h, x + h] makes the loss jump;
          // the jump lies on one side only, so one one-sided difference stays exact.
          pass = ok((Lp - L0) / h) || ok((L0 - Lm) / h);
          one_sided += pass;
        }
        EXPECT_TRUE(pass) << kind.name << " of Gaussian " << i << " [" << k << "]: analytic " << analytic
                          << " vs finite difference " << central << " (scale " << scale << ")";
        ++checked;
      }
    }
  }
  EXPECT_LE(one_sided, checked / 50) << "too many discontinuities: the pixel rules differ between passes?";
  if (checked_out) *checked_out = checked;
}

TEST(RasterizerBackward, ForwardMatchesRender) {
  GaussianScene scene = overlapping_scene(400, 3, 5);
  for (size_t i = 0; i < scene.size(); ++i) scene.scales[3 * i] -= 0.8f;  // thinner, more of them visible
  Camera cam = test_camera(133, 97, 110);
  RenderSettings rs;
  rs.background[0] = 0.2f;
  rs.background[1] = 0.7f;
  rs.background[2] = 0.4f;
  RenderOutput ref = render(scene, cam, rs);
  std::vector<int32_t> slot(scene.size(), -1);
  for (size_t i = 0; i < scene.size(); i += 3) slot[i] = int32_t(i / 3);
  DiffRender<float> r;
  diff_render_forward(params_of(scene), cam, slot, test_settings(), r);
  EXPECT_EQ(r.visible, ref.stats.visible);
  double max_err = 0, max_t = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      for (int c = 0; c < 3; ++c)
        max_err = std::max(max_err, double(std::abs(r.color[(size_t(y) * cam.width + x) * 3 + c] - ref.color.at(x, y, c))));
      max_t = std::max(max_t, double(std::abs((1.f - r.transmittance[size_t(y) * cam.width + x]) - ref.alpha.at(x, y))));
    }
  EXPECT_LT(max_err, 1e-5);
  EXPECT_LT(max_t, 1e-5);

  // Tiles without slotted Gaussians are skipped, the others are identical.
  DiffRenderSettings only = test_settings();
  only.only_diff_tiles = true;
  std::vector<int32_t> few(scene.size(), -1);
  few[7] = 0;
  DiffRender<float> part;
  diff_render_forward(params_of(scene), cam, few, only, part);
  size_t active = 0;
  for (int ty = 0; ty < part.grid_y; ++ty)
    for (int tx = 0; tx < part.grid_x; ++tx) {
      if (!part.tile_active[size_t(ty) * part.grid_x + tx]) continue;
      ++active;
      for (int y = ty * kTileSize; y < std::min(cam.height, (ty + 1) * kTileSize); ++y)
        for (int x = tx * kTileSize; x < std::min(cam.width, (tx + 1) * kTileSize); ++x)
          for (int c = 0; c < 3; ++c)
            ASSERT_EQ(part.color[(size_t(y) * cam.width + x) * 3 + c], r.color[(size_t(y) * cam.width + x) * 3 + c]);
    }
  EXPECT_GT(active, 0u);
  EXPECT_LT(active, size_t(part.grid_x) * part.grid_y);
}

TEST(RasterizerBackward, GradientsMatchFiniteDifferencesShDegree3WithOcclusion) {
  GaussianScene scene = overlapping_scene(24, 3, 1);
  Camera cam = test_camera(64, 48, 55);
  std::vector<int32_t> slot(scene.size(), -1);
  int next = 0;
  for (size_t i = 0; i < scene.size(); ++i)
    if (i % 2 == 1 || i == scene.size() - 1) slot[i] = next++;
  // The slotted Gaussians must be partly hidden by frozen ones: count pixels where a
  // frozen Gaussian in front covers a slotted one.
  int checked = 0;
  check_gradients(scene, cam, slot, test_settings(), &checked);
  EXPECT_EQ(checked, 12 * 59);
}

TEST(RasterizerBackward, GradientsMatchFiniteDifferencesLowDegreesAndAlphaClamp) {
  for (int degree : {0, 1, 2}) {
    GaussianScene scene = overlapping_scene(16, degree, 20 + degree);
    // Very opaque Gaussians so alpha hits alpha_max at their centres.
    for (size_t i = 0; i < scene.size(); i += 4) scene.opacity[i] = 8.f;
    Camera cam = test_camera(48, 40, 45);
    std::vector<int32_t> slot(scene.size(), -1);
    for (size_t i = 0; i < scene.size(); ++i) slot[i] = int32_t(i);  // all slotted
    SCOPED_TRACE("SH degree " + std::to_string(degree));
    check_gradients(scene, cam, slot, test_settings(), nullptr);
  }
}

TEST(RasterizerBackward, OcclusionByFrozenGaussiansIsRespected) {
  // A slotted Gaussian completely behind an opaque frozen one gets no gradient where it is
  // hidden: with a large opaque front disc, its gradient is (near) zero.
  GaussianScene s;
  s.resize(2, 0);
  s.positions = {0.f, 0.f, 2.f, 0.f, 0.f, 4.f};
  s.scales = {std::log(1.5f), std::log(1.5f), std::log(0.05f), std::log(0.1f), std::log(0.1f), std::log(0.1f)};
  s.opacity = {12.f, 1.f};
  s.sh = {1.f, 1.f, 1.f, -1.f, 0.f, 0.f};
  Camera cam = test_camera(32, 32, 30);
  cam.R = Mat3::identity();
  cam.t = {0, 0, 0};
  std::vector<int32_t> slot = {-1, 0};
  DiffRenderSettings set = test_settings();
  DiffRender<float> r;
  diff_render_forward(params_of(s), cam, slot, set, r);
  std::vector<float> ones(r.color.size(), 1.f);
  GaussianGrads<float> g;
  g.resize(1, 0);
  diff_render_backward(params_of(s), cam, slot, set, r, ones.data(), g);
  // Behind alpha 0.99 the Gaussian still shows through T = 0.01 of its pixels.
  const float dsh = g.sh[0];
  // Now remove the front disc: the same Gaussian gets ~100x the gradient.
  GaussianScene back = s.subset({false, true});
  std::vector<int32_t> slot2 = {0};
  DiffRender<float> r2;
  diff_render_forward(params_of(back), cam, slot2, set, r2);
  GaussianGrads<float> g2;
  g2.resize(1, 0);
  diff_render_backward(params_of(back), cam, slot2, set, r2, ones.data(), g2);
  EXPECT_GT(std::abs(g2.sh[0]), 50 * std::abs(dsh));
  EXPECT_GT(std::abs(dsh), 0.f);
}

TEST(RasterizerBackward, FloatGradientsAgreeWithDoubleAndAreThreadIndependent) {
  GaussianScene scene = overlapping_scene(200, 3, 9);
  Camera cam = test_camera(120, 90, 100);
  std::vector<int32_t> slot(scene.size(), -1);
  int next = 0;
  for (size_t i = 0; i < scene.size(); i += 4) slot[i] = next++;
  std::mt19937 rng(3);
  std::vector<float> wf(size_t(cam.width) * cam.height * 3);
  for (float& v : wf) v = std::uniform_real_distribution<float>(-1, 1)(rng);
  std::vector<double> wd(wf.begin(), wf.end());

  auto float_grads = [&](int threads, bool only) {
    DiffRenderSettings s = test_settings();
    s.threads = threads;
    s.only_diff_tiles = only;
    DiffRender<float> r;
    diff_render_forward(params_of(scene), cam, slot, s, r);
    GaussianGrads<float> g;
    g.resize(size_t(next), scene.sh_degree);
    diff_render_backward(params_of(scene), cam, slot, s, r, wf.data(), g);
    return g;
  };
  GaussianGrads<float> g1 = float_grads(1, false), g2 = float_grads(2, false), g3 = float_grads(2, true);
  EXPECT_EQ(g1.positions, g2.positions);
  EXPECT_EQ(g1.sh, g2.sh);
  EXPECT_EQ(g1.opacity, g2.opacity);
  EXPECT_EQ(g1.scales, g2.scales);
  EXPECT_EQ(g1.rotations, g2.rotations);
  EXPECT_EQ(g1.positions, g3.positions);  // skipping untouched tiles changes nothing
  EXPECT_EQ(g1.sh, g3.sh);

  DoubleParams P(scene);
  DiffRender<double> rd;
  DiffRenderSettings s = test_settings();
  diff_render_forward(P.view(), cam, slot, s, rd);
  GaussianGrads<double> gd;
  gd.resize(size_t(next), scene.sh_degree);
  diff_render_backward(P.view(), cam, slot, s, rd, wd.data(), gd);
  auto compare = [](const std::vector<float>& f, const std::vector<double>& d, const char* name) {
    double scale = 0, err = 0;
    for (size_t i = 0; i < d.size(); ++i) {
      scale = std::max(scale, std::abs(d[i]));
      err = std::max(err, std::abs(double(f[i]) - d[i]));
    }
    EXPECT_LE(err, 2e-3 * scale) << name;
  };
  compare(g1.positions, gd.positions, "positions");
  compare(g1.sh, gd.sh, "sh");
  compare(g1.opacity, gd.opacity, "opacity");
  compare(g1.scales, gd.scales, "scales");
  compare(g1.rotations, gd.rotations, "rotations");
}

}  // namespace
}  // namespace isegman
