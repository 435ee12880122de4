#include "edit/combine.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "edit/test_scenes.h"

namespace isegman::edit {
namespace {

TEST(Combine, InsertsTransformedSelectionAndPadsShDegree) {
  const GaussianScene a = testing::random_scene(30, 1, 1, false, false);
  GaussianScene b = testing::random_scene(20, 3, 2, true, true);
  std::vector<bool> sa(30, false);
  sa[2] = sa[7] = true;
  Similarity t;
  t.translation = {1, 2, 3};
  std::vector<bool> mb(20, false);
  mb[4] = true;
  const Delta d = plan_combine(b, mb, a, Selection::from_mask(a, sa), t);
  const GaussianScene b0 = b;
  apply_delta(d, b, mb);
  ASSERT_EQ(b.size(), 22u);
  EXPECT_EQ(b.sh_degree, 3);
  EXPECT_EQ(b.positions[3 * 20], a.positions[3 * 2] + 1.f);
  EXPECT_EQ(b.positions[3 * 21 + 2], a.positions[3 * 7 + 2] + 3.f);
  // Degree 1 coefficients copied, bands 2-3 zero.
  for (int k = 0; k < 12; ++k) EXPECT_EQ(b.sh_of(21)[k], a.sh_of(7)[k]);
  for (int k = 12; k < 48; ++k) EXPECT_EQ(b.sh_of(21)[k], 0.f);
  // Normals and extras follow the target, zero-filled.
  EXPECT_EQ(b.normals.size(), 66u);
  EXPECT_EQ(b.normals[3 * 20], 0.f);
  EXPECT_EQ(b.extras[0].data.size(), 22u);
  bool padded_note = false;
  for (const auto& n : d.notes) padded_note |= n.find("padded") != std::string::npos;
  EXPECT_TRUE(padded_note);
  // Selection: only the inserted ones.
  for (size_t i = 0; i < 22; ++i) EXPECT_EQ(mb[i], i >= 20) << i;
  revert_delta(d, b, mb);
  EXPECT_TRUE(testing::same_scene(b, b0));
}

TEST(Combine, TruncatesAHigherDegreeAndSaysSo) {
  const GaussianScene a = testing::random_scene(10, 3, 3, false, false);
  const GaussianScene b = testing::random_scene(10, 0, 4, false, false);
  const Delta d = plan_combine(b, std::vector<bool>(10, false), a, Selection::all_of(a), {});
  EXPECT_EQ(d.appended.sh_degree, 0);
  for (size_t i = 0; i < 10; ++i)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(d.appended.sh_of(i)[k], a.sh_of(i)[k]);
  ASSERT_FALSE(d.notes.empty());
  EXPECT_NE(d.notes[0].find("truncated"), std::string::npos);
}

TEST(Combine, RejectsBadInput) {
  const GaussianScene a = testing::random_scene(10, 0, 5);
  const GaussianScene b = testing::random_scene(10, 0, 6);
  EXPECT_THROW(plan_combine(b, std::vector<bool>(10), a, Selection::none_of(a), {}), Error);
  EXPECT_THROW(plan_combine(b, std::vector<bool>(10), a, Selection::all_of(b), {}), Error);
  EXPECT_THROW(plan_combine(b, std::vector<bool>(3), a, Selection::all_of(a), {}), Error);
  Similarity t;
  t.scale = -1;
  EXPECT_THROW(plan_combine(b, std::vector<bool>(10), a, Selection::all_of(a), t), Error);
}

}  // namespace
}  // namespace isegman::edit
