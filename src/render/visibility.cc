#include "render/visibility.h"

#include <algorithm>
#include <mutex>
#include <numeric>

#include "core/error.h"
#include "core/parallel.h"
#include "core/prefetch.h"
#include "render/radix_sort.h"
#include "render/tile_kernel.h"

namespace isegman {

namespace {
// Per-splat sum arrays, kept zeroed between passes: a dense frame's pass would otherwise
// allocate and clear one per worker (tens of MB at millions of splats) every time. A pass
// takes what it needs and gives the arrays back zeroed (its read-out clears them); at
// most kKeptArrays stay, so the memory held is a few arrays of the largest frame.
class SplatSums {
 public:
  std::vector<uint64_t> take(size_t n) {
    std::vector<uint64_t> a;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!kept_.empty()) {
        a = std::move(kept_.back());
        kept_.pop_back();
      }
    }
    // A kept array is zero throughout (the read-out clears what a pass wrote): growing it
    // zeroes only the new tail, not the 8 bytes a splat of a frame millions of splats long.
    if (a.size() < n) a.resize(n, 0);
    return a;
  }
  void give_back(std::vector<uint64_t> a) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (kept_.size() < kKeptArrays) kept_.push_back(std::move(a));
  }

 private:
  static constexpr size_t kKeptArrays = 4;
  std::mutex mutex_;
  std::vector<std::vector<uint64_t>> kept_;
};
SplatSums& splat_sums() {
  static SplatSums pool;
  return pool;
}

// The (Gaussian, sum) pairs in ascending Gaussian index, the sums of a Gaussian listed more
// than once added up (integers, so the order they were found in does not matter).
template <class Sum>
GaussianWeights sum_by_gaussian(std::vector<uint32_t> keys, const std::vector<Sum>& sums, int threads) {
  std::vector<uint32_t> position(keys.size());
  std::iota(position.begin(), position.end(), 0u);
  radix_sort_pairs(keys, position, threads);
  GaussianWeights out;
  out.index.reserve(keys.size());
  out.weight.reserve(keys.size());
  for (size_t i = 0; i < keys.size();) {
    const uint32_t g = keys[i];
    int64_t total = 0;
    for (; i < keys.size() && keys[i] == g; ++i) total += int64_t(sums[position[i]]);
    out.index.push_back(g);
    out.weight.push_back(total);
  }
  return out;
}
}  // namespace

GaussianWeights join_in_order(std::vector<GaussianWeights> parts) {
  if (parts.size() == 1) return std::move(parts[0]);
  size_t n = 0;
  for (const GaussianWeights& part : parts) n += part.index.size();
  GaussianWeights out;
  out.index.reserve(n);
  out.weight.reserve(n);
  for (const GaussianWeights& part : parts) {
    out.index.insert(out.index.end(), part.index.begin(), part.index.end());
    out.weight.insert(out.weight.end(), part.weight.begin(), part.weight.end());
  }
  return out;
}

SplitWeights split_in_order(const GaussianWeights& list, const std::vector<uint8_t>& flagged, int threads) {
  const size_t n = list.index.size();
  const size_t grain = list_grain(n);
  const size_t chunks = chunk_count(n, grain);
  std::vector<GaussianWeights> flagged_parts(chunks), rest_parts(chunks);
  parallel_chunks(n, grain, threads, [&](size_t chunk, size_t begin, size_t end) {
    GaussianWeights in, out;  // locals, moved in at the end: the chunks' lists share cache lines
    for (size_t k = begin; k < end; ++k) {
      GaussianWeights& to = flagged[k] ? in : out;
      to.index.push_back(list.index[k]);
      to.weight.push_back(list.weight[k]);
    }
    flagged_parts[chunk] = std::move(in);
    rest_parts[chunk] = std::move(out);
  });
  return {join_in_order(std::move(flagged_parts)), join_in_order(std::move(rest_parts))};
}

