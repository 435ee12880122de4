#include "render/rasterizer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <mutex>

#include "core/sh.h"

namespace isegman {
namespace {

Camera axis_camera(int w, int h, double f, double cx, double cy) {
  Camera c;  // at the origin looking along +z (identity pose)
  c.width = w;
  c.height = h;
  c.fx = c.fy = f;
  c.cx = cx;
  c.cy = cy;
  return c;
}

// Adds an isotropic Gaussian with linear scale s, opacity o and colour rgb.
void add_gaussian(GaussianScene& g, Vec3 p, double s, double o, Vec3 rgb) {
  g.positions.insert(g.positions.end(), {float(p.x), float(p.y), float(p.z)});
  g.scales.insert(g.scales.end(), 3, float(std::log(s)));
  g.rotations.insert(g.rotations.end(), {1, 0, 0, 0});
  g.opacity.push_back(o >= 1 ? 50.f : float(std::log(o / (1 - o))));
  const int K = g.coeffs();
  for (int k = 0; k < K; ++k)
    for (int c = 0; c < 3; ++c) g.sh.push_back(k == 0 ? rgb_to_sh_dc(float(rgb[c])) : 0.f);
}

TEST(Rasterizer, SingleGaussianMatchesTheAnalyticFootprint) {
  GaussianScene g;
  g.sh_degree = 0;
  // Opacity 0.3 keeps alpha < 1/255 beyond 3 sigma, so INRIA's 3-sigma tile rectangle
  // never cuts the footprint and the analytic Gaussian is the whole answer.
  const double z = 4, s = 0.05, f = 300, o = 0.3;
  add_gaussian(g, {0.1, -0.05, z}, s, o, {1, 0.5, 0.25});
  Camera cam = axis_camera(96, 80, f, 48, 40);
  RenderSettings rs;
  rs.threads = 1;
  RenderOutput r = render(g, cam, rs);
  // At the centre line the Jacobian is f/z; off-axis it adds a small shear, so compare
  // with the exact EWA covariance computed here in double precision.
  const double X = 0.1, Y = -0.05;
  const double j00 = f / z, j02 = -f * X / (z * z), j11 = f / z, j12 = -f * Y / (z * z);
  const double v = s * s;
  double a = v * (j00 * j00 + j02 * j02) + 0.3, b = v * (j02 * j12), c = v * (j11 * j11 + j12 * j12) + 0.3;
  const double det = a * c - b * b;
  const double mx = f * X / z + 48, my = f * Y / z + 40;  // continuous coordinates
  double max_err = 0;
  int lit = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const double dx = x + 0.5 - mx, dy = y + 0.5 - my;
      const double power = -0.5 * (c * dx * dx - 2 * b * dx * dy + a * dy * dy) / det;
      double alpha = std::min(0.99, o * std::exp(power));
      if (alpha < 1.0 / 255) alpha = 0;
      lit += alpha > 0;
      max_err = std::max(max_err, std::fabs(alpha - r.alpha.at(x, y)));
      max_err = std::max(max_err, std::fabs(alpha * 0.25 - r.color.at(x, y, 2)));
    }
  EXPECT_GT(lit, 50);
  EXPECT_LT(max_err, 2e-5);
  // Expected depth of a single Gaussian is its camera-space z wherever it is visible.
  EXPECT_NEAR(r.depth.at(int(mx), int(my)), z, 1e-5);
  EXPECT_EQ(r.depth.at(0, 0), 0.f);
}

TEST(Rasterizer, CompositesFrontToBackWhateverTheStorageOrder) {
  GaussianScene g;
  g.sh_degree = 0;
  Camera cam = axis_camera(32, 32, 100, 16.5, 16.5);  // pixel (16,16) centre is on axis
  add_gaussian(g, {0, 0, 5}, 0.5, 0.6, {0, 0, 1});  // far, blue (stored first)
  add_gaussian(g, {0, 0, 3}, 0.5, 0.5, {1, 0, 0});  // near, red
  RenderSettings rs;
  rs.background[1] = 1.f;  // green background
  RenderOutput r = render(g, cam, rs);
  // Both Gaussians are centred on the pixel: alpha = opacity exactly.
  EXPECT_NEAR(r.color.at(16, 16, 0), 0.5, 1e-6);               // red: 0.5 * 1
  EXPECT_NEAR(r.color.at(16, 16, 2), 0.5 * 0.6, 1e-6);         // blue behind: T=0.5
  EXPECT_NEAR(r.color.at(16, 16, 1), 0.5 * 0.4, 1e-6);         // background: T = 0.2
  EXPECT_NEAR(r.alpha.at(16, 16), 0.8, 1e-6);
  EXPECT_NEAR(r.depth.at(16, 16), (0.5 * 3 + 0.3 * 5) / 0.8, 1e-5);
}

// Records every contribution of one pixel.
struct PixelRecorder : ContributionVisitor {
  int px, py;
  std::vector<std::pair<uint32_t, float>> seen;
  std::mutex m;
  PixelRecorder(int x, int y) : px(x), py(y) {}
  void visit(int, int x, int y, uint32_t g, float w) override {
    if (x != px || y != py) return;
    std::lock_guard<std::mutex> lock(m);
    seen.push_back({g, w});
  }
};

TEST(Rasterizer, StopsBeforeTransmittanceFallsBelowOneInTenThousand) {
  GaussianScene g;
  g.sh_degree = 0;
  Camera cam = axis_camera(32, 32, 100, 16.5, 16.5);
  // 20 layers of alpha 0.5 (logit 0), nearest stored last. T = 0.5^k is exact in float:
  // 0.5^13 >= 1e-4 but 0.5^14 < 1e-4, so the 14th layer is refused and the pixel stops.
  for (int k = 19; k >= 0; --k) add_gaussian(g, {0, 0, 2.0 + 0.1 * k}, 0.5, 0.5, {1, 1, 1});
  PixelRecorder rec(16, 16);
  RenderOutput r = render(g, cam, {}, nullptr, &rec);
  ASSERT_EQ(rec.seen.size(), 13u);
  for (size_t k = 0; k < rec.seen.size(); ++k) {
    EXPECT_EQ(rec.seen[k].first, uint32_t(19 - k));  // front to back
    EXPECT_FLOAT_EQ(rec.seen[k].second, std::ldexp(1.f, -int(k) - 1));
  }
  EXPECT_FLOAT_EQ(r.alpha.at(16, 16), 1.f - std::ldexp(1.f, -13));
}

TEST(Rasterizer, ProjectsPointsWhereTheCameraSaysTheyAre) {
  GaussianScene g;
  g.sh_degree = 0;
  Camera cam = Camera::look_at({3, -4, 2}, {0, 0, 0}, {0, 0, 1}, 200, 150, 60);
  const Vec3 p{0.3, 0.2, -0.1};
  add_gaussian(g, p, 0.004, 0.99, {1, 1, 1});
  RenderOutput r = render(g, cam);
  double u, v;
  ASSERT_TRUE(cam.project(p, u, v));
  int bx = 0, by = 0;
  float best = -1;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x)
      if (r.alpha.at(x, y) > best) { best = r.alpha.at(x, y); bx = x; by = y; }
  EXPECT_EQ(bx, int(std::floor(u)));
  EXPECT_EQ(by, int(std::floor(v)));
}

