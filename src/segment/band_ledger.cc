#include "segment/band_ledger.h"

#include <algorithm>

#include "core/error.h"
#include "core/parallel.h"
#include "render/visibility.h"

namespace isegman::segment {

namespace {

size_t tile_of(int x, int y, int grid_x) { return size_t(y / kTileSize) * size_t(grid_x) + size_t(x / kTileSize); }

size_t flagged(const std::vector<uint8_t>& flags) {
  size_t n = 0;
  for (uint8_t f : flags) n += f != 0;
  return n;
}

}  // namespace

Image BandLedger::band_in(const Waiting& w, const std::vector<uint8_t>& tiles, int grid_x) {
  // Only the flagged tiles' pixels are read: a vote often releases a few tiles of a view.
  Image out(w.width, w.height, 1);
  for (size_t t = 0; t < tiles.size(); ++t) {
    if (!tiles[t]) continue;
    const int x0 = int(t % size_t(grid_x)) * kTileSize, y0 = int(t / size_t(grid_x)) * kTileSize;
    const int x1 = std::min(w.width, x0 + kTileSize), y1 = std::min(w.height, y0 + kTileSize);
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const size_t p = size_t(y) * w.width + x;
        if (w.band[p]) out.data[p] = 1.f;
      }
  }
  return out;
}

ViewVotes BandLedger::outside(const ViewVotes& votes, const std::vector<bool>& shown) {
  ViewVotes out;
  for (size_t i = 0; i < votes.index.size(); ++i)
    if (!shown[votes.index[i]]) {
      out.index.push_back(votes.index[i]);
      out.weight.push_back(votes.weight[i]);
    }
  return out;
}

ViewVotes BandLedger::add_view(size_t view, const PreparedFrame& frame, const Image& band,
                               const std::vector<uint32_t>& shown, int threads) {
  if (band.width != frame.camera.width || band.height != frame.camera.height || band.channels != 1)
    throw Error("BandLedger: the band does not match the view's resolution");
  if (frame.gaussians != supported_.size()) throw Error("BandLedger: the view's frame is of another scene");
  const int gx = frame.grid_x;
  Waiting w;
  w.view = view;
  w.width = band.width;
  w.height = band.height;
  w.band.assign(size_t(band.width) * band.height, 0);
  w.tiles.assign(size_t(gx) * frame.grid_y, 0);
  for (int y = 0; y < band.height; ++y)
    for (int x = 0; x < band.width; ++x) {
      const size_t p = size_t(y) * band.width + x;
      if (band.data[p] > 0.5f) {
        w.band[p] = 1;
        w.tiles[tile_of(x, y, gx)] = 1;
      }
    }
  w.shown.assign(supported_.size(), false);
  for (uint32_t j : shown) w.shown[j] = true;
  // Now: the tiles that list a Gaussian with a positive vote, outside this view's mask (every
  // tile of a frame not compacted: only the voting views' frames are worth the wait).
  std::vector<uint8_t> now = w.tiles;
  if (is_compact(frame)) {
    std::vector<bool> wanted = supported_;
    for (uint32_t j : shown) wanted[j] = false;
    w.listed.assign((supported_.size() + 63) / 64, 0);
    now = tiles_listing(frame, w.tiles, wanted, threads, &w.listed);
  }
  ViewVotes votes;
  if (const size_t n = flagged(now)) {
    blended_ += n;
    votes = outside(masked_votes(frame, band_in(w, now, gx), threads), w.shown);
    for (size_t t = 0; t < now.size(); ++t)
      if (now[t]) w.tiles[t] = 0;
  }
  if (flagged(w.tiles) > 0) waiting_.push_back(std::move(w));
  return votes;
}

std::vector<ViewVotes> BandLedger::add_positive(const std::vector<uint32_t>& positive,
                                                const std::function<const PreparedFrame&(size_t)>& frame_of,
                                                int threads) {
  std::vector<uint32_t> fresh;
  for (uint32_t j : positive)
    if (!supported_[j]) {
      supported_[j] = true;
      fresh.push_back(j);
    }
  std::vector<ViewVotes> out;
  if (fresh.empty() || waiting_.empty()) return out;
  // Each waiting view on a worker: the waiting tiles the fresh Gaussians' splats reach.
  std::vector<std::vector<uint8_t>> now(waiting_.size());
  parallel_for(waiting_.size(), threads, [&](int, size_t i) {
    Waiting& w = waiting_[i];
    const PreparedFrame& frame = frame_of(w.view);
    const size_t gx = size_t(frame.grid_x);
    // Only a Gaussian a waiting tile lists can release one: the others are not projected
    // (most of a vote's Gaussians lie under its own mask).
    std::vector<uint32_t> listed;
    for (uint32_t j : fresh)
      if (!w.shown[j] && !w.listed.empty() && ((w.listed[j >> 6] >> (j & 63)) & 1)) listed.push_back(j);
    for (const TileBox& box : binned_tiles(*scene_, frame, listed))
      for (int ty = box.y0; ty <= box.y1; ++ty)
        for (int tx = box.x0; tx <= box.x1; ++tx) {
          const size_t t = size_t(ty) * gx + size_t(tx);
          if (!w.tiles[t]) continue;
          if (now[i].empty()) now[i].assign(w.tiles.size(), 0);
          now[i][t] = 1;
          w.tiles[t] = 0;
        }
  });
  for (size_t i = 0; i < waiting_.size(); ++i) {
    if (now[i].empty()) continue;
    const Waiting& w = waiting_[i];
    const PreparedFrame& frame = frame_of(w.view);
    blended_ += flagged(now[i]);
    out.push_back(outside(masked_votes(frame, band_in(w, now[i], frame.grid_x), threads), w.shown));
  }
  return out;
}

size_t BandLedger::waiting_tiles() const {
  size_t n = 0;
  for (const Waiting& w : waiting_) n += flagged(w.tiles);
  return n;
}

}  // namespace isegman::segment