RenderOutput compact_frame(PreparedFrame& frame, const RenderSettings& s, bool keep_shading) {
  PreparedFrame::Data& d = PreparedFrameAccess::data(frame);
  if (d.compact) {
    RenderOutput out = rasterize(frame, s);
    if (!keep_shading) {
      std::vector<float>().swap(d.rgb);
      std::vector<float>().swap(d.depth);
    }
    return out;
  }
  const size_t entries = d.tile_list.size();
  std::vector<uint32_t> sums(entries);
  std::vector<uint8_t> blended(entries);
  const std::vector<float> ones(frame.gaussians, 1.f);
  TilePass pass;
  pass.values = &ones;
  pass.on_tile = [&](int, size_t t, const uint32_t* su, const uint8_t* bl) {
    const size_t b = d.tile_start[t], n = d.tile_start[t + 1] - b;
    std::copy(su, su + n, sums.begin() + std::ptrdiff_t(b));
    std::copy(bl, bl + n, blended.begin() + std::ptrdiff_t(b));
  };
  RenderOutput out = run_tiles(frame, s, pass);
  d.alpha_all = out.alpha.data;
  d.value_all = std::move(out.value.data);
  out.value = Image();

  // Keep the blended entries, and the splats they refer to in the order the tiles first
  // list them: tile by tile, front to back. A tile's splats then lie close together, and
  // the passes that blend it read them nearly in order instead of at random across a
  // frame of millions (a mask's sums over a 6M-Gaussian view ~16 -> ~12 ms, BM_VotePass).
  const size_t tiles = d.tile_start.size() - 1;
  constexpr uint32_t kDropped = UINT32_MAX;
  std::vector<uint32_t> remap(d.splats.size(), kDropped), order;  // order: old positions, new order
  std::vector<uint32_t> start(tiles + 1, 0);
  size_t kept = 0;
  for (size_t t = 0; t < tiles; ++t) {
    for (size_t e = d.tile_start[t]; e < d.tile_start[t + 1]; ++e)
      if (blended[e]) {
        ++kept;
        uint32_t& to = remap[d.tile_list[e]];
        if (to == kDropped) {
          to = uint32_t(order.size());
          order.push_back(d.tile_list[e]);
        }
      }
    start[t + 1] = uint32_t(kept);
  }
  const size_t live = order.size();
  std::vector<Splat> splats(live);
  std::vector<float> rgb(keep_shading && !d.rgb.empty() ? 3 * live : 0), depth(keep_shading ? live : 0);
  for (size_t j = 0; j < live; ++j) {
    const size_t i = order[j];
    splats[j] = d.splats[i];
    if (!rgb.empty())
      for (int c = 0; c < 3; ++c) rgb[3 * j + c] = d.rgb[3 * i + c];
    if (keep_shading) depth[j] = d.depth[i];
  }
  std::vector<uint32_t>().swap(order);
  std::vector<uint32_t> list(kept), weight(kept);
  for (size_t e = 0, k = 0; e < entries; ++e)
    if (blended[e]) {
      list[k] = remap[d.tile_list[e]];
      weight[k++] = sums[e];
    }
  d.splats = std::move(splats);
  d.rgb = std::move(rgb);
  d.depth = std::move(depth);
  d.tile_start = std::move(start);
  d.tile_list = std::move(list);
  d.entry_weight = std::move(weight);
  d.compact = true;
  d.alpha_max = s.alpha_max;
  frame.stats.tile_pairs = kept;
  return out;
}

bool is_compact(const PreparedFrame& frame) { return PreparedFrameAccess::data(frame).compact; }

size_t frame_bytes(const PreparedFrame& frame) {
  const PreparedFrame::Data& d = PreparedFrameAccess::data(frame);
  return sizeof(PreparedFrame) + sizeof(PreparedFrame::Data) + d.splats.capacity() * sizeof(Splat) +
         (d.rgb.capacity() + d.depth.capacity() + d.tile_start.capacity() + d.tile_list.capacity() + d.entry_weight.capacity() +
          d.alpha_all.capacity() + d.value_all.capacity()) *
             4;
}