GaussianScene cloud(size_t n, int degree, unsigned seed) {
  GaussianScene g;
  g.sh_degree = degree;
  uint64_t s = seed;
  auto rnd = [&] {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return double(s >> 11) / 9007199254740992.0;
  };
  for (size_t i = 0; i < n; ++i) {
    add_gaussian(g, {rnd() * 2 - 1, rnd() * 2 - 1, rnd() * 2 - 1}, 0.01 + 0.05 * rnd(), 0.1 + 0.9 * rnd(),
                 {rnd(), rnd(), rnd()});
    const size_t q = 4 * i;
    for (int k = 0; k < 4; ++k) g.rotations[q + k] = float(rnd() * 2 - 1);
    for (int a = 0; a < 3; ++a) g.scales[3 * i + a] = float(std::log(0.005 + 0.06 * rnd()));
    for (int k = 3; k < 3 * g.coeffs(); ++k) g.sh_of(i)[k] = float(0.3 * (rnd() - 0.5));
  }
  return g;
}

TEST(Rasterizer, OutputDoesNotDependOnTheThreadCount) {
  GaussianScene g = cloud(4000, 3, 42);
  Camera cam = Camera::look_at({0.5, -3.5, 1}, {0, 0, 0}, {0, 0, 1}, 161, 117, 50);  // partial tiles
  RenderSettings one, two, four;
  one.threads = 1;
  two.threads = 2;
  four.threads = 4;
  RenderOutput a = render(g, cam, one), b = render(g, cam, two), c = render(g, cam, four);
  EXPECT_EQ(a.color.data, b.color.data);
  EXPECT_EQ(a.color.data, c.color.data);
  EXPECT_EQ(a.depth.data, c.depth.data);
  EXPECT_EQ(a.alpha.data, b.alpha.data);
  EXPECT_GT(a.stats.contributed, 10000u);
}

