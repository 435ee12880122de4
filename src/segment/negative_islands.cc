#include "segment/negative_islands.h"

#include <algorithm>
#include <cmath>

namespace isegman::segment {

namespace {

// Every selected Gaussian's weight at one pixel.
class PixelWeights : public ContributionVisitor {
 public:
  PixelWeights(const std::vector<bool>& selection, int x, int y) : selection_(selection), x_(x), y_(y) {}
  void visit(int, int x, int y, uint32_t g, float w) override {
    if (x == x_ && y == y_ && selection_[g]) found.emplace_back(g, w);  // one worker holds the pixel's tile
  }
  std::vector<std::pair<uint32_t, float>> found;

 private:
  const std::vector<bool>& selection_;
  int x_, y_;
};

}  // namespace

std::vector<uint32_t> selected_at_pixel(const PreparedFrame& frame, const std::vector<bool>& selection, int x, int y,
                                        int threads) {
  if (x < 0 || y < 0 || x >= frame.camera.width || y >= frame.camera.height) return {};
  std::vector<uint8_t> tiles(size_t(frame.grid_x) * frame.grid_y, 0);
  tiles[size_t(y / kTileSize) * frame.grid_x + x / kTileSize] = 1;
  PixelWeights visitor(selection, x, y);
  RenderSettings s;
  s.color = false;
  s.depth = false;
  s.threads = threads;
  rasterize(frame, s, nullptr, &visitor, &tiles);
  float largest = 0;
  for (const auto& [g, w] : visitor.found) largest = std::max(largest, w);
  std::vector<uint32_t> out;
  for (const auto& [g, w] : visitor.found)
    if (w >= 0.5f * largest && w > 0) out.push_back(g);
  std::sort(out.begin(), out.end());
  return out;
}

NegativeCut cut_negative_islands(std::vector<bool>& selection, const GaussianScene& scene, const CentreIndex& index,
                                 const std::vector<uint32_t>& positive_seeds,
                                 const std::vector<std::vector<uint32_t>>& negative_seeds, const IslandOptions& link) {
  NegativeCut out;
  if (negative_seeds.empty()) return out;
  // An island's Gaussians leave the selection only after its flood ends, so the touch rule
  // sees the selection as it was for the whole flood.
  const TouchingGaussians touching(scene, index, selection, link.link_sigmas);
  std::vector<uint8_t> positive(selection.size(), 0);
  for (uint32_t g : positive_seeds) positive[g] = 1;
  std::vector<uint8_t> seen(selection.size(), 0);
  for (const std::vector<uint32_t>& seeds : negative_seeds) {
    // Flood the island from the click's Gaussians, over selected Gaussians only, breadth
    // first: a positive click's Gaussians joined to them are found within the distance
    // between the two, not after most of the object (a depth-first flood).
    std::vector<uint32_t> island, frontier;
    size_t head = 0;
    bool joined = false;
    std::fill(seen.begin(), seen.end(), 0);
    for (uint32_t g : seeds)
      if (selection[g] && !seen[g]) {
        seen[g] = 1;
        frontier.push_back(g);
      }
    if (frontier.empty()) continue;
    while (head < frontier.size() && !joined) {
      const uint32_t g = frontier[head++];
      island.push_back(g);
      if (positive[g]) {
        joined = true;
        break;
      }
      touching.for_each(g, [&](uint32_t j) {
        if (seen[j]) return;
        seen[j] = 1;
        frontier.push_back(j);
      });
    }
    if (joined) {
      ++out.joined;
      continue;
    }
    for (uint32_t g : island) selection[g] = false;
    out.removed += island.size();
    ++out.cut;
  }
  return out;
}

}  // namespace isegman::segment