GaussianWeights weight_sums(const PreparedFrame& frame, const Image* mask, const RenderSettings& settings,
                            const std::vector<float>* values, Image* value_image, ValueExtent extent) {
  const bool all_tiles = extent == ValueExtent::kAllTiles;
  const PreparedFrame::Data& d = PreparedFrameAccess::data(frame);
  const int gx = frame.grid_x, gy = frame.grid_y, W = frame.camera.width, H = frame.camera.height;
  const size_t tiles = size_t(gx) * gy;
  // Tiles the mask touches, and those it covers entirely.
  std::vector<uint8_t> touched(tiles, mask ? 0 : 1), full(tiles, mask ? 0 : 1);
  if (mask) {
    if (mask->width != W || mask->height != H || mask->channels != 1)
      throw Error("visibility: the pixel mask does not match the view's resolution");
    // Counted a tile's row at a time (a loop the compiler vectorises; a view is ~10^6 pixels
    // and a click runs this pass dozens of times).
    std::vector<uint32_t> on(tiles, 0);
    for (int y = 0; y < H; ++y) {
      const float* row = mask->data.data() + size_t(y) * W;
      uint32_t* counts = on.data() + size_t(y / kTileSize) * gx;
      for (int tx = 0; tx < gx; ++tx) {
        const int x0 = tx * kTileSize, x1 = std::min(W, x0 + kTileSize);
        uint32_t c = 0;
        for (int x = x0; x < x1; ++x) c += row[x] > 0.5f;
        counts[tx] += c;
      }
    }
    for (size_t t = 0; t < tiles; ++t) {
      const int tx = int(t % gx), ty = int(t / gx);
      const uint32_t pixels = uint32_t((std::min(W, (tx + 1) * kTileSize) - tx * kTileSize) *
                                       (std::min(H, (ty + 1) * kTileSize) - ty * kTileSize));
      touched[t] = on[t] > 0;
      full[t] = on[t] == pixels;
    }
  }
  // Fully covered tiles of a compacted frame come from its stored sums, unless the pass
  // renders values there anyway.
  const bool stored = d.compact;
  std::vector<uint8_t> raster(tiles, 0), summed(tiles, 0);
  bool any_raster = false;
  for (size_t t = 0; t < tiles; ++t) {
    summed[t] = touched[t] && !(stored && full[t]);
    raster[t] = summed[t] || (values && (all_tiles || touched[t]));
    any_raster |= raster[t] != 0;
  }
  // A partly covered tile of a compacted frame may blend the pixels outside the mask
  // instead, when they occupy fewer row groups of 8 lanes (the unit the tile kernel
  // blends): the mask's sums are the stored sums less theirs, exactly, being integers.
  // Only when no image is rendered there (the image needs the mask's own pixels).
  std::vector<uint8_t> outside(tiles, 0);
  Image flipped;
  if (stored && mask && !values) {
    for (size_t t = 0; t < tiles; ++t) {
      if (!summed[t]) continue;
      const int x0 = int(t % gx) * kTileSize, y0 = int(t / gx) * kTileSize;
      const int x1 = std::min(W, x0 + kTileSize), y1 = std::min(H, y0 + kTileSize);
      int in_groups = 0, out_groups = 0;
      for (int y = y0; y < y1; ++y)
        for (int xg = x0; xg < x1; xg += kLanes) {
          bool in = false, out = false;
          for (int x = xg; x < std::min(x1, xg + kLanes); ++x) (mask->data[size_t(y) * W + x] > 0.5f ? in : out) = true;
          in_groups += in;
          out_groups += out;
        }
      outside[t] = out_groups < in_groups;
      if (!outside[t]) continue;
      if (flipped.empty()) flipped = *mask;
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
          float& p = flipped.data[size_t(y) * W + x];
          p = p > 0.5f ? 0.f : 1.f;
        }
    }
  }
  const int slots = resolve_threads(settings.threads);
  // Each tile gives a (Gaussian, sum) pair per entry. Few pairs are sorted by Gaussian and
  // summed; many (a large mask over a dense frame) are summed per splat instead, one array
  // per worker, read out in splat order and then sorted by Gaussian: one pair a splat to
  // sort instead of one an entry, and the same integers.
  const size_t live = d.splats.size();
  size_t entries = 0;
  for (size_t t = 0; t < tiles; ++t)
    if (touched[t] || raster[t]) entries += d.tile_start[t + 1] - d.tile_start[t];
  const bool dense = stored && entries > live / 8;
  std::vector<std::vector<uint64_t>> per_splat(dense ? size_t(slots) : 0);
  // Per worker, a flag per block of kBlock splats that it summed into: the read-out skips
  // the blocks no worker wrote (a mask's Gaussians are a small share of a large frame's).
  constexpr size_t kBlockShift = 6, kBlock = size_t(1) << kBlockShift;
  const size_t blocks = (live + kBlock - 1) / kBlock;
  std::vector<std::vector<uint8_t>> written(dense ? size_t(slots) : 0);
  std::vector<std::vector<uint32_t>> keys(static_cast<size_t>(slots)), sums(static_cast<size_t>(slots));
  auto add_pairs = [&](int w, size_t t, const uint32_t* entry_sums, bool rest_of_tile) {
    const size_t b = d.tile_start[t], n = d.tile_start[t + 1] - b;
    if (dense) {
      std::vector<uint64_t>& into = per_splat[size_t(w)];
      std::vector<uint8_t>& flags = written[size_t(w)];
      if (into.empty()) {
        into = splat_sums().take(live);
        flags.assign(blocks, 0);
      }
      uint64_t* to = into.data();  // raw pointers: a byte store could alias the vectors' own fields
      uint8_t* marks = flags.data();
      for (size_t e = 0; e < n; ++e) {
        const uint32_t splat = d.tile_list[b + e];
        to[splat] += rest_of_tile ? d.entry_weight[b + e] - entry_sums[e] : entry_sums[e];
        marks[splat >> kBlockShift] = 1;
      }
      return;
    }
    // Grown as locals: the workers' vectors sit side by side, and growing them in place would
    // write a cache line the other worker writes too at every pair (false sharing).
    std::vector<uint32_t> k = std::move(keys[size_t(w)]), s = std::move(sums[size_t(w)]);
    for (size_t e = 0; e < n; ++e) {
      const uint32_t v = rest_of_tile ? d.entry_weight[b + e] - entry_sums[e] : entry_sums[e];
      if (v) {
        k.push_back(d.splats[d.tile_list[b + e]].index);
        s.push_back(v);
      }
    }
    keys[size_t(w)] = std::move(k);
    sums[size_t(w)] = std::move(s);
  };
  if (any_raster) {
    RenderSettings rs = settings;
    rs.color = false;
    rs.depth = false;
    TilePass pass;
    pass.values = values;
    pass.tile_mask = &raster;
    pass.sum_mask = flipped.empty() ? mask : &flipped;
    pass.sum_tiles = &summed;
    // Only the mask's pixels matter when no image is returned, or only its pixels are asked for.
    pass.sum_pixels_only = mask && (!values || extent == ValueExtent::kMaskPixels);
    pass.on_tile = [&](int w, size_t t, const uint32_t* entry_sums, const uint8_t*) {
      add_pairs(w, t, entry_sums, outside[t] != 0);
    };
    RenderOutput r = run_tiles(frame, rs, pass);
    if (values && value_image) *value_image = std::move(r.value);
  } else if (values && value_image) {
    *value_image = Image(W, H, 1);
  }
  if (stored)
    parallel_for(tiles, slots, [&](int w, size_t t) {
      if (touched[t] && !summed[t]) add_pairs(w, t, d.entry_weight.data() + d.tile_start[t], false);
    });

  if (dense) {
    // Read out in contiguous chunks in parallel, each into its own list, joined in order.
    // Many more chunks than workers: the written blocks bunch together (an object's
    // Gaussians sit side by side), so one chunk per worker left one worker all of them.
    const size_t chunks = std::max<size_t>(1, std::min(blocks, size_t(slots) * 32)), blocks_per_chunk = (blocks + chunks - 1) / chunks;
    std::vector<GaussianWeights> parts(chunks);
    parallel_for(chunks, slots, [&](int, size_t c) {
      GaussianWeights part;  // a local, moved in at the end: the parts share cache lines
      for (size_t k = c * blocks_per_chunk, k_end = std::min(blocks, (c + 1) * blocks_per_chunk); k < k_end; ++k) {
        bool any = false;
        for (size_t w = 0; w < per_splat.size(); ++w) any |= !per_splat[w].empty() && written[w][k];
        if (!any) continue;
        for (size_t i = k * kBlock, e = std::min(live, (k + 1) * kBlock); i < e; ++i) {
          uint64_t total = 0;
          for (size_t w = 0; w < per_splat.size(); ++w) {
            std::vector<uint64_t>& from = per_splat[w];
            if (from.empty() || !written[w][k]) continue;
            total += from[i];
            from[i] = 0;  // zeroed for the next pass
          }
          if (total) {
            part.index.push_back(d.splats[i].index);
            part.weight.push_back(int64_t(total));
          }
        }
      }
      parts[c] = std::move(part);
    });
    for (std::vector<uint64_t>& from : per_splat)
      if (!from.empty()) splat_sums().give_back(std::move(from));
    GaussianWeights joined = join_in_order(std::move(parts));  // each Gaussian once, in splat order
    return sum_by_gaussian(std::move(joined.index), joined.weight, slots);
  }
  // Each worker's (Gaussian, sum) pairs, a Gaussian once per tile it was found in.
  size_t pairs = 0;
  for (const auto& k : keys) pairs += k.size();
  std::vector<uint32_t> all_keys, all_sums;
  all_keys.reserve(pairs);
  all_sums.reserve(pairs);
  for (int w = 0; w < slots; ++w) {
    all_keys.insert(all_keys.end(), keys[size_t(w)].begin(), keys[size_t(w)].end());
    all_sums.insert(all_sums.end(), sums[size_t(w)].begin(), sums[size_t(w)].end());
    std::vector<uint32_t>().swap(keys[size_t(w)]);
    std::vector<uint32_t>().swap(sums[size_t(w)]);
  }
  return sum_by_gaussian(std::move(all_keys), all_sums, slots);
}