// Sums the visitor's weights per pixel (one worker slot each, merged afterwards).
struct WeightSums : ContributionVisitor {
  int w, h;
  std::vector<std::vector<double>> per_worker;
  WeightSums(int w_, int h_) : w(w_), h(h_) {}
  void begin(int workers) override { per_worker.assign(workers, std::vector<double>(size_t(w) * h, 0.0)); }
  void visit(int worker, int x, int y, uint32_t, float weight) override {
    per_worker[worker][size_t(y) * w + x] += weight;
  }
};

TEST(Rasterizer, VisitorWeightsAddUpToAlpha) {
  GaussianScene g = cloud(3000, 1, 7);
  Camera cam = Camera::look_at({0, -3, 0.5}, {0, 0, 0}, {0, 0, 1}, 120, 90, 55);
  WeightSums sums(cam.width, cam.height);
  RenderOutput r = render(g, cam, {}, nullptr, &sums);
  double max_err = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      double s = 0;
      for (auto& pw : sums.per_worker) s += pw[size_t(y) * cam.width + x];
      max_err = std::max(max_err, std::fabs(s - r.alpha.at(x, y)));
    }
  EXPECT_LT(max_err, 1e-4);
}

TEST(Rasterizer, SelectionCoverageRespectsOcclusion) {
  GaussianScene g;
  g.sh_degree = 0;
  Camera cam = axis_camera(32, 32, 100, 16.5, 16.5);
  add_gaussian(g, {0, 0, 5}, 0.5, 0.6, {0, 0, 1});   // selected, behind
  add_gaussian(g, {0, 0, 3}, 0.5, 0.5, {1, 0, 0});   // unselected, in front
  Image m = render_selection(g, cam, std::vector<bool>{true, false});
  EXPECT_NEAR(m.at(16, 16), 0.5 * 0.6, 1e-6);
  Image all = render_selection(g, cam, std::vector<bool>{true, true});
  RenderOutput r = render(g, cam);
  for (size_t i = 0; i < all.data.size(); ++i) ASSERT_NEAR(all.data[i], r.alpha.data[i], 1e-6);
  Image none = render_selection(g, cam, std::vector<bool>{false, false});
  for (float v : none.data) ASSERT_EQ(v, 0.f);
}

TEST(Rasterizer, CullsBehindTheCameraAndKeepsBackground) {
  GaussianScene g;
  g.sh_degree = 0;
  add_gaussian(g, {0, 0, -3}, 0.5, 0.9, {1, 0, 0});
  add_gaussian(g, {0, 0, 0.1}, 0.5, 0.9, {1, 0, 0});  // inside the near plane
  RenderSettings rs;
  rs.background[2] = 0.5f;
  RenderOutput r = render(g, axis_camera(20, 20, 50, 10, 10), rs);
  EXPECT_EQ(r.stats.visible, 0u);
  EXPECT_EQ(r.color.at(10, 10, 2), 0.5f);
  EXPECT_EQ(r.alpha.at(10, 10), 0.f);
}

}  // namespace
}  // namespace isegman

namespace isegman {
namespace {

TEST(Rasterizer, PreparedFrameReusedWithTileMaskMatchesFullRender) {
  GaussianScene g = cloud(3000, 2, 9);
  Camera cam = Camera::look_at({0, -3, 0.5}, {0, 0, 0}, {0, 0, 1}, 100, 70, 55);
  PreparedFrame frame = prepare_frame(g, cam);
  std::vector<float> values(g.size());
  for (size_t i = 0; i < values.size(); ++i) values[i] = float(i % 3) * 0.5f;
  RenderOutput full = render(g, cam, {}, &values);
  std::vector<uint8_t> tiles(size_t(frame.grid_x) * frame.grid_y, 0);
  tiles[1] = tiles[frame.grid_x + 2] = 1;
  RenderOutput part = rasterize(frame, {}, &values, nullptr, &tiles);
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const bool on = tiles[size_t(y / kTileSize) * frame.grid_x + x / kTileSize];
      ASSERT_EQ(part.value.at(x, y), on ? full.value.at(x, y) : 0.f);
      ASSERT_EQ(part.alpha.at(x, y), on ? full.alpha.at(x, y) : 0.f);
    }
  // The same frame rasterised again gives the same image.
  EXPECT_EQ(rasterize(frame).color.data, full.color.data);
}

}  // namespace
}  // namespace isegman
