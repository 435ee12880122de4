#include "segment/overlay.h"

#include <gtest/gtest.h>

namespace isegman::segment {
namespace {

bool is(const Image& img, int x, int y, float r, float g, float b) {
  return img.at(x, y, 0) == r && img.at(x, y, 1) == g && img.at(x, y, 2) == b;
}

// A w x h one-channel image holding the square [x0, x1) x [y0, y1).
Image square(int w, int h, int x0, int y0, int x1, int y1) {
  Image m(w, h, 1);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) m.at(x, y) = 1;
  return m;
}

TEST(Overlay, OutlinesTheSelectionInOrangeAndTheTruthInCyanOverIt) {
  const Image rgb(40, 30, 3);
  const ViewState state;  // no clicks: a grey border two pixels wide
  const Image selection = square(40, 30, 5, 5, 20, 20), truth = square(40, 30, 10, 10, 30, 25);
  const Image out = make_overlay(rgb, state, selection, truth);
  EXPECT_TRUE(is(out, 5, 12, 1.f, 0.55f, 0.f));    // the selection's edge, outside the truth
  EXPECT_TRUE(is(out, 10, 22, 0.f, 0.95f, 1.f));   // the truth's edge, outside the selection
  EXPECT_TRUE(is(out, 10, 12, 0.f, 0.95f, 1.f));   // the truth's edge inside the selection, over its tint
  EXPECT_TRUE(is(out, 29, 15, 0.f, 0.95f, 1.f));
  EXPECT_FALSE(is(out, 15, 15, 0.f, 0.95f, 1.f));  // inside both: tinted, no outline
  EXPECT_FALSE(is(out, 15, 15, 1.f, 0.55f, 0.f));
  EXPECT_TRUE(is(out, 1, 15, 0.5f, 0.5f, 0.5f));   // the border
  // Without a truth, only the selection's outline.
  const Image plain = make_overlay(rgb, state, selection);
  EXPECT_FALSE(is(plain, 10, 22, 0.f, 0.95f, 1.f));
  EXPECT_TRUE(is(plain, 5, 12, 1.f, 0.55f, 0.f));
}

}  // namespace
}  // namespace isegman::segment