std::vector<uint8_t> tiles_listing(const PreparedFrame& frame, const std::vector<uint8_t>& tiles,
                                   const std::vector<bool>& wanted, int threads,
                                   std::vector<uint64_t>* unwanted_listed) {
  const PreparedFrame::Data& d = PreparedFrameAccess::data(frame);
  const size_t n = size_t(frame.grid_x) * frame.grid_y;
  if (tiles.size() != n) throw Error("tiles_listing: tile flags do not match the frame");
  if (wanted.size() != frame.gaussians) throw Error("tiles_listing: Gaussian flags do not match the scene");
  if (unwanted_listed && unwanted_listed->size() != (frame.gaussians + 63) / 64)
    throw Error("tiles_listing: the listed Gaussians' bits do not match the scene");
  std::vector<uint8_t> out(n, 0);
  // The listed Gaussians' bits, one set per worker (no atomics), or-ed together at the end.
  const int slots = resolve_threads(threads);
  std::vector<std::vector<uint64_t>> worker_bits(unwanted_listed ? size_t(slots) : 0);
  std::vector<std::vector<uint32_t>> worker_seen(static_cast<size_t>(slots));
  parallel_for(n, slots, [&](int w, size_t t) {
    if (!tiles[t]) return;
    const uint32_t begin = d.tile_start[t], end = d.tile_start[t + 1];
    // A local while in use (the workers' vectors share cache lines), kept for its capacity.
    std::vector<uint32_t> seen = std::move(worker_seen[size_t(w)]);
    seen.clear();
    bool found = false;
    for (uint32_t e = begin; e < end; ++e) {
      if (e + kPrefetchAhead < end) __builtin_prefetch(&d.splats[d.tile_list[e + kPrefetchAhead]]);  // read at random
      const uint32_t g = d.splats[d.tile_list[e]].index;
      if (wanted[g]) {
        found = true;
        break;
      }
      if (unwanted_listed) seen.push_back(g);
    }
    if (found) {
      out[t] = 1;
    } else if (unwanted_listed) {
      std::vector<uint64_t>& bits = worker_bits[size_t(w)];
      if (bits.empty()) bits.assign(unwanted_listed->size(), 0);
      for (uint32_t g : seen) bits[g >> 6] |= uint64_t(1) << (g & 63);
    }
    worker_seen[size_t(w)] = std::move(seen);
  });
  for (const std::vector<uint64_t>& bits : worker_bits)
    if (!bits.empty())
      for (size_t i = 0; i < bits.size(); ++i) (*unwanted_listed)[i] |= bits[i];
  return out;
}

