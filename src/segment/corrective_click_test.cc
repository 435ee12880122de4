#include "segment/corrective_click.h"

#include <gtest/gtest.h>

namespace isegman::segment {
namespace {

Image disc(int w, int h, double cx, double cy, double r) {
  Image m(w, h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if ((x + 0.5 - cx) * (x + 0.5 - cx) + (y + 0.5 - cy) * (y + 0.5 - cy) < r * r) m.at(x, y) = 1.f;
  return m;
}

TEST(CorrectiveClick, ClicksPositiveInTheMissingPart) {
  const Image truth = disc(80, 60, 40, 30, 20);
  Image sel = truth;
  for (int y = 0; y < 60; ++y)
    for (int x = 40; x < 80; ++x) sel.at(x, y) = 0.f;  // the right half is missed
  const auto c = corrective_click(truth, sel);
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->label, 1);
  EXPECT_GT(c->x, 40);  // inside the missing half, well away from its border
  EXPECT_GT(truth.at(int(c->x), int(c->y)), 0.5f);
  EXPECT_NEAR(c->y, 30, 6);  // near the axis (chamfer distances tie along it)
}

TEST(CorrectiveClick, ClicksNegativeInAWronglyTakenNeighbour) {
  const Image truth = disc(80, 60, 25, 30, 12);
  Image sel = truth;
  const Image neighbour = disc(80, 60, 58, 30, 14);
  for (size_t i = 0; i < sel.data.size(); ++i) sel.data[i] = std::max(sel.data[i], neighbour.data[i]);
  const auto c = corrective_click(truth, sel);
  ASSERT_TRUE(c.has_value());
  EXPECT_EQ(c->label, 0);
  EXPECT_NEAR(c->x, 58, 2);
  EXPECT_NEAR(c->y, 30, 2);
}

TEST(CorrectiveClick, NoClickForAThinSliverOrAPerfectSelection) {
  const Image truth = disc(80, 60, 40, 30, 20);
  EXPECT_FALSE(corrective_click(truth, truth).has_value());
  Image sel = truth;
  for (int y = 0; y < 60; ++y) sel.at(40, y) = 0.f;  // a one-pixel line missed
  EXPECT_FALSE(corrective_click(truth, sel).has_value());
  Image other(81, 60, 1);
  EXPECT_THROW(corrective_click(truth, other), std::exception);
}

}  // namespace
}  // namespace isegman::segment
