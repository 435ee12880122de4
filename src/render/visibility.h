// Exact per-Gaussian visibility of a prepared frame: the blending weights w = alpha * T
// each Gaussian receives, summed over a set of pixels. Each weight is rounded to 2^-24
// fixed point before it is summed, so sums are integers: exact, independent of thread
// count and order, and removable again bit for bit (segment/votes.h builds on this).
//
// A frame kept for many such passes is compacted once: the (tile, Gaussian) entries that
// were never blended at a pixel still open (hidden behind pixels that had already ended,
// or below alpha 1/255 wherever they reach) are dropped, which changes no output of any
// later pass, and every remaining entry keeps its weight summed over its whole tile. A
// pixel mask then costs a rasterisation only for the tiles it covers partly; the tiles
// it covers fully are read from those sums. In a partly covered tile a sums pass blends
// the mask's pixels or the rest of the tile, whichever touches fewer row groups (the rest's
// sums subtracted from the tile's).
#pragma once

#include <cstdint>
#include <vector>

#include "core/image.h"
#include "render/rasterizer.h"

namespace isegman {

constexpr double kWeightScale = 16777216.0;  // 2^24 fixed-point units per unit weight
inline int64_t fixed_weight(float w) { return int64_t(double(w) * kWeightScale + 0.5); }  // w >= 0

// Per-Gaussian sums, ascending Gaussian index, zero sums left out.
struct GaussianWeights {
  std::vector<uint32_t> index;
  std::vector<int64_t> weight;  // fixed point
};

// The lists a pass built in chunks (each over its own ascending run of Gaussians, the runs
// in order) joined into one.
GaussianWeights join_in_order(std::vector<GaussianWeights> parts);

// `list` split by a flag per entry (flagged.size() == list.index.size()): the entries
// flagged and those not, each in its order. In parallel chunks over long lists.
struct SplitWeights {
  GaussianWeights flagged, rest;
};
SplitWeights split_in_order(const GaussianWeights& list, const std::vector<uint8_t>& flagged, int threads);

// Compacts `frame` (see above) with one full pass, which also renders it: returns what
// rasterize(frame, settings) would. The frame then renders only with settings.alpha_max,
// and colour or depth only when `keep_shading` (frames kept for voting need neither:
// rasterize throws for them).
RenderOutput compact_frame(PreparedFrame& frame, const RenderSettings& settings, bool keep_shading = false);
bool is_compact(const PreparedFrame& frame);
// Bytes the frame holds.
size_t frame_bytes(const PreparedFrame& frame);

// Where weight_sums renders `values` (0 elsewhere): over the tiles the mask touches, over
// every tile, or at the mask's pixels only (its partly covered tiles then blend only those
// pixels, as the sums alone do: a pixel's blend does not depend on the other pixels).
enum class ValueExtent { kMaskTiles, kAllTiles, kMaskPixels };

// Weights summed over the pixels where mask > 0.5 (mask at the frame's resolution, one
// channel), or over every pixel without a mask. With `values` (one per Gaussian) the
// same pass renders their blend into `value_image` over `extent`, as rasterize() does.
GaussianWeights weight_sums(const PreparedFrame& frame, const Image* mask, const RenderSettings& settings,
                            const std::vector<float>* values = nullptr, Image* value_image = nullptr,
                            ValueExtent extent = ValueExtent::kMaskTiles);

// The Gaussians a frame's tiles list (flags over the frame's tiles, grid_x * grid_y): for
// each flagged tile, whether its list names a Gaussian `wanted` holds (one flag per
// Gaussian of the scene); unflagged tiles come out 0. `unwanted_listed` (optional: one bit
// per Gaussian of the scene, in 64-bit words): the Gaussians the flagged tiles that name
// none wanted list are set in it (those tiles' lists are read whole anyway).
std::vector<uint8_t> tiles_listing(const PreparedFrame& frame, const std::vector<uint8_t>& tiles,
                                   const std::vector<bool>& wanted, int threads = 0,
                                   std::vector<uint64_t>* unwanted_listed = nullptr);
// The tiles the splats of the flagged Gaussians reach (one flag per Gaussian of the scene;
// flags over the frame's tiles): the only tiles where a blend of values 0 elsewhere is not
// 0. One pass over the frame's splats, which hold each one's pixel box already; flags in
// bits, because a compacted frame's splats come in tile order, not by Gaussian.
std::vector<uint8_t> tiles_reached(const PreparedFrame& frame, const std::vector<bool>& flagged, int threads = 0);

}  // namespace isegman
