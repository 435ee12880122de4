#include "segment/whole_band.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/click.h"
#include "core/error.h"
#include "core/random.h"

namespace isegman::segment {
namespace {

constexpr int kW = 80, kH = 60;

Mask rect_mask(int x0, int y0, int x1, int y1) {
  Mask m(kW, kH);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) m.data[size_t(y) * kW + x] = 1;
  return m;
}

// A view of a part (the mask: x 20..49, y 15..44, rendered at depth 10) inside a larger
// candidate reaching 10 px further on every side. Left of the part the band shows a
// sibling part (depth 10.5), right of it the background (depth 20).
struct PartView {
  Image mask = Image(kW, kH, 1), band = Image(kW, kH, 1), depth = Image(kW, kH, 1, 30.f), alpha = Image(kW, kH, 1, 1.f);
  PartView() {
    for (int y = 5; y < 55; ++y)
      for (int x = 10; x < 60; ++x) {
        const size_t i = size_t(y) * kW + x;
        const bool in_part = x >= 20 && x < 50 && y >= 15 && y < 45;
        (in_part ? mask : band).data[i] = 1.f;
        depth.data[i] = in_part ? 10.f : x < 35 ? 10.5f : 20.f;
      }
  }
  // Gaps of the part that show the background: every third column of its middle ten rows
  // (90 of its 676 inner pixels).
  void open_gaps() {
    for (int y = 25; y < 35; ++y)
      for (int x = 22; x < 48; x += 3) depth.data[size_t(y) * kW + x] = 20.f;
  }
  int band_pixels(int x0, int x1) const {
    int n = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = x0; x < x1; ++x) n += band.data[size_t(y) * kW + x] > 0.5f;
    return n;
  }
};

TEST(WholeBand, IsWhatALargerCandidateHoldingThePartAddsLessTheCut) {
  models::SegmentResult r;
  r.candidates = {rect_mask(20, 15, 50, 45), rect_mask(10, 5, 60, 55), rect_mask(0, 0, 30, 60), rect_mask(0, 0, 80, 60)};
  r.candidate_scores = {0.9f, 0.9f, 0.9f, 0.9f};
  // The second holds the part and is 2.8x its area; the third holds a third of it; the
  // fourth is 5.3x, above a growth of 4.
  const Mask cut = rect_mask(55, 0, 80, 60);
  const Image band = whole_band(r, 0, &cut, 4.0, 0.5);
  ASSERT_FALSE(band.empty());
  int n = 0;
  for (float v : band.data) n += v > 0.5f;
  EXPECT_EQ(n, 45 * 50 - 30 * 30);  // x 10..54 (the cut takes 55..59), y 5..54, less the part
  EXPECT_GT(band.at(10, 5), 0.5f);
  EXPECT_EQ(band.at(56, 30), 0.f);
  EXPECT_EQ(band.at(30, 30), 0.f);
  r.candidate_scores[1] = 0.3f;  // too unsure of itself to be a whole
  EXPECT_TRUE(whole_band(r, 0, nullptr, 4.0, 0.5).empty());
}

TEST(WholeBand, WhatLiesBeyondAPartThatShowsItThroughItsGapsIsNoLongerOpen) {
  PartView v;
  v.open_gaps();
  const int sibling = v.band_pixels(0, 35), background = v.band_pixels(35, kW);
  const size_t cleared = clear_band_beyond_part(v.band, v.mask, v.depth, v.alpha, BeyondPart{});
  std::printf("band: sibling %d -> %d px, background %d -> %d px\n", sibling, v.band_pixels(0, 35), background,
              v.band_pixels(35, kW));
  EXPECT_EQ(int(cleared), background);
  EXPECT_EQ(v.band_pixels(35, kW), 0);
  EXPECT_EQ(v.band_pixels(0, 35), sibling);  // a part beside it stays open
}

