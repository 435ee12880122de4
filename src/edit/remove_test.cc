#include "edit/remove.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "edit/test_scenes.h"

namespace isegman::edit {
namespace {

TEST(Remove, DeletesExactlyTheSelectionKeepingOrderAndExtras) {
  GaussianScene s = testing::random_scene(12, 2, 1);
  const GaussianScene before = s;
  std::vector<bool> m(12, false);
  m[0] = m[5] = m[11] = true;
  const Delta d = plan_remove(s, Selection::from_mask(s, m));
  apply_delta(d, s, m);
  ASSERT_EQ(s.size(), 9u);
  EXPECT_EQ(m, std::vector<bool>(9, false));
  std::vector<bool> keep(12, true);
  keep[0] = keep[5] = keep[11] = false;
  EXPECT_TRUE(testing::same_scene(s, before.subset(keep)));
  revert_delta(d, s, m);
  EXPECT_TRUE(testing::same_scene(s, before));
  EXPECT_EQ(m[5], true);
}

TEST(Remove, ExtractKeepsOnlyTheSelection) {
  GaussianScene s = testing::random_scene(12, 1, 2);
  const GaussianScene before = s;
  std::vector<bool> m(12, false);
  m[3] = m[4] = true;
  apply_delta(plan_extract(s, Selection::from_mask(s, m)), s, m);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(m, (std::vector<bool>{true, true}));
  EXPECT_EQ(s.positions[0], before.positions[9]);
}

TEST(Remove, RefusesEmptyAllAndForeignSelections) {
  GaussianScene s = testing::random_scene(5, 0, 3);
  EXPECT_THROW(plan_remove(s, Selection::none_of(s)), Error);
  try {
    plan_remove(s, Selection::all_of(s));
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("empty scene"), std::string::npos);
  }
  EXPECT_THROW(plan_remove(testing::random_scene(5, 0, 4), Selection::all_of(s)), Error);
  EXPECT_THROW(plan_extract(s, Selection::none_of(s)), Error);
}

}  // namespace
}  // namespace isegman::edit
