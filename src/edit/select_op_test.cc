#include "edit/select_op.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "edit/selection_tools.h"

namespace isegman::edit {
namespace {

GaussianScene line() {  // Gaussians at x = 0..9 with opacity logit x - 5
  GaussianScene s;
  s.resize(10, 0);
  for (size_t i = 0; i < 10; ++i) {
    s.positions[3 * i] = float(i);
    s.opacity[i] = float(i) - 5.f;
  }
  return s;
}

std::vector<bool> flags(std::initializer_list<int> on) {
  std::vector<bool> m(10, false);
  for (int i : on) m[size_t(i)] = true;
  return m;
}

SelectOp box(double x0, double x1, CombineMode mode) {
  SelectOp op;
  op.kind = SelectKind::kBox;
  op.lo = {x0, -1, -1};
  op.hi = {x1, 1, 1};
  op.mode = mode;
  return op;
}

TEST(SelectOp, NamesParse) {
  ShapeKind shape = ShapeKind::kRect;
  EXPECT_EQ(parse_select_kind("lasso", &shape), SelectKind::kShape);
  EXPECT_EQ(shape, ShapeKind::kLasso);
  EXPECT_EQ(parse_select_kind("shrink"), SelectKind::kShrink);
  EXPECT_FALSE(parse_select_kind("magic"));
  EXPECT_NE(select_kind_list().find("brush"), std::string::npos);
}

TEST(SelectOp, CombineModesMeetTheCurrentSelection) {
  const GaussianScene s = line();
  const Selection cur = Selection::from_mask(s, flags({2, 3, 4}));
  EXPECT_EQ(run_select(s, cur, box(3, 6, CombineMode::kReplace)).selection.mask, flags({3, 4, 5, 6}));
  EXPECT_EQ(run_select(s, cur, box(3, 6, CombineMode::kAdd)).selection.mask, flags({2, 3, 4, 5, 6}));
  EXPECT_EQ(run_select(s, cur, box(3, 6, CombineMode::kSubtract)).selection.mask, flags({2}));
  const SelectOutcome inter = run_select(s, cur, box(3, 6, CombineMode::kIntersect));
  EXPECT_EQ(inter.selection.mask, flags({3, 4}));
  EXPECT_EQ(inter.label, "box selection (intersect): 2 Gaussians");
}

TEST(SelectOp, GrowShrinkRangesAndColour) {
  const GaussianScene s = line();
  const Selection cur = Selection::from_mask(s, flags({4, 5}));
  SelectOp g;
  g.kind = SelectKind::kGrow;
  g.k = 0;
  g.distance = 1.0;
  EXPECT_EQ(run_select(s, cur, g).selection.mask, flags({3, 4, 5, 6}));
  g.kind = SelectKind::kShrink;
  EXPECT_EQ(run_select(s, run_select(s, cur, g).selection, g).selection.count(), 0u);
  SelectOp r;
  r.kind = SelectKind::kOpacity;
  r.min = 0.5;
  r.max = 1;
  r.mode = CombineMode::kIntersect;
  EXPECT_EQ(run_select(s, cur, r).selection.mask, flags({5}));
  SelectOp c;
  c.kind = SelectKind::kColor;
  c.color = Vec3{0.5, 0.5, 0.5};  // every Gaussian here has DC 0: grey
  EXPECT_EQ(run_select(s, cur, c).selection.count(), 10u);
  r.min = 2;
  EXPECT_THROW(run_select(s, cur, r), Error);
}

}  // namespace
}  // namespace isegman::edit
