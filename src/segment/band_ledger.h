// The part/whole band's votes (SessionOptions::whole_neutral), blended only where they can
// matter. The band (a view's larger SAM candidates around its mask) may be several times the
// mask's area, and in a dense scene most of it lies over Gaussians no mask ever shows. The
// whole rule reads a Gaussian's band weight only once the Gaussian has a positive vote
// (VoteAccumulator::selects), so a tile of the band waits while none of the Gaussians it
// lists (outside the view's own mask) has had one, and is blended when one first gets one,
// before any decision reads it. A tile's sums are the same integers whichever tiles are
// blended with it, so every decision is what one pass over the whole band gives.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/image.h"
#include "core/scene.h"
#include "render/rasterizer.h"
#include "segment/votes.h"

namespace isegman::segment {

class BandLedger {
 public:
  // `scene`: the views' scene (its Gaussians' tiles are found by projecting them); it must
  // outlive the ledger.
  explicit BandLedger(const GaussianScene& scene) : scene_(&scene), supported_(scene.size(), false) {}

  // A view's band (> 0.5 at its pixels; the view's frame and resolution) and its mask's
  // Gaussians (`shown`, ascending: the band's votes leave them out). Returns the votes of
  // the tiles that count now; the others wait. A frame not compacted waits for nothing.
  ViewVotes add_view(size_t view, const PreparedFrame& frame, const Image& band, const std::vector<uint32_t>& shown,
                     int threads);

  // A vote's positive Gaussians (ascending): for those voted positive for the first time, the
  // waiting tiles their splats are binned to (binned_tiles: every tile that lists them) are
  // blended. Returns their votes, one list per view, each to add to the whole weights.
  // `frame_of` gives a view's frame by the index add_view was given (compacted, as add_view
  // saw it).
  std::vector<ViewVotes> add_positive(const std::vector<uint32_t>& positive,
                                      const std::function<const PreparedFrame&(size_t)>& frame_of, int threads);

  // Tiles blended and tiles still waiting, over every view so far (for reports and tests).
  size_t blended_tiles() const { return blended_; }
  size_t waiting_tiles() const;

 private:
  struct Waiting {
    size_t view = 0;
    int width = 0, height = 0;
    std::vector<uint8_t> band;   // per pixel, 1 in the band (only in waiting tiles)
    std::vector<uint8_t> tiles;  // per tile, 1 while it waits
    std::vector<bool> shown;     // the view's mask's Gaussians
    // One bit per Gaussian: those its waiting tiles list (set when they started waiting).
    // Only they can release a tile, so only they are projected.
    std::vector<uint64_t> listed;
  };
  // The band's pixels in the flagged tiles, as an image for masked_votes.
  static Image band_in(const Waiting& w, const std::vector<uint8_t>& tiles, int grid_x);
  // `votes` less the Gaussians of `shown`.
  static ViewVotes outside(const ViewVotes& votes, const std::vector<bool>& shown);

  const GaussianScene* scene_;
  std::vector<bool> supported_;  // has had a positive vote
  std::vector<Waiting> waiting_;
  size_t blended_ = 0;
};

}  // namespace isegman::segment
