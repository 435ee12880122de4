// Internals shared by rasterizer.cc and visibility.cc, not an API: the projected splat,
// the prepared frame's storage and one pass over a frame's tiles.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "render/rasterizer.h"

namespace isegman {

// A projected Gaussian, as the tile loop reads it. 32 bytes: a prepared frame of a large
// scene holds millions, so colours and depths live apart (frames kept for voting drop them).
struct Splat {
  float mx, my;          // centre, index coordinates
  float ca, cb, cc;      // conic
  float opacity;         // activated
  uint32_t index;        // Gaussian index in the scene
  // Half-widths of the pixel box outside which alpha < 1/255, in 1/16 pixel rounded up:
  // [ceil(mx - hx / 16), floor(mx + hx / 16)] (and the same in y) holds every pixel it
  // reaches; kWholeImage: wider than any image. 4 bytes instead of the box's 8 keep a splat
  // at 32 bytes (kept frames hold millions); a finer unit than whole pixels keeps the box
  // from growing a row for most small splats (the voting passes' cost).
  uint16_t hx, hy;
};
static_assert(sizeof(Splat) == 32, "a splat is half a cache line");
constexpr float kHalfWidthUnit = 1.f / 16;
constexpr uint16_t kWholeImage = 65535;
inline uint16_t encode_half_width(float e) {
  const float units = std::ceil(e / kHalfWidthUnit);
  return units < float(kWholeImage) ? uint16_t(units) : kWholeImage;
}
inline float decode_half_width(uint16_t h) { return h == kWholeImage ? 1e9f : float(h) * kHalfWidthUnit; }

// The tile kernel blends a tile's row in groups of this many pixels (one vector; its
// buffers hold pixel k = row * 16 + column, two groups a row), so a pass over some of a
// tile's pixels costs the groups they touch.
constexpr int kLanes = 8;

struct PreparedFrame::Data {
  // Visible Gaussians in depth order; after compact_frame in the order the tiles first list
  // them (tile by tile, front to back; the tile lists keep the depth order), so a tile's
  // splats lie close together and a pass blending it reads them nearly in order.
  std::vector<Splat> splats;
  std::vector<float> rgb;             // 3 per splat; empty: the frame renders black
  std::vector<float> depth;           // per splat; empty after compact_frame without shading
  std::vector<uint32_t> tile_start;   // tiles + 1 offsets into tile_list
  std::vector<uint32_t> tile_list;    // per tile: indices into splats, front to back
  // Set by compact_frame: per tile_list entry, its fixed-point weights summed over the
  // tile's pixels; and the alpha_max the compaction is exact for.
  std::vector<uint32_t> entry_weight;
  // Also set by compact_frame: alpha, and the blend of the value 1 for every Gaussian
  // (sum of w per pixel). A value pass over a tile whose Gaussians all carry 1, or all 0,
  // is one of these (w * 1 == w and w * 0 == 0 exactly), so it needs no blending.
  std::vector<float> alpha_all, value_all;
  bool compact = false;
  float alpha_max = 0;
  // What prepare_frame projected with (binned_tiles projects the same way).
  float near_plane = 0, blur = 0;
};

struct PreparedFrameAccess {
  static PreparedFrame::Data& data(PreparedFrame& f) { return *f.data_; }
  static const PreparedFrame::Data& data(const PreparedFrame& f) { return *f.data_; }
  static void adopt(PreparedFrame& f, std::unique_ptr<PreparedFrame::Data> d) { f.data_ = std::move(d); }
};

// What one pass over a frame's tiles computes besides the images.
struct TilePass {
  const std::vector<float>* values = nullptr;
  ContributionVisitor* visitor = nullptr;
  const std::vector<uint8_t>* tile_mask = nullptr;  // only these tiles (nullptr: all)
  // Per-entry sums: after each rasterised tile, on_tile gets for every entry of the
  // tile's list the fixed_weight()s summed over its pixels where sum_mask > 0.5 (all
  // pixels when sum_mask is null), and whether the entry was blended at a pixel that was
  // still open (contributed, or ended it): an entry that never was changes no pixel.
  const Image* sum_mask = nullptr;
  const std::vector<uint8_t>* sum_tiles = nullptr;  // on_tile only for these (nullptr: all)
  // Summed tiles blend only their pixels where sum_mask > 0.5 (a pixel's weights do not
  // depend on other pixels): the sums are the same, the images there are not rendered.
  bool sum_pixels_only = false;
  std::function<void(int worker, size_t tile, const uint32_t* sums, const uint8_t* blended)> on_tile;
};

RenderOutput run_tiles(const PreparedFrame& frame, const RenderSettings& s, const TilePass& pass);

}  // namespace isegman
