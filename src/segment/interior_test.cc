#include "segment/interior.h"

#include <gtest/gtest.h>

#include <cmath>

namespace isegman::segment {
namespace {

// A 200 x 100 view: a wall at depth 4 with a vertical post (x in [100, 120), depth 2) in
// front of it; the mask is the post.
struct PostView {
  Image mask{200, 100, 1}, depth{200, 100, 1}, alpha{200, 100, 1};
  PostView() {
    for (int y = 0; y < 100; ++y)
      for (int x = 0; x < 200; ++x) {
        const bool post = x >= 100 && x < 120;
        mask.at(x, y) = post;
        depth.at(x, y) = post ? 2.f : 4.f;
        alpha.at(x, y) = 1.f;
      }
  }
};

// The post's middle columns are 109 and 110 (10 px from the outside on either side).
void expect_post_middle(const Click& c) {
  EXPECT_GE(c.x, 109.5);
  EXPECT_LE(c.x, 110.5);
}

TEST(ChamferDistance, CountsThreePerStepAndTheBorderAsAsked) {
  // A 5 x 5 image all inside, the border outside: 3 on the rim, 6 inside it, 9 at the centre.
  const std::vector<uint8_t> block(25, 1);
  const std::vector<int> out = chamfer_distance(block, 5, 5, true);
  EXPECT_EQ(out[0], 3);
  EXPECT_EQ(out[2], 3);
  EXPECT_EQ(out[6], 6);
  EXPECT_EQ(out[12], 9);
  // With the border inside, only the outside pixel ends the region.
  const std::vector<uint8_t> half = {0, 1, 1, 1, 1};
  const std::vector<int> in = chamfer_distance(half, 5, 1, false);
  EXPECT_EQ(in, (std::vector<int>{0, 3, 6, 9, 12}));
}

TEST(InteriorAnchor, MovesAnEdgeClickToThePostsMiddle) {
  PostView v;
  AnchorOptions o;
  o.radius = 0.06;  // 12 px
  const Click c = interior_anchor(v.mask, v.depth, v.alpha, {118.5, 50.5, 1}, o);
  // The anchor moves along the row to the nearer of the post's middle columns.
  EXPECT_DOUBLE_EQ(c.y, 50.5);
  expect_post_middle(c);
  EXPECT_EQ(c.label, 1);
}

TEST(InteriorAnchor, MovesNoFartherThanTheRadiusAsks) {
  // Radius 4 px: the nearest pixel 4 px inside the outline is margin enough (a large object's
  // click moves no deeper than that).
  PostView v;
  AnchorOptions o;
  o.radius = 0.02;
  const Click c = interior_anchor(v.mask, v.depth, v.alpha, {119.5, 50.5, 1}, o);
  EXPECT_DOUBLE_EQ(c.x, 116.5);
  EXPECT_DOUBLE_EQ(c.y, 50.5);
}

TEST(InteriorAnchor, KeepsAClickAlreadyInTheMiddleOrOffTheSurface) {
  PostView v;
  AnchorOptions o;
  const Click middle = interior_anchor(v.mask, v.depth, v.alpha, {110.5, 50.5, 1}, o);
  EXPECT_DOUBLE_EQ(middle.x, 110.5);
  // Outside the mask (the wall), and on a mask pixel without surface: unchanged.
  const Click wall = interior_anchor(v.mask, v.depth, v.alpha, {60.5, 50.5, 1}, o);
  EXPECT_DOUBLE_EQ(wall.x, 60.5);
  v.alpha.at(118, 50) = 0.1f;
  const Click bare = interior_anchor(v.mask, v.depth, v.alpha, {118.5, 50.5, 1}, o);
  EXPECT_DOUBLE_EQ(bare.x, 118.5);
}

TEST(InteriorAnchor, IgnoresWhatTheMaskShowsAtAnotherDepth) {
  // The mask also covers the wall right of the post (a gap SAM masked with the object): the
  // wall is not the clicked surface, so the anchor still moves into the post, not onto the
  // mask's middle on the wall.
  PostView v;
  for (int y = 0; y < 100; ++y)
    for (int x = 120; x < 160; ++x) v.mask.at(x, y) = 1.f;
  AnchorOptions o;
  o.radius = 0.1;  // 20 px: the wall's strip of the mask is within reach
  const Click c = interior_anchor(v.mask, v.depth, v.alpha, {118.5, 50.5, 1}, o);
  expect_post_middle(c);
}

TEST(InteriorAnchor, AnEdgePixelBlendingThePostAndTheWallStillFindsThePost) {
  // The clicked edge pixel's expected depth lies between the post's and the wall's: the
  // post is 4 % nearer than it (within the loose nearer band), so the anchor moves in.
  PostView v;
  v.depth.at(119, 50) = 2.08f;
  AnchorOptions o;
  o.radius = 0.06;
  const Click c = interior_anchor(v.mask, v.depth, v.alpha, {119.5, 50.5, 1}, o);
  expect_post_middle(c);
  // A wall 1.5 % farther than the clicked pixel is outside the tight farther band.
  PostView far;
  for (int y = 0; y < 100; ++y)
    for (int x = 120; x < 160; ++x) {
      far.mask.at(x, y) = 1.f;
      far.depth.at(x, y) = 2.03f;
    }
  const Click d = interior_anchor(far.mask, far.depth, far.alpha, {118.5, 50.5, 1}, o);
  expect_post_middle(d);
}

TEST(InteriorAnchor, AnObjectLeavingTheFrameDoesNotEndAtTheBorder) {
  // A click at the top of the post, one row below the image's border: the border is no
  // outline, so the anchor moves sideways to the middle and not down.
  PostView v;
  AnchorOptions o;
  o.radius = 0.06;
  const Click c = interior_anchor(v.mask, v.depth, v.alpha, {118.5, 0.5, 1}, o);
  EXPECT_DOUBLE_EQ(c.y, 0.5);
  expect_post_middle(c);
}

}  // namespace
}  // namespace isegman::segment