namespace {
// The tiles a splat reaches: the pixels raster_tile evaluates for it, [ceil(mx - hx),
// floor(mx + hx)] and the same in y, clipped to the image. False when none is inside.
bool tile_box_of(const Splat& s, int W, int H, TileBox& box) {
  const float hx = decode_half_width(s.hx), hy = decode_half_width(s.hy);
  const float x0 = std::max(std::ceil(s.mx - hx), 0.f), x1 = std::min(std::floor(s.mx + hx), float(W - 1));
  const float y0 = std::max(std::ceil(s.my - hy), 0.f), y1 = std::min(std::floor(s.my + hy), float(H - 1));
  if (x0 > x1 || y0 > y1) return false;
  box = {int(x0) / kTileSize, int(y0) / kTileSize, int(x1) / kTileSize, int(y1) / kTileSize};
  return true;
}
}  // namespace

std::vector<uint8_t> tiles_reached(const PreparedFrame& frame, const std::vector<bool>& flagged, int threads) {
  const PreparedFrame::Data& d = PreparedFrameAccess::data(frame);
  if (flagged.size() != frame.gaussians) throw Error("tiles_reached: the Gaussian flags do not match the scene");
  const size_t gx = size_t(frame.grid_x), n = d.splats.size();
  const int W = frame.camera.width, H = frame.camera.height;
  // Each worker flags its own copy (no atomics), or-ed together at the end.
  const size_t grain = list_grain(n);
  std::vector<std::vector<uint8_t>> flags(chunk_count(n, grain));
  parallel_chunks(n, grain, threads, [&](size_t chunk, size_t begin, size_t end) {
    std::vector<uint8_t> f(gx * size_t(frame.grid_y), 0);  // a local, moved in at the end
    TileBox box;
    for (size_t k = begin; k < end; ++k) {
      const Splat& s = d.splats[k];
      if (!flagged[s.index] || !tile_box_of(s, W, H, box)) continue;
      for (int ty = box.y0; ty <= box.y1; ++ty)
        for (int tx = box.x0; tx <= box.x1; ++tx) f[size_t(ty) * gx + size_t(tx)] = 1;
    }
    flags[chunk] = std::move(f);
  });
  std::vector<uint8_t> out(gx * size_t(frame.grid_y), 0);
  for (const std::vector<uint8_t>& f : flags)
    for (size_t t = 0; t < f.size(); ++t) out[t] |= f[t];
  return out;
}

}  // namespace isegman
