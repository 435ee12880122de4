#include "segment/votes.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"
#include "core/prefetch.h"
#include "segment/depth_layers.h"

namespace isegman::segment {
namespace {

RenderSettings vote_settings(int threads) {
  RenderSettings s;
  s.color = false;
  s.depth = false;
  s.threads = threads;
  return s;
}

}  // namespace

std::vector<uint8_t> tiles_under_mask(const Image& mask, int grid_x, int grid_y) {
  std::vector<uint8_t> tiles(size_t(grid_x) * grid_y, 0);
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x)
      if (mask.at(x, y) > 0.5f) tiles[size_t(y / kTileSize) * grid_x + x / kTileSize] = 1;
  return tiles;
}

ViewVotes total_votes(const PreparedFrame& frame, int threads) {
  return weight_sums(frame, nullptr, vote_settings(threads));
}

ViewVotes masked_votes(const PreparedFrame& frame, const Image& mask, int threads, const std::vector<float>* values,
                       Image* coverage) {
  if (mask.width != frame.camera.width || mask.height != frame.camera.height || mask.channels != 1)
    throw Error("masked_votes: mask does not match the view's resolution");
  return weight_sums(frame, &mask, vote_settings(threads), values, coverage, ValueExtent::kMaskPixels);
}

namespace {
// into[index[k]] += sign * weight[k]. A view's list names each Gaussian once, so chunks of
// it write disjoint sums, and integer sums do not depend on the order.
void scatter_add(ZeroedArray<int64_t>& into, const ViewVotes& v, int64_t sign, int threads) {
  const size_t n = v.index.size();
  const size_t grain = list_grain(n);
  parallel_chunks(n, grain, threads, [&](size_t, size_t a, size_t e) {
    for (size_t k = a; k < e; ++k) {
      prefetch_element_ahead(into.data(), v.index, k);
      into[v.index[k]] += sign * v.weight[k];
    }
  });
}
}  // namespace

void VoteAccumulator::add(const ViewVotes& positive, const ViewVotes& total, int sign, const ViewVotes* neutral,
                          const ViewVotes* centred, const ViewVotes* whole, int threads) {
  scatter_add(positive_, positive, sign, threads);
  if (centred) scatter_add(centred_, *centred, sign, threads);
  scatter_add(total_, total, sign, threads);
  if (neutral) scatter_add(total_, *neutral, -sign, threads);
  if (whole) scatter_add(whole_, *whole, sign, threads);
}

std::vector<bool> VoteAccumulator::select(double tau, double min_total, const CentreRule& centre,
                                          const WholeRule& whole) const {
  std::vector<bool> sel(total_.size(), false);
  const int64_t fixed = min_fixed(min_total);
  for (size_t j = 0; j < total_.size(); ++j) sel[j] = selects(j, tau, fixed, centre, whole);
  return sel;
}

namespace {
bool mask_near(const Image& mask, int x, int y, int margin) {
  for (int yy = std::max(0, y - margin); yy <= std::min(mask.height - 1, y + margin); ++yy)
    for (int xx = std::max(0, x - margin); xx <= std::min(mask.width - 1, x + margin); ++xx)
      if (mask.at(xx, yy) > 0.5f) return true;
  return false;
}
}  // namespace

