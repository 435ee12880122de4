#include "edit/edit_op.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "edit/remove.h"
#include "edit/selection_tools.h"
#include "edit/test_scenes.h"

namespace isegman::edit {
namespace {

Selection first_k(const GaussianScene& s, size_t k) {
  std::vector<bool> m(s.size(), false);
  for (size_t i = 0; i < k && i < m.size(); ++i) m[i] = true;
  return Selection::from_mask(s, m);
}

TEST(EditOp, OneNamePerOperationAndTheOldAlias) {
  for (EditKind k : {EditKind::kRemove, EditKind::kExtract, EditKind::kColorize, EditKind::kScale, EditKind::kCopy,
                     EditKind::kTransform, EditKind::kCombine})
    EXPECT_EQ(parse_edit_kind(edit_kind_name(k)), k);
  EXPECT_EQ(parse_edit_kind("move"), EditKind::kTransform);
  EXPECT_FALSE(parse_edit_kind("explode"));
  EXPECT_FALSE(parse_edit_kind("select"));  // a selection change, not an edit
  EXPECT_EQ(edit_kind_list(), "remove, extract, colorize, scale, copy, transform, combine");
}

TEST(EditOp, CombineModes) {
  GaussianScene s = testing::random_scene(10, 0, 3);
  const Selection a = first_k(s, 6);
  std::vector<bool> mb(10, false);
  for (size_t i = 4; i < 10; ++i) mb[i] = true;
  const Selection b = Selection::from_mask(s, mb);
  EXPECT_EQ(combine_selections(a, b, parse_combine_mode("replace")).count(), 6u);
  EXPECT_EQ(combine_selections(a, b, parse_combine_mode("add")).count(), 10u);
  EXPECT_EQ(combine_selections(a, b, parse_combine_mode("subtract")).count(), 4u);
  EXPECT_EQ(combine_selections(a, b, parse_combine_mode("intersect")).count(), 2u);
  EXPECT_THROW(parse_combine_mode("xor"), Error);
  for (CombineMode m : {CombineMode::kReplace, CombineMode::kAdd, CombineMode::kSubtract, CombineMode::kIntersect})
    EXPECT_EQ(parse_combine_mode(combine_mode_name(m)), m);
}

TEST(EditOp, PlanMatchesTheToolboxFunctions) {
  GaussianScene s = testing::random_scene(40, 2, 4);
  const Selection sel = first_k(s, 7);
  EditOp op;
  op.kind = EditKind::kRemove;
  const Delta a = plan_edit(op, s, sel), b = plan_remove(s, sel);
  GaussianScene sa = s, sb = s;
  std::vector<bool> ma = sel.mask, mb = sel.mask;
  apply_delta(a, sa, ma);
  apply_delta(b, sb, mb);
  EXPECT_TRUE(testing::same_scene(sa, sb));
  EXPECT_EQ(a.label, b.label);
}

TEST(EditOp, RefusesEmptySelectionsAndBadParameters) {
  GaussianScene s = testing::random_scene(20, 1, 5);
  EditOp op;
  op.kind = EditKind::kScale;
  op.factor = 2;
  EXPECT_THROW(plan_edit(op, s, Selection::none_of(s)), Error);
  op.factor = 0;
  EXPECT_THROW(plan_edit(op, s, first_k(s, 3)), Error);
  op.kind = EditKind::kColorize;
  op.color = {1.5, 0, 0};
  EXPECT_THROW(check_edit_op(op), Error);
  op.kind = EditKind::kCombine;
  EXPECT_THROW(check_edit_op(op), Error);  // no other scene named
}

TEST(EditOp, ApplyRecordsHistoryAndUndoRestores) {
  GaussianScene s = testing::random_scene(30, 3, 6);
  EditSession session(s);
  session.select(first_k(s, 10));
  EditOp op;
  op.kind = EditKind::kCopy;
  op.transform.translation = {1, 0, 0};
  op.transform.rotation = rotation_from_euler_deg(0, 0, 90);
  const EditOutcome r = apply_edit(session, op);
  EXPECT_EQ(r.gaussians_before, 30u);
  EXPECT_EQ(session.scene().size(), 40u);
  EXPECT_EQ(session.selection().count(), 10u);
  session.undo();
  session.undo();
  EXPECT_TRUE(testing::same_scene(session.scene(), s));
}

TEST(EditOp, CombineInBothDirections) {
  GaussianScene a = testing::random_scene(25, 1, 7), b = testing::random_scene(15, 1, 8);
  EditOp op;
  op.kind = EditKind::kCombine;
  op.other_path = "b.ply";
  // From: every Gaussian of b is inserted into a and selected.
  EditSession from(a);
  op.direction = CombineDirection::kFrom;
  apply_edit(from, op, &b);
  EXPECT_EQ(from.scene().size(), 40u);
  EXPECT_EQ(from.selection().count(), 15u);
  // Into: a's selection goes into b; the session continues on b.
  EditSession into(a);
  into.select(first_k(a, 5));
  op.direction = CombineDirection::kInto;
  const EditOutcome r = apply_edit(into, op, &b);
  EXPECT_EQ(r.gaussians_before, 15u);
  EXPECT_EQ(into.scene().size(), 20u);
  EXPECT_EQ(into.selection().count(), 5u);
  EXPECT_THROW(apply_edit(into, op, nullptr), Error);
}

}  // namespace
}  // namespace isegman::edit
