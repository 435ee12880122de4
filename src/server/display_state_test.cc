#include "server/display_state.h"

#include <gtest/gtest.h>

#include "server/app_error.h"

namespace isegman::server {
namespace {

TEST(DisplayState, HideIsolateAndShowAll) {
  DisplayState d;
  EXPECT_TRUE(d.hidden(4).empty());
  const DisplayResult h = d.apply(DisplayOp::kHide, {true, false, false, false});
  EXPECT_EQ(h.hidden, 1u);
  EXPECT_EQ(d.hidden(4), (std::vector<bool>{true, false, false, false}));
  // Isolating keeps what was hidden hidden and hides everything outside the selection.
  const DisplayResult i = d.apply(DisplayOp::kIsolate, {true, true, false, false});
  EXPECT_EQ(i.hidden, 3u);
  EXPECT_GT(i.revision, h.revision);
  EXPECT_EQ(d.hidden(4), (std::vector<bool>{true, false, true, true}));
  EXPECT_EQ(d.apply(DisplayOp::kShowAll, {false, false, false, false}).hidden, 0u);
  EXPECT_TRUE(d.hidden(4).empty());
}

TEST(DisplayState, NeedsASelectionToHide) {
  DisplayState d;
  EXPECT_THROW(d.apply(DisplayOp::kHide, {false, false}), AppError);
  EXPECT_THROW(d.apply(DisplayOp::kIsolate, {false, false}), AppError);
  EXPECT_NO_THROW(d.apply(DisplayOp::kShowAll, {false, false}));
}

TEST(DisplayState, ForgetsFlagsWhenTheGaussianCountChanges) {
  DisplayState d;
  d.apply(DisplayOp::kHide, {true, false, true});
  const uint64_t before = d.revision();
  EXPECT_TRUE(d.hidden(2).empty());  // e.g. one Gaussian was removed: indices moved
  EXPECT_GT(d.revision(), before);
  EXPECT_TRUE(d.hidden(3).empty());  // and they do not come back
}

}  // namespace
}  // namespace isegman::server
