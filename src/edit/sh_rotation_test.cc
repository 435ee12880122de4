#include "edit/sh_rotation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/camera.h"
#include "core/image.h"
#include "core/sh.h"
#include "edit/test_scenes.h"
#include "edit/transform.h"
#include "render/rasterizer.h"

namespace isegman::edit {
namespace {

Vec3 random_unit(testing::TestRng& rng) {
  Vec3 v;
  do v = {rng.range(-1, 1), rng.range(-1, 1), rng.range(-1, 1)};
  while (norm(v) < 0.1 || norm(v) > 1);
  return normalized(v);
}

Mat3 random_rotation(testing::TestRng& rng) {
  return Quat::from_axis_angle(random_unit(rng), rng.range(-M_PI, M_PI)).to_matrix();
}

TEST(ShRotation, FloatAndDoubleBasisAgree) {
  testing::TestRng rng(1);
  for (int t = 0; t < 50; ++t) {
    Vec3 d = random_unit(rng);
    float bf[16];
    double bd[16];
    sh_basis(3, float(d.x), float(d.y), float(d.z), bf);
    sh_basis(3, d.x, d.y, d.z, bd);
    for (int k = 0; k < 16; ++k) EXPECT_NEAR(bd[k], bf[k], 2e-6) << k;
  }
}

// The defining property: the rotated coefficients evaluated at d give the original
// colour at R^T d, for every band, evaluated with the renderer's own (float) basis.
TEST(ShRotation, RotatedCoefficientsReproduceTheColourFunction) {
  testing::TestRng rng(2);
  for (int t = 0; t < 20; ++t) {
    const Mat3 R = random_rotation(rng);
    const ShRotation shr(R);
    float c[48], r[48];
    for (float& v : c) v = float(rng.range(-1, 1));
    std::copy(c, c + 48, r);
    shr.apply(3, r);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(r[k], c[k]);  // DC untouched
    for (int s = 0; s < 20; ++s) {
      const Vec3 d = random_unit(rng);
      const Vec3 src = R.transposed() * d;
      float b1[16], b2[16];
      sh_basis(3, float(d.x), float(d.y), float(d.z), b1);
      sh_basis(3, float(src.x), float(src.y), float(src.z), b2);
      for (int ch = 0; ch < 3; ++ch) {
        double rotated = 0, original = 0;
        for (int k = 0; k < 16; ++k) {
          rotated += double(b1[k]) * r[3 * k + ch];
          original += double(b2[k]) * c[3 * k + ch];
        }
        EXPECT_NEAR(rotated, original, 2e-5);
      }
    }
  }
}

TEST(ShRotation, BandMatricesAreOrthogonalAndComposable) {
  testing::TestRng rng(3);
  const Mat3 A = random_rotation(rng), B = random_rotation(rng);
  const ShRotation ra(A), rb(B), rab(A * B), id(Mat3::identity());
  for (int l = 1; l <= 3; ++l) {
    const int n = 2 * l + 1;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        double mtm = 0, prod = 0;
        for (int k = 0; k < n; ++k) {
          mtm += ra.band(l, k, i) * ra.band(l, k, j);
          // b(B^T A^T d) = M_B b(A^T d) = M_B M_A b(d): M_{AB} = M_B M_A
          prod += rb.band(l, i, k) * ra.band(l, k, j);
        }
        // Orthogonal up to the float rounding of the basis constants in core/sh.h.
        EXPECT_NEAR(mtm, i == j ? 1.0 : 0.0, 1e-7);
        EXPECT_NEAR(rab.band(l, i, j), prod, 1e-10);
        EXPECT_NEAR(id.band(l, i, j), i == j ? 1.0 : 0.0, 1e-12);
      }
  }
  // Band 1 is the rotation itself in the basis order (-y, z, -x).
  const ShRotation rz(Quat::from_axis_angle({0, 0, 1}, M_PI / 2).to_matrix());
  // Rotating by +90 deg about z: a function peaked at +x moves to +y. Coefficient of
  // b3 = -C1 x set to -1 (peak at +x) becomes coefficient of b1 = -C1 y = -1.
  float c[12] = {0};
  c[3 * 3] = -1.f;
  rz.apply(1, c);
  EXPECT_NEAR(c[3 * 1], -1.f, 1e-6);
  EXPECT_NEAR(c[3 * 3], 0.f, 1e-6);
}

// A blob of anisotropic Gaussians with strong view-dependent colour.
GaussianScene blob() {
  GaussianScene s = testing::random_scene(400, 3, 11, false, false, 0.6);
  for (size_t i = 0; i < s.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      s.positions[3 * i + a] *= 0.5f;
      s.scales[3 * i + a] += 0.8f;
    }
    s.opacity[i] = 1.5f;
  }
  return s;
}

// Renders the object and its rotated copy from cameras related by the same motion.
double copy_psnr(bool rotate_sh) {
  const GaussianScene obj = blob();
  Similarity t;
  t.rotation = rotation_from_euler_deg(35, -60, 110);
  t.translation = {4, -2, 1};
  GaussianScene copy = obj;
  const Vec3 pivot{0.1, 0.2, -0.1};
  transform_records(copy, t, pivot, "test");
  if (!rotate_sh)  // control: orientation and position moved, colours not rotated
    for (size_t i = 0; i < copy.size(); ++i)
      for (int k = 3; k < 48; ++k) copy.sh_of(i)[k] = obj.sh_of(i)[k];
  const Camera cam = Camera::look_at({0.5, -3.2, 1.4}, {0, 0, 0}, {0, 0, 1}, 160, 120, 50);
  Camera moved = cam;
  const Mat3 R = t.rotation.to_matrix();
  moved.R = cam.R * R.transposed();
  moved.t = cam.t - moved.R * (pivot + t.translation) + cam.R * pivot;
  RenderSettings rs;
  rs.threads = 1;
  const Image a = render(obj, cam, rs).color;
  const Image b = render(copy, moved, rs).color;
  return psnr(a, b);
}

TEST(ShRotation, RotatedCopySeenFromRotatedCameraMatchesTheOriginal) {
  const double with = copy_psnr(true), without = copy_psnr(false);
  std::printf("[ sh-rotation ] rotated copy vs original: %.2f dB (without SH rotation: %.2f dB)\n", with, without);
  EXPECT_GT(with, 40.0);
  EXPECT_LT(without, 35.0);  // the control shows the SH rotation matters
}

}  // namespace
}  // namespace isegman::edit