TEST(WholeBand, APartWithoutGapsLeavesItsBandOpenWhateverItsOutlineBlends) {
  // No gaps, but the part's outline (1 px) blends the background behind it (rendered depth 20):
  // that is no sight through the part, so the band stays as it is (a lamp's base lies
  // deeper than its shade for a camera looking down).
  PartView v;
  for (int y = 15; y < 45; ++y)
    for (int x = 20; x < 50; ++x)
      if (x < 21 || x >= 49 || y < 16 || y >= 44) v.depth.data[size_t(y) * kW + x] = 20.f;
  const Image before = v.band;
  EXPECT_EQ(clear_band_beyond_part(v.band, v.mask, v.depth, v.alpha, BeyondPart{}), 0u);
  EXPECT_EQ(v.band.data, before.data);
}

TEST(WholeBand, ASurfaceBesideTheObjectThatThePartTakesInIsNoGap) {
  // The part's right six columns are the wall beside the object (a post's part that takes in
  // the wall by it): 15 % of its inner pixels lie beyond its far side, but with nearer pixels
  // of the part on one side only. Not gaps: the band stays open.
  PartView v;
  for (int y = 15; y < 45; ++y)
    for (int x = 44; x < 50; ++x) v.depth.data[size_t(y) * kW + x] = 20.f;
  EXPECT_TRUE(std::isinf(seen_through_depth(v.mask, v.depth, v.alpha, BeyondPart{})));
  const Image before = v.band;
  EXPECT_EQ(clear_band_beyond_part(v.band, v.mask, v.depth, v.alpha, BeyondPart{}), 0u);
  EXPECT_EQ(v.band.data, before.data);
  // The same pixels as gaps (a column of the part's own nearer pixels right of them) are.
  for (int y = 15; y < 45; ++y) v.depth.data[size_t(y) * kW + 46] = 10.f;
  BeyondPart wide;
  wide.max_gap = 0.05;  // 4 px here
  EXPECT_EQ(seen_through_depth(v.mask, v.depth, v.alpha, wide), 20.f);
}

TEST(WholeBand, UnrenderedBandPixelsAndFewGapsChangeNothing) {
  PartView v;
  v.open_gaps();
  for (int y = 5; y < 55; ++y)
    for (int x = 50; x < 60; ++x) v.alpha.data[size_t(y) * kW + x] = 0.2f;  // nothing rendered there
  clear_band_beyond_part(v.band, v.mask, v.depth, v.alpha, BeyondPart{});
  EXPECT_EQ(v.band_pixels(50, 60), 50 * 10);
  EXPECT_EQ(v.band_pixels(35, 50), 0);

  PartView few;
  few.open_gaps();
  BeyondPart strict;
  strict.min_share = 0.5;  // the gaps are 13 % of the part's inner pixels
  const Image before = few.band;
  EXPECT_EQ(clear_band_beyond_part(few.band, few.mask, few.depth, few.alpha, strict), 0u);
  EXPECT_EQ(few.band.data, before.data);
}

TEST(WholeBand, TheBackgroundBeginsAboveThePartsOwnDeeperPieces) {
  // The gaps show 20 px of the plant's own deeper leaves (depth 13) and 70 px of the wall
  // (depth 20): the background begins at the wall, so a leaf as deep beside the part stays.
  PartView v;
  int n = 0;
  for (int y = 25; y < 35; ++y)
    for (int x = 22; x < 48; x += 3) v.depth.data[size_t(y) * kW + x] = n++ < 20 ? 13.f : 20.f;
  EXPECT_EQ(seen_through_depth(v.mask, v.depth, v.alpha, BeyondPart{}), 20.f);
  for (int y = 5; y < 15; ++y)
    for (int x = 10; x < 20; ++x) v.depth.data[size_t(y) * kW + x] = 13.f;  // a deeper leaf beside the part
  clear_band_beyond_part(v.band, v.mask, v.depth, v.alpha, BeyondPart{});
  EXPECT_EQ(v.band_pixels(10, 20), 10 * 50);
  EXPECT_EQ(v.band_pixels(35, kW), 0);
  BeyondPart nearest;
  nearest.background_quantile = 0;
  EXPECT_EQ(seen_through_depth(v.mask, v.depth, v.alpha, nearest), 13.f);
}

