#include "core/scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "core/error.h"

namespace isegman {
namespace {

GaussianScene small_scene(size_t n, int degree) {
  GaussianScene s;
  s.resize(n, degree);
  for (size_t i = 0; i < n; ++i) {
    s.positions[3 * i] = float(i);
    s.opacity[i] = float(i) * 0.1f;
    s.sh_of(i)[0] = float(i);
  }
  return s;
}

TEST(Scene, SubsetKeepsChosenGaussiansInOrder) {
  GaussianScene s = small_scene(5, 2);
  ExtraProperty e{"label", "uchar", 1, {10, 11, 12, 13, 14}};
  s.extras.push_back(e);
  GaussianScene t = s.subset({true, false, true, false, true});
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t.positions[3], 2.f);
  EXPECT_EQ(t.sh_of(2)[0], 4.f);
  EXPECT_EQ(t.extras[0].data, (std::vector<uint8_t>{10, 12, 14}));
  EXPECT_NO_THROW(t.validate("t"));
}

TEST(Scene, FingerprintSeesEveryParameter) {
  GaussianScene s = small_scene(4, 1);
  const uint64_t f = s.fingerprint();
  GaussianScene a = s;
  a.sh[7] += 1e-6f;
  GaussianScene b = s;
  b.rotations[5] = 0.5f;
  EXPECT_NE(a.fingerprint(), f);
  EXPECT_NE(b.fingerprint(), f);
  EXPECT_EQ(s.fingerprint(), f);
  // Every value of every array, in the hash's 32-byte blocks and in their tails, counts:
  // changing any one gives a fingerprint no other change gives.
  GaussianScene big = small_scene(37, 2);
  std::set<uint64_t> seen = {big.fingerprint()};
  size_t changes = 0;
  for (std::vector<float>* v : {&big.positions, &big.sh, &big.opacity, &big.scales, &big.rotations})
    for (size_t i = 0; i < v->size(); ++i) {
      const float old = (*v)[i];
      (*v)[i] = old + 0.25f;
      seen.insert(big.fingerprint());
      (*v)[i] = old;
      ++changes;
    }
  EXPECT_EQ(seen.size(), changes + 1);
  EXPECT_NE(big.fingerprint(), big.legacy_fingerprint());
}

TEST(Scene, ValidateRejectsNonFiniteAndBrokenArrays) {
  GaussianScene s = small_scene(3, 0);
  s.scales[4] = std::nanf("");
  try {
    s.validate("scene.ply");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "scene.ply: Gaussian 1 has a non-finite scale");
  }
  GaussianScene t = small_scene(3, 0);
  t.rotations.pop_back();
  EXPECT_THROW(t.validate("x"), Error);
  GaussianScene z = small_scene(2, 0);
  z.rotations[4] = 0;
  EXPECT_THROW(z.validate("x"), Error);
}

TEST(Scene, AppendFromCopiesOneGaussian) {
  GaussianScene a = small_scene(2, 3), b = small_scene(3, 3);
  a.append_from(b, 2);
  ASSERT_EQ(a.size(), 3u);
  EXPECT_EQ(a.positions[6], 2.f);
  EXPECT_EQ(a.sh_of(2)[0], 2.f);
  GaussianScene c = small_scene(1, 1);
  EXPECT_THROW(a.append_from(c, 0), Error);
}

}  // namespace
}  // namespace isegman
