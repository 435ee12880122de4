#include "edit/transform.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "edit/test_scenes.h"

namespace isegman::edit {
namespace {

using testing::random_scene;

// Four Gaussians on exact binary values; S = {0, 1, 2}, centroid (1, 1, 1).
GaussianScene grid() {
  GaussianScene s;
  s.resize(4, 1);
  const float p[12] = {0, 0, 0, 2, 0, 2, 1, 3, 1, 9, 9, 9};
  std::copy(p, p + 12, s.positions.begin());
  for (size_t i = 0; i < 4; ++i) {
    s.scales[3 * i] = -1.f;
    s.scales[3 * i + 1] = -2.f;
    s.scales[3 * i + 2] = -3.f;
    s.sh_of(i)[3] = 0.25f;  // a band-1 coefficient
  }
  return s;
}

Selection first_three(const GaussianScene& s) { return Selection::from_mask(s, {true, true, true, false}); }

void apply(const Delta& d, GaussianScene& s) {
  std::vector<bool> m(s.size(), false);
  apply_delta(d, s, m);
}

TEST(Scale, PaperFormulaExactValues) {
  GaussianScene s = grid();
  const Delta d = plan_scale(s, first_three(s), 2.0);
  apply(d, s);
  // mu' = (mu - (1,1,1)) * 2 + (1,1,1)
  const float want[12] = {-1, -1, -1, 3, -1, 3, 1, 5, 1, 9, 9, 9};
  for (int k = 0; k < 12; ++k) EXPECT_EQ(s.positions[k], want[k]) << k;
  const float l2 = float(std::log(2.0));
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(s.scales[3 * i], -1.f + l2);
    EXPECT_EQ(s.scales[3 * i + 2], -3.f + l2);
    EXPECT_EQ(s.rotations[4 * i], 1.f);  // orientation untouched
    EXPECT_EQ(s.sh_of(i)[3], 0.25f);     // colours untouched
  }
  EXPECT_EQ(s.scales[9], -1.f);  // Gaussian 3 is not selected
  EXPECT_EQ(d.modified, (std::vector<uint32_t>{0, 1, 2}));
}

TEST(Transform, RotationTurnsPositionsOrientationsAndNormals) {
  GaussianScene s = grid();
  s.normals.assign(12, 0.f);
  s.normals[0] = 1.f;  // Gaussian 0 faces +x
  s.rotations[0] = 2.f;  // unnormalised identity
  Similarity t;
  t.rotation = Quat::from_axis_angle({0, 0, 1}, M_PI / 2);  // +90 deg about z
  t.translation = {10, 0, 0};
  t.pivot = Vec3{0, 0, 0};
  apply(plan_transform(s, first_three(s), t), s);
  // (2, 0, 2) -> (0, 2, 2) + (10, 0, 0)
  EXPECT_NEAR(s.positions[3], 10.f, 1e-6);
  EXPECT_NEAR(s.positions[4], 2.f, 1e-6);
  EXPECT_NEAR(s.positions[5], 2.f, 1e-6);
  // Normal +x -> +y.
  EXPECT_NEAR(s.normals[0], 0.f, 1e-6);
  EXPECT_NEAR(s.normals[1], 1.f, 1e-6);
  // Orientation: q' = q_R * q, norm kept (2).
  const Quat q = s.rotation(0);
  EXPECT_NEAR(q.norm(), 2.0, 1e-6);
  const Mat3 m = q.to_matrix();
  EXPECT_NEAR(m.m[1][0], 1.0, 1e-6);  // local x axis -> world +y
  // Covariance: R Sigma R^T. The x scale (e^-1) now lies along y.
  // Unselected Gaussian untouched.
  EXPECT_EQ(s.positions[9], 9.f);
}

TEST(Transform, CovarianceRotatesAsRSigmaRt) {
  GaussianScene s = random_scene(20, 0, 4);
  const Selection all = Selection::all_of(s);
  Similarity t;
  t.rotation = rotation_from_euler_deg(20, 40, -70);
  t.scale = 1.5;
  GaussianScene r = s;
  apply(plan_transform(s, all, t), r);
  const Mat3 R = t.rotation.to_matrix();
  for (size_t i = 0; i < s.size(); ++i) {
    auto cov = [](const GaussianScene& g, size_t i) {
      const Mat3 q = g.rotation(i).to_matrix();
      const Vec3 sc = g.scale(i);
      Mat3 c;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
          double v = 0;
          for (int k = 0; k < 3; ++k) v += q.m[a][k] * sc[k] * sc[k] * q.m[b][k];
          c.m[a][b] = v;
        }
      return c;
    };
    const Mat3 want = R * cov(s, i) * R.transposed();
    const Mat3 got = cov(r, i);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) EXPECT_NEAR(got.m[a][b], want.m[a][b] * 2.25, 1e-6);
  }
}

TEST(Copy, AppendsATransformedCopyAndSelectsIt) {
  GaussianScene s = grid();
  const GaussianScene original = s;
  Similarity t;
  t.translation = {0, 0, 5};
  const Delta d = plan_copy(s, first_three(s), t);
  std::vector<bool> m = {true, true, true, false};
  apply_delta(d, s, m);
  ASSERT_EQ(s.size(), 7u);
  for (size_t k = 0; k < 12; ++k) EXPECT_EQ(s.positions[k], original.positions[k]);  // originals kept
  EXPECT_EQ(s.positions[3 * 4 + 2], 5.f);  // copy of Gaussian 0 at z + 5
  EXPECT_EQ(s.positions[3 * 6 + 1], 3.f);
  EXPECT_EQ(m, (std::vector<bool>{false, false, false, false, true, true, true}));
}

TEST(Transform, RejectsBadInput) {
  GaussianScene s = grid();
  const Selection sel = first_three(s);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(plan_scale(s, sel, 0.0), Error);
  EXPECT_THROW(plan_scale(s, sel, -2.0), Error);
  EXPECT_THROW(plan_scale(s, sel, nan), Error);
  EXPECT_THROW(plan_scale(s, sel, inf), Error);
  Similarity t;
  t.translation = {nan, 0, 0};
  EXPECT_THROW(plan_copy(s, sel, t), Error);
  t = {};
  t.rotation = {0, 0, 0, 0};
  EXPECT_THROW(plan_transform(s, sel, t), Error);
  t = {};
  t.pivot = Vec3{inf, 0, 0};
  EXPECT_THROW(plan_transform(s, sel, t), Error);
  // Empty selection and a selection of another scene.
  try {
    plan_scale(s, Selection::none_of(s), 2.0);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("empty"), std::string::npos);
  }
  GaussianScene other = s;
  other.positions[0] = 0.5f;
  try {
    plan_copy(other, sel, {});
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("different scene"), std::string::npos);
  }
  // A result that overflows float is refused.
  EXPECT_THROW(plan_scale(s, sel, 1e300), Error);
}

TEST(Transform, EulerOrderIsXThenYThenZ) {
  const Mat3 r = rotation_from_euler_deg(90, 0, 90).to_matrix();
  // x-rotation sends +y to +z; the z-rotation then leaves +z alone.
  const Vec3 y = r * Vec3{0, 1, 0};
  EXPECT_NEAR(y.z, 1.0, 1e-12);
  // +x: x-rotation keeps it, z-rotation sends it to +y.
  const Vec3 x = r * Vec3{1, 0, 0};
  EXPECT_NEAR(x.y, 1.0, 1e-12);
}

}  // namespace
}  // namespace isegman::edit
