#include "render/visibility.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "core/error.h"
#include "core/parallel.h"
#include "render/tile_kernel.h"

namespace isegman {
namespace {

// A dense random cloud: most pixels end (transmittance < 1e-4) long before the back of
// the cloud, so compaction has hidden entries to drop.
GaussianScene dense_cloud(size_t n, unsigned seed) {
  GaussianScene g;
  g.sh_degree = 1;
  uint64_t s = seed;
  auto rnd = [&] {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return double(s >> 11) / 9007199254740992.0;
  };
  for (size_t i = 0; i < n; ++i) {
    g.positions.insert(g.positions.end(), {float(rnd() * 2 - 1), float(rnd() * 2 - 1), float(rnd() * 2 - 1)});
    for (int a = 0; a < 3; ++a) g.scales.push_back(float(std::log(0.01 + 0.07 * rnd())));
    for (int k = 0; k < 4; ++k) g.rotations.push_back(float(rnd() * 2 - 1));
    g.opacity.push_back(float(rnd() * 8 - 3));  // logits: opacity 0.05 .. 0.99
    for (int k = 0; k < 3 * g.coeffs(); ++k) g.sh.push_back(float(k < 3 ? rnd() : 0.3 * (rnd() - 0.5)));
  }
  return g;
}

// The reference: every (pixel, Gaussian) weight from the visitor, rounded and summed.
struct Reference : ContributionVisitor {
  const Image* mask;
  std::vector<std::map<uint32_t, int64_t>> per_worker;
  explicit Reference(const Image* m) : mask(m) {}
  void begin(int workers) override { per_worker.assign(size_t(workers), {}); }
  void visit(int worker, int x, int y, uint32_t g, float w) override {
    if (mask && !(mask->at(x, y) > 0.5f)) return;
    per_worker[size_t(worker)][g] += fixed_weight(w);
  }
  GaussianWeights sums() const {
    std::map<uint32_t, int64_t> all;
    for (const auto& m : per_worker)
      for (const auto& [g, w] : m) all[g] += w;
    GaussianWeights out;
    for (const auto& [g, w] : all)
      if (w) {
        out.index.push_back(g);
        out.weight.push_back(w);
      }
    return out;
  }
};

GaussianWeights reference_sums(const GaussianScene& g, const Camera& cam, const Image* mask) {
  Reference ref(mask);
  render(g, cam, {}, nullptr, &ref);
  return ref.sums();
}

void expect_same(const GaussianWeights& a, const GaussianWeights& b) {
  ASSERT_EQ(a.index, b.index);
  ASSERT_EQ(a.weight, b.weight);
}

// A blob and a stripe: tiles fully inside, partly inside and outside.
Image irregular_mask(int w, int h) {
  Image m(w, h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double dx = x - 0.45 * w, dy = y - 0.5 * h;
      m.at(x, y) = (dx * dx + dy * dy < 0.09 * w * w || (x > 0.8 * w && y % 7 < 4)) ? 1.f : 0.f;
    }
  return m;
}

TEST(Visibility, CompactionChangesNoPixelAndDropsHiddenEntries) {
  const GaussianScene g = dense_cloud(20000, 5);
  const Camera cam = Camera::look_at({0.3, -3.2, 0.8}, {0, 0, 0}, {0, 0, 1}, 141, 103, 55);  // partial tiles
  std::vector<float> values(g.size());
  for (size_t i = 0; i < values.size(); ++i) values[i] = float(i % 4) * 0.25f;
  PreparedFrame plain = prepare_frame(g, cam), compact = prepare_frame(g, cam), colored = prepare_frame(g, cam);
  const RenderOutput full = rasterize(plain);
  const RenderOutput during = compact_frame(compact, {});
  EXPECT_EQ(during.color.data, full.color.data);
  EXPECT_EQ(during.depth.data, full.depth.data);
  EXPECT_EQ(during.alpha.data, full.alpha.data);
  compact_frame(colored, {}, true);
  EXPECT_TRUE(is_compact(compact));
  EXPECT_FALSE(is_compact(plain));
  // Hidden entries are dropped, and the frame shrinks.
  EXPECT_LT(compact.stats.tile_pairs, plain.stats.tile_pairs * 3 / 4);
  EXPECT_LT(frame_bytes(compact), frame_bytes(plain) * 3 / 4);
  // Every later pass is bit-identical: values, depth, alpha; colour when it was kept.
  const RenderOutput a = rasterize(plain, {}, &values), c = rasterize(colored, {}, &values);
  RenderSettings value_pass;
  value_pass.color = value_pass.depth = false;
  EXPECT_EQ(a.value.data, rasterize(compact, value_pass, &values).value.data);
  EXPECT_EQ(a.alpha.data, rasterize(compact, value_pass, &values).alpha.data);
  EXPECT_EQ(a.color.data, c.color.data);
  EXPECT_EQ(a.depth.data, c.depth.data);
  EXPECT_EQ(a.value.data, c.value.data);
  EXPECT_THROW(rasterize(compact), Error);  // shading dropped: colour and depth refused
  // Values that are 1 (or 0) for a whole tile's Gaussians come from the stored blends:
  // a region of the cloud selected, everything, nothing.
  RenderSettings value_only;
  value_only.color = value_only.depth = false;
  std::vector<float> left(g.size()), all_on(g.size(), 1.f), all_off(g.size(), 0.f);
  for (size_t i = 0; i < g.size(); ++i) left[i] = g.positions[3 * i] < -0.2f ? 1.f : 0.f;
  std::vector<float> all_values = values;
  for (const auto* v : {&left, &all_on, &all_off}) {
    const RenderOutput p = rasterize(plain, value_only, v), q = rasterize(compact, value_only, v);
    EXPECT_EQ(p.value.data, q.value.data);
    EXPECT_EQ(p.alpha.data, q.alpha.data);
    if (v != &left) EXPECT_EQ(q.stats.evaluated, 0u);  // nothing blended
    else EXPECT_LT(q.stats.evaluated, rasterize(compact, value_only, &all_values).stats.evaluated);
  }
  // A compaction is exact for one alpha_max only.
  RenderSettings other = value_only;
  other.alpha_max = 0.999f;
  EXPECT_THROW(rasterize(compact, other), Error);
}

TEST(Visibility, DenseSumsStayExactAcrossFramesOfDifferentSizes) {
  // Dense sums go through per-splat arrays kept zeroed between passes and grown by their
  // tail for a frame with more splats: frames of alternating sizes, on two workers (each
  // takes an array), must each give their own reference sums, nothing left from another.
  const GaussianScene g = dense_cloud(12000, 4);
  const Camera near_cam = Camera::look_at({-0.2, -1.6, 0.5}, {0, 0, 0}, {0, 0, 1}, 150, 97, 60);
  const Camera far_cam = Camera::look_at({-0.4, -3.5, 1.2}, {0, 0, 0}, {0, 0, 1}, 150, 97, 60);
  PreparedFrame near_frame = prepare_frame(g, near_cam), far_frame = prepare_frame(g, far_cam);
  compact_frame(near_frame, {});
  compact_frame(far_frame, {});
  const Image near_mask = irregular_mask(near_cam.width, near_cam.height), far_mask = irregular_mask(far_cam.width, far_cam.height);
  const GaussianWeights near_ref = reference_sums(g, near_cam, &near_mask), far_ref = reference_sums(g, far_cam, &far_mask);
  ASSERT_NE(near_frame.stats.visible, far_frame.stats.visible);
  RenderSettings two;
  two.threads = 2;
  for (int round = 0; round < 3; ++round) {
    expect_same(weight_sums(near_frame, &near_mask, two), near_ref);
    expect_same(weight_sums(far_frame, &far_mask, two), far_ref);
  }
}

TEST(Visibility, SumsMatchTheRoundedWeightsOfEveryPixel) {
  const GaussianScene g = dense_cloud(12000, 9);
  const Camera cam = Camera::look_at({-0.4, -3.0, 1.2}, {0, 0, 0}, {0, 0, 1}, 150, 97, 60);
  const Image mask = irregular_mask(cam.width, cam.height);
  PreparedFrame plain = prepare_frame(g, cam), compact = prepare_frame(g, cam);
  compact_frame(compact, {});
  const GaussianWeights all = reference_sums(g, cam, nullptr), masked = reference_sums(g, cam, &mask);
  ASSERT_GT(all.index.size(), 1000u);
  ASSERT_GT(masked.index.size(), 100u);
  ASSERT_LT(masked.index.size(), all.index.size());
  RenderSettings one, three;
  one.threads = 1;
  three.threads = 3;
  for (const RenderSettings& s : {one, three}) {
    expect_same(weight_sums(plain, nullptr, s), all);
    expect_same(weight_sums(compact, nullptr, s), all);
    expect_same(weight_sums(plain, &mask, s), masked);
    expect_same(weight_sums(compact, &mask, s), masked);
  }
  // A small mask: few (tile, Gaussian) pairs, summed by sorting them, where a large mask's
  // many pairs are summed per splat of the compacted frame (the same integers either way).
  Image spot(cam.width, cam.height, 1);
  for (int y = 36; y < 44; ++y)  // inside one tile
    for (int x = 68; x < 76; ++x) spot.at(x, y) = 1.f;
  const GaussianWeights in_spot = reference_sums(g, cam, &spot);
  ASSERT_GT(in_spot.index.size(), 10u);
  for (const RenderSettings& s : {one, three}) {
    expect_same(weight_sums(plain, &spot, s), in_spot);
    expect_same(weight_sums(compact, &spot, s), in_spot);
  }
  // The mask's complement: its partly covered tiles are mostly covered, so a compacted
  // frame blends the pixels outside it there and subtracts their sums from the stored ones.
  Image complement = mask;
  for (float& p : complement.data) p = p > 0.5f ? 0.f : 1.f;
  const GaussianWeights rest = reference_sums(g, cam, &complement);
  ASSERT_GT(rest.index.size(), 100u);
  for (const RenderSettings& s : {one, three}) {
    expect_same(weight_sums(plain, &complement, s), rest);
    expect_same(weight_sums(compact, &complement, s), rest);
  }
  // With values the same pass renders their blend over the mask's tiles (every tile
  // with all_tiles), as rasterize does.
  std::vector<float> values(g.size());
  for (size_t i = 0; i < values.size(); ++i) values[i] = (i % 3 == 0) ? 1.f : 0.f;
  const Image expected = rasterize(plain, {}, &values).value;
  Image covered;
  expect_same(weight_sums(compact, &mask, {}, &values, &covered, ValueExtent::kAllTiles), masked);
  EXPECT_EQ(covered.data, expected.data);
  // At the mask's pixels only: the same values there, 0 elsewhere.
  Image at_mask;
  expect_same(weight_sums(compact, &mask, {}, &values, &at_mask, ValueExtent::kMaskPixels), masked);
  int inside = 0;
  for (size_t p = 0; p < at_mask.data.size(); ++p) {
    ASSERT_EQ(at_mask.data[p], mask.data[p] > 0.5f ? expected.data[p] : 0.f) << "pixel " << p;
    inside += mask.data[p] > 0.5f && expected.data[p] > 0.f;
  }
  EXPECT_GT(inside, 100);
  expect_same(weight_sums(compact, &mask, {}, &values, &covered, ValueExtent::kMaskTiles), masked);
  int outside = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      bool touched = false;
      const int tx = x / kTileSize, ty = y / kTileSize;
      for (int yy = ty * kTileSize; yy < std::min(cam.height, (ty + 1) * kTileSize) && !touched; ++yy)
        for (int xx = tx * kTileSize; xx < std::min(cam.width, (tx + 1) * kTileSize); ++xx)
          if (mask.at(xx, yy) > 0.5f) touched = true;
      ASSERT_EQ(covered.at(x, y), touched ? expected.at(x, y) : 0.f);
      outside += !touched;
    }
  EXPECT_GT(outside, 0);
  Image wrong(cam.width + 1, cam.height, 1);
  EXPECT_THROW(weight_sums(compact, &wrong, {}), Error);
}

TEST(Visibility, TilesListingFindsTheWantedAndListsTheRestsGaussians) {
  // Against the frame's own tile lists: a flagged tile comes out 1 when its list names a
  // wanted Gaussian, and the Gaussians of the flagged tiles that name none are the bits set.
  const GaussianScene g = dense_cloud(8000, 5);
  const Camera cam = Camera::look_at({0.3, -3.0, 0.8}, {0, 0, 0}, {0, 0, 1}, 130, 90, 60);
  PreparedFrame frame = prepare_frame(g, cam);
  compact_frame(frame, {});
  const PreparedFrame::Data& d = PreparedFrameAccess::data(frame);
  const size_t tiles = size_t(frame.grid_x) * frame.grid_y;
  uint64_t s = 77;
  auto rnd = [&] { return (s = s * 6364136223846793005ull + 1442695040888963407ull) >> 33; };
  for (int trial = 0; trial < 4; ++trial) {
    std::vector<bool> wanted(g.size(), false);
    for (size_t j = 0; j < g.size(); ++j) wanted[j] = rnd() % (trial == 0 ? 2000 : 200) == 0;
    std::vector<uint8_t> flags(tiles, 0);
    for (size_t t = 0; t < tiles; ++t) flags[t] = rnd() % 3 != 0;
    std::vector<uint8_t> want_out(tiles, 0);
    std::vector<uint64_t> want_bits((g.size() + 63) / 64, 0);
    size_t rest = 0;
    for (size_t t = 0; t < tiles; ++t) {
      if (!flags[t]) continue;
      for (uint32_t e = d.tile_start[t]; e < d.tile_start[t + 1]; ++e) want_out[t] |= wanted[d.splats[d.tile_list[e]].index];
      if (want_out[t]) continue;
      ++rest;
      for (uint32_t e = d.tile_start[t]; e < d.tile_start[t + 1]; ++e) {
        const uint32_t j = d.splats[d.tile_list[e]].index;
        want_bits[j >> 6] |= uint64_t(1) << (j & 63);
      }
    }
    ASSERT_GT(rest, 0u);
    ASSERT_NE(want_bits, std::vector<uint64_t>(want_bits.size(), 0));  // the rest's tiles list Gaussians
    for (int threads : {1, 3}) {
      std::vector<uint64_t> bits((g.size() + 63) / 64, 0);
      EXPECT_EQ(tiles_listing(frame, flags, wanted, threads, &bits), want_out) << "trial " << trial;
      EXPECT_EQ(bits, want_bits) << "trial " << trial << ", " << threads << " threads";
      EXPECT_EQ(tiles_listing(frame, flags, wanted, threads), want_out);
    }
  }
  std::vector<uint64_t> short_bits(3, 0);
  EXPECT_THROW(tiles_listing(frame, std::vector<uint8_t>(tiles, 1), std::vector<bool>(g.size(), false), 1, &short_bits),
               Error);
}

TEST(Visibility, BinnedTilesAreTheTilesAFrameListsEachGaussianIn) {
  // A frame as prepared bins each splat into every tile of its rect, so the tiles whose lists
  // name a Gaussian are its binned_tiles box exactly; a compacted frame names it in some of
  // them (its blended entries), never outside. Gaussians the frame holds no splat of (behind
  // the camera here) come out empty. Near plane and blur other than the defaults, kept by
  // the frame.
  GaussianScene g = dense_cloud(8000, 3);
  const Camera cam = Camera::look_at({0.3, -3.0, 0.8}, {0, 0, 0}, {0, 0, 1}, 130, 90, 60);
  for (size_t i = 0; i < 50; ++i) g.positions[3 * i + 1] = -6.f;  // behind the camera
  RenderSettings rs;
  rs.near_plane = 0.5f;
  rs.blur = 0.5f;
  PreparedFrame plain = prepare_frame(g, cam, rs), compact = prepare_frame(g, cam, rs);
  compact_frame(compact, rs);
  std::vector<uint32_t> all(g.size());
  for (uint32_t j = 0; j < g.size(); ++j) all[j] = j;
  size_t listed = 0, empty = 0;
  for (const PreparedFrame* frame : {&plain, &compact}) {
    const PreparedFrame::Data& d = PreparedFrameAccess::data(*frame);
    const std::vector<TileBox> boxes = binned_tiles(g, *frame, all);
    ASSERT_EQ(boxes.size(), g.size());
    std::vector<std::vector<size_t>> tiles_of(g.size());
    for (size_t t = 0; t + 1 < d.tile_start.size(); ++t)
      for (uint32_t e = d.tile_start[t]; e < d.tile_start[t + 1]; ++e) tiles_of[d.splats[d.tile_list[e]].index].push_back(t);
    for (uint32_t j = 0; j < g.size(); ++j) {
      const TileBox& b = boxes[j];
      const size_t area = b.x1 < b.x0 ? 0 : size_t(b.x1 - b.x0 + 1) * size_t(b.y1 - b.y0 + 1);
      for (size_t t : tiles_of[j]) {
        const int tx = int(t % size_t(frame->grid_x)), ty = int(t / size_t(frame->grid_x));
        ASSERT_TRUE(tx >= b.x0 && tx <= b.x1 && ty >= b.y0 && ty <= b.y1) << "Gaussian " << j << ", tile " << t;
      }
      if (frame == &plain) {
        ASSERT_EQ(tiles_of[j].size(), area) << "Gaussian " << j;
        listed += area > 0;
        empty += area == 0;
        if (j < 50) {
          ASSERT_EQ(area, 0u);
        }
      }
    }
  }
  std::printf("binned tiles: %zu Gaussians binned, %zu with no splat\n", listed, empty);
  EXPECT_GT(listed, g.size() / 2);
  EXPECT_GE(empty, 50u);
  EXPECT_THROW(binned_tiles(dense_cloud(10, 1), plain, {0}), Error);
  EXPECT_THROW(binned_tiles(g, plain, {uint32_t(g.size())}), Error);
}

TEST(Visibility, TilesReachedAreTheTilesWhoseListsNameAValuedGaussian) {
  // A few Gaussians carry values: the tiles their splats reach are the tiles whose lists
  // name one of them (binning boxes each splat by its unrounded half-widths, which the
  // stored ones round up by under 1/16 px: on this scene no box crosses a tile edge in that
  // margin), and a render over those tiles alone has every pixel of the render over all tiles.
  const GaussianScene g = dense_cloud(8000, 9);
  const Camera cam = Camera::look_at({0.3, -3.0, 0.8}, {0, 0, 0}, {0, 0, 1}, 130, 90, 60);
  PreparedFrame plain = prepare_frame(g, cam), compact = prepare_frame(g, cam);
  compact_frame(compact, {});
  const size_t tiles = size_t(plain.grid_x) * plain.grid_y;
  uint64_t s = 31;
  auto rnd = [&] { return (s = s * 6364136223846793005ull + 1442695040888963407ull) >> 33; };
  RenderSettings rs;
  rs.color = rs.depth = false;
  for (int trial = 0; trial < 3; ++trial) {
    std::vector<float> values(g.size(), 0.f);
    std::vector<bool> valued(g.size(), false);
    for (size_t j = 0; j < g.size(); ++j)
      if (rnd() % (trial == 0 ? 1000 : 60) == 0) {
        values[j] = trial == 2 ? 0.25f + float(rnd() % 4) * 0.25f : 1.f;
        valued[j] = true;
      }
    const std::vector<uint8_t> listing = tiles_listing(plain, std::vector<uint8_t>(tiles, 1), valued, 1);
    const std::vector<uint8_t> reached = tiles_reached(plain, valued, 3);
    EXPECT_EQ(reached, listing) << "trial " << trial;
    size_t flagged = 0;
    for (uint8_t f : reached) flagged += f;
    EXPECT_GT(flagged, 0u);
    EXPECT_LT(flagged, tiles) << "trial " << trial << ": the test needs tiles no valued splat reaches";
    for (const PreparedFrame* frame : {&plain, &compact}) {
      const std::vector<uint8_t> t = tiles_reached(*frame, valued, 2);
      const Image all = rasterize(*frame, rs, &values).value;
      const Image only = rasterize(*frame, rs, &values, nullptr, &t).value;
      EXPECT_EQ(only.data, all.data) << "trial " << trial;
    }
  }
  EXPECT_THROW(tiles_reached(plain, std::vector<bool>(3, true)), Error);
}

TEST(Visibility, SplitInOrderKeepsEachSidesOrderOnAnyNumberOfThreads) {
  // Several chunks and a bit (list_grain(n) entries each), flags in an irregular pattern.
  const size_t n = 3 * kListGrain + 1234;
  GaussianWeights list;
  std::vector<uint8_t> flags(n);
  for (size_t k = 0; k < n; ++k) {
    list.index.push_back(uint32_t(3 * k + 1));
    list.weight.push_back(int64_t(k % 97 + 1));
    flags[k] = (k * 2654435761u >> 7) % 3 == 0;
  }
  GaussianWeights flagged, rest;
  for (size_t k = 0; k < n; ++k) {
    GaussianWeights& to = flags[k] ? flagged : rest;
    to.index.push_back(list.index[k]);
    to.weight.push_back(list.weight[k]);
  }
  ASSERT_GT(flagged.index.size(), n / 4);
  ASSERT_GT(rest.index.size(), n / 2);
  for (int threads : {1, 2, 4}) {
    const SplitWeights split = split_in_order(list, flags, threads);
    EXPECT_EQ(split.flagged.index, flagged.index) << threads << " threads";
    EXPECT_EQ(split.flagged.weight, flagged.weight) << threads << " threads";
    EXPECT_EQ(split.rest.index, rest.index) << threads << " threads";
    EXPECT_EQ(split.rest.weight, rest.weight) << threads << " threads";
  }
  const SplitWeights empty = split_in_order(GaussianWeights{}, {}, 2);
  EXPECT_TRUE(empty.flagged.index.empty() && empty.rest.index.empty());
}

}  // namespace
}  // namespace isegman