// SAM's choice is the larger mask (the fronds with what lies under them), its part the fronds.
struct WholeView : PartView {
  models::SegmentResult r;
  std::vector<uint8_t> mask;
  std::vector<Click> clicks{pixel_centre_click(30, 30, 1)};  // on the part
  WholeView() {
    r.candidates = {rect_mask(20, 15, 50, 45), rect_mask(10, 5, 60, 55)};
    r.candidate_scores = {0.9f, 0.95f};
    r.mask_index = 1;
    mask = r.candidates[1].data;
  }
  int mask_pixels(int x0, int x1) const {
    int n = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = x0; x < x1; ++x) n += mask[size_t(y) * kW + x] != 0;
    return n;
  }
};

TEST(WholeBand, ALargerMaskLosesTheBackgroundItsPartShowsThroughItsGaps) {
  WholeView v;
  v.open_gaps();
  const int sibling = v.mask_pixels(0, 20), part = 30 * 30;
  const size_t cleared = trim_beyond_part(v.mask, v.r, 1, v.clicks, v.depth, v.alpha, BeyondPart{});
  std::printf("mask: %d -> %d px (%zu cleared)\n", 2500, v.mask_pixels(0, kW), cleared);
  EXPECT_EQ(cleared, size_t(25 * 50 - 30 * 15));  // x 35..59 outside the part
  EXPECT_EQ(v.mask_pixels(0, 20), sibling);        // beside the part, as near: kept
  EXPECT_EQ(v.mask_pixels(0, kW), 2500 - int(cleared));
  int part_kept = 0;  // the part's own pixels stay, its gaps too
  for (int y = 15; y < 45; ++y)
    for (int x = 20; x < 50; ++x) part_kept += v.mask[size_t(y) * kW + x] != 0;
  EXPECT_EQ(part_kept, part);
}

TEST(WholeBand, ALargerMaskWithoutASeeThroughPartStaysWhole) {
  WholeView solid;  // the part has no gaps
  EXPECT_EQ(trim_beyond_part(solid.mask, solid.r, 1, solid.clicks, solid.depth, solid.alpha, BeyondPart{}), 0u);
  WholeView tiny;  // the part is too small a share of the mask to be its part
  tiny.open_gaps();
  BeyondPart strict;
  strict.min_part = 0.5;  // the part is 36 % of the mask
  EXPECT_EQ(trim_beyond_part(tiny.mask, tiny.r, 1, tiny.clicks, tiny.depth, tiny.alpha, strict), 0u);
  EXPECT_EQ(tiny.mask_pixels(0, kW), 2500);
}

TEST(WholeBand, ALargerMaskIsTrimmedOnlyByThePartTheClickIsOn) {
  // Clicked beside the part (on the sibling at the left), or not clicked (a view prompted
  // from the selection): the part is not what the click picked, its gaps say nothing.
  for (const std::vector<Click>& clicks :
       {std::vector<Click>{pixel_centre_click(12, 30, 1)}, std::vector<Click>{},
        std::vector<Click>{pixel_centre_click(30, 30, 1), pixel_centre_click(12, 30, 1)},
        std::vector<Click>{pixel_centre_click(12, 30, 0)}}) {
    WholeView v;
    v.open_gaps();
    EXPECT_EQ(trim_beyond_part(v.mask, v.r, 1, clicks, v.depth, v.alpha, BeyondPart{}), 0u);
  }
  WholeView v;  // a negative click elsewhere does not matter
  v.open_gaps();
  v.clicks.push_back(pixel_centre_click(12, 30, 0));
  EXPECT_EQ(trim_beyond_part(v.mask, v.r, 1, v.clicks, v.depth, v.alpha, BeyondPart{}), 800u);
}