ViewVotes centred_votes(const GaussianScene& scene, const Camera& camera, const Image& mask, const Image& depth,
                        const ViewVotes& positive, const ViewVotes& total, int margin, int threads) {
  // No depth image (a view built without one): centres are not tested for being hidden.
  const bool have_depth = !depth.data.empty();
  if (have_depth && (depth.width != mask.width || depth.height != mask.height))
    throw Error("centred_votes: depth and mask sizes differ");
  // Chunks of `positive` in parallel, each into its own list; concatenated in order, the
  // lists are what one pass would give.
  const size_t n = positive.index.size();
  const size_t grain = std::max(list_grain(n), (n + 3) / 4);
  std::vector<ViewVotes> parts(chunk_count(n, grain));
  auto run = [&](size_t chunk, size_t begin, size_t end) {
    ViewVotes out;  // moved in at the end: the chunks' lists share cache lines
    size_t t = size_t(std::lower_bound(total.index.begin(), total.index.end(), positive.index[begin]) - total.index.begin());
    // In blocks: the block's centres are projected first and the depth and mask values at
    // their pixels prefetched, then each centre is judged. A scattered list's centres fall
    // anywhere in the view, and those reads would each wait on memory.
    constexpr size_t kBlock = 32;
    struct Centre {
      double z;
      int x, y;
    };
    Centre block[kBlock];
    for (size_t b0 = begin; b0 < end; b0 += kBlock) {
      const size_t b1 = std::min(end, b0 + kBlock);
      for (size_t k = b0; k < b1; ++k) {
        prefetch_centre_ahead(scene, positive.index, k);
        double u = 0, v = 0, z = 0;
        const bool projects = camera.project(scene.position(positive.index[k]), u, v, &z);  // false: behind the camera
        Centre& c = block[k - b0];
        c = {z, projects ? int(std::floor(u)) : -1, projects ? int(std::floor(v)) : -1};
        if (c.x >= 0 && c.y >= 0 && c.x < mask.width && c.y < mask.height) {
          __builtin_prefetch(&mask.data[size_t(c.y) * size_t(mask.width) + size_t(c.x)]);
          if (have_depth) __builtin_prefetch(&depth.data[size_t(c.y) * size_t(depth.width) + size_t(c.x)]);
        }
      }
      for (size_t k = b0; k < b1; ++k) {
        const uint32_t g = positive.index[k];
        while (t < total.index.size() && total.index[t] < g) ++t;
        if (t == total.index.size() || total.index[t] != g) continue;
        const Centre& c = block[k - b0];
        const int x = c.x, y = c.y;
        const double z = c.z;
        const bool in_frame = x >= 0 && y >= 0 && x < mask.width && y < mask.height;
        const double surface = in_frame && have_depth ? double(depth.at(x, y)) : 0.0;
        // The extent (a covariance per Gaussian) only where the centre lies beyond the 5 %
        // margin: one within it is never hidden, whatever the extent (it is >= 0).
        const bool hidden = surface > 0 && z > surface * 1.05 &&
                            z > surface * 1.05 + 2.0 * depth_extent(scene, camera, g);
        bool counts;
        if (in_frame && mask.at(x, y) > 0.5f) {
          counts = !hidden;
        } else if (!in_frame || (hidden && !mask_near(mask, x, y, margin))) {
          counts = 2 * positive.weight[k] > total.weight[t];
        } else {
          counts = false;  // a visible centre outside the mask, or one hidden at the mask's edge
        }
        if (!counts) continue;
        out.index.push_back(g);
        out.weight.push_back(total.weight[t]);
      }
    }
    parts[chunk] = std::move(out);
  };
  parallel_chunks(n, grain, threads, run);
  return join_in_order(std::move(parts));
}

int64_t flagged_weight(const ViewVotes& votes, const std::vector<bool>& flags, int threads) {
  const size_t n = votes.index.size(), grain = list_grain(n);
  std::vector<int64_t> sums(chunk_count(n, grain), 0);
  parallel_chunks(n, grain, threads, [&](size_t chunk, size_t begin, size_t end) {
    int64_t sum = 0;
    for (size_t i = begin; i < end; ++i)
      if (flags[votes.index[i]]) sum += votes.weight[i];
    sums[chunk] = sum;
  });
  int64_t total = 0;
  for (int64_t s : sums) total += s;
  return total;
}

std::vector<float> VoteAccumulator::ratios() const {
  std::vector<float> r(total_.size(), 0.f);
  for (size_t j = 0; j < total_.size(); ++j)
    if (total_[j] > 0) r[j] = float(double(positive_[j]) / double(total_[j]));
  return r;
}

}  // namespace isegman::segment
