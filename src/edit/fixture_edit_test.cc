// On a real trained scene: removing a box-selected region changes a render only where
// that region projected (where the removed Gaussians contributed a blending weight).
// One exact exception of the INRIA rules: a removed Gaussian that would have pushed a
// pixel's transmittance below 1e-4 ended that pixel without contributing; without it
// the pixel blends on, by at most the transmittance left then (< 1e-4 / (1 - 0.99)).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/image.h"
#include "edit/history.h"
#include "edit/remove.h"
#include "edit/selection_tools.h"
#include "edit/test_scenes.h"
#include "io/scene_loader.h"
#include "render/rasterizer.h"

namespace isegman::edit {
namespace {

double percentile(std::vector<float> v, double p) {
  const size_t k = size_t(p * double(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

TEST(FixtureEdit, RemovingABoxChangesOnlyWhereItProjected) {
  const std::string dir = std::string(ISEGMAN_FIXTURES_DIR) + "/fern/scene";
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << "fixtures not found at " << dir;
  const SceneBundle b = load_scene(dir);
  const GaussianScene& g = b.gaussians;
  // A box around the median centre, 30% of the 10-90 percentile extent per axis.
  Vec3 lo, hi;
  for (int a = 0; a < 3; ++a) {
    std::vector<float> v(g.size());
    for (size_t i = 0; i < g.size(); ++i) v[i] = g.positions[3 * i + a];
    const double med = percentile(v, 0.5), ext = percentile(v, 0.9) - percentile(v, 0.1);
    lo[a] = med - 0.15 * ext;
    hi[a] = med + 0.15 * ext;
  }
  EditSession e(g);
  e.select(select_box(g, lo, hi));
  const size_t n_sel = e.selection().count();
  ASSERT_GT(n_sel, 100u);
  ASSERT_LT(n_sel, g.size() / 2);
  const std::vector<bool> removed = e.mask();
  e.apply(plan_remove(e.scene(), e.selection()));
  ASSERT_EQ(e.scene().size(), g.size() - n_sel);

  RenderSettings rs;
  rs.threads = 2;
  size_t changed_total = 0, covered_total = 0;
  for (size_t c : {size_t(0), b.cameras.size() / 2}) {
    const Camera cam = b.cameras[c].resized(b.cameras[c].width / 2, b.cameras[c].height / 2);
    const Image before = render(g, cam, rs).color;
    const Image after = render(e.scene(), cam, rs).color;
    const Image coverage = render_selection(g, cam, removed, rs);
    size_t changed = 0, changed_outside = 0, covered = 0;
    float max_outside = 0;
    for (int y = 0; y < cam.height; ++y)
      for (int x = 0; x < cam.width; ++x) {
        bool diff = false;
        float delta = 0;
        for (int ch = 0; ch < 3; ++ch) {
          diff |= before.at(x, y, ch) != after.at(x, y, ch);
          delta = std::max(delta, std::fabs(before.at(x, y, ch) - after.at(x, y, ch)));
        }
        const bool cov = coverage.at(x, y) > 0;
        changed += diff;
        covered += cov;
        changed_outside += diff && !cov;
        if (!cov) max_outside = std::max(max_outside, delta);
      }
    std::printf("[ fixture ] fern camera %zu: removed %zu of %zu Gaussians; %zu pixels changed, %zu covered by the "
                "region, %zu changed outside it (largest change there %.2g)\n",
                c, n_sel, g.size(), changed, covered, changed_outside, double(max_outside));
    // Outside the footprint: only the early-termination pixels, few and faint.
    EXPECT_LE(changed_outside * 200, changed + 200);
    EXPECT_LT(max_outside, 0.01f);
    changed_total += changed;
    covered_total += covered;
  }
  EXPECT_GT(changed_total, 100u);
  EXPECT_GT(changed_total * 2, covered_total / 4);  // the region visibly changed where it projected

  // Undo restores the scene bit-exactly.
  e.undo();
  EXPECT_TRUE(testing::same_scene(e.scene(), g));
}

}  // namespace
}  // namespace isegman::edit