// seen_through_depth's definition, pixel by pixel: windows counted, rows and columns
// searched, the quantiles read from sorted lists.
float seen_through_depth_by_definition(const Image& part, const Image& depth, const Image& alpha, const BeyondPart& o) {
  const int W = part.width, H = part.height, e = std::max(0, o.erosion);
  auto at = [&](const Image& im, int x, int y) { return im.data[size_t(y) * W + x]; };
  auto in_part = [&](int x, int y) { return at(part, x, y) > 0.5f && at(alpha, x, y) > 0.5f; };
  std::vector<uint8_t> inner(size_t(W) * H, 0);
  std::vector<float> depths;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      if (!in_part(x, y)) continue;
      bool full = true;
      for (int v = std::max(0, y - e); v <= std::min(H - 1, y + e); ++v)
        for (int u = std::max(0, x - e); u <= std::min(W - 1, x + e); ++u) full = full && at(part, u, v) > 0.5f;
      if (!full) continue;
      inner[size_t(y) * W + x] = 1;
      depths.push_back(at(depth, x, y));
    }
  if (depths.empty()) return INFINITY;
  std::sort(depths.begin(), depths.end());
  const float far = depths[size_t(std::clamp(o.quantile, 0.0, 1.0) * double(depths.size() - 1))] * float(1 + o.margin);
  const int reach = std::max(1, int(std::lround(o.max_gap * double(std::max(W, H)))));
  auto near = [&](int x, int y) { return x >= 0 && y >= 0 && x < W && y < H && in_part(x, y) && at(depth, x, y) <= far; };
  auto flanked = [&](int x, int y, int dx, int dy) {
    bool before = false, after = false;
    for (int t = 1; t <= reach; ++t) {
      before = before || near(x - t * dx, y - t * dy);
      after = after || near(x + t * dx, y + t * dy);
    }
    return before && after;
  };
  std::vector<float> seen;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      if (inner[size_t(y) * W + x] && at(depth, x, y) > far && (flanked(x, y, 1, 0) || flanked(x, y, 0, 1)))
        seen.push_back(at(depth, x, y));
  if (seen.empty() || double(seen.size()) < o.min_share * double(depths.size())) return INFINITY;
  std::sort(seen.begin(), seen.end());
  return seen[size_t(std::clamp(o.background_quantile, 0.0, 1.0) * double(seen.size() - 1))];
}

TEST(WholeBand, SeenThroughDepthFollowsItsDefinitionOnRandomParts) {
  // Parts of random rectangles with random holes and depths, some unrendered pixels, at
  // sizes from a sliver to the whole image (its edges clip the windows): the fast version
  // (bounding box, summed areas, column sweeps, selection instead of sorting) gives what
  // the definition gives, to the bit.
  SplitMix64 rng(11);
  int found = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int W = 20 + int(rng.next() % 60), H = 15 + int(rng.next() % 50);
    Image part(W, H, 1), depth(W, H, 1, 30.f), alpha(W, H, 1, 1.f);
    const int x0 = int(rng.next() % size_t(W)), y0 = int(rng.next() % size_t(H));
    const int x1 = std::min(W, x0 + 1 + int(rng.next() % size_t(W))), y1 = std::min(H, y0 + 1 + int(rng.next() % size_t(H)));
    const double holes = rng.range(0.0, 0.3), far_share = rng.range(0.0, 0.5);
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const size_t i = size_t(y) * W + x;
        part.data[i] = rng.uniform() < 0.97 ? 1.f : 0.f;
        depth.data[i] = rng.uniform() < holes ? float(rng.range(15, 25)) : float(rng.range(9.5, 10.5));
        if (rng.uniform() < far_share * 0.1) alpha.data[i] = 0.2f;
      }
    BeyondPart o;
    o.erosion = int(rng.next() % 3);
    o.max_gap = rng.range(0.02, 0.2);
    o.min_share = rng.range(0.0, 0.1);
    o.background_quantile = rng.uniform();
    const float want = seen_through_depth_by_definition(part, depth, alpha, o);
    const float got = seen_through_depth(part, depth, alpha, o);
    ASSERT_TRUE(got == want || (std::isinf(got) && std::isinf(want))) << "trial " << trial << ": " << got << " vs " << want;
    found += !std::isinf(want);
  }
  std::printf("%d of 300 random parts show something through their gaps\n", found);
  EXPECT_GT(found, 50);  // the trials exercise the gap search, not only its early exits
}

TEST(WholeBand, ImagesOfAnotherSizeAreAnError) {
  PartView v;
  const Image small(kW / 2, kH, 1);
  EXPECT_THROW(clear_band_beyond_part(v.band, small, v.depth, v.alpha, BeyondPart{}), Error);
  WholeView w;
  EXPECT_THROW(trim_beyond_part(w.mask, w.r, 1, w.clicks, w.depth, small, BeyondPart{}), Error);
  EXPECT_THROW(seen_through_depth(small, w.depth, w.alpha, BeyondPart{}), Error);
}

}  // namespace
}  // namespace isegman::segment
