// The touch rule of whole_islands.h among a chosen set of Gaussians, for floods that search the
// neighbours of each Gaussian they reach (apart_islands.h).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/scene.h"

namespace isegman::segment {

// The touch rule of TouchingGaussians among `members` alone: a flood's neighbour search reads
// the members near it, not every centre of the scene there (the wall behind the object), which
// took 15-20 us a search. The members are counted into a dense grid of cells two link reaches
// wide over their bounding box, each row of cells along x in order of x, with each centre and
// largest scale kept beside it: a search reads one contiguous run a row its reach crosses,
// from the first centre within reach in x to the last. (A hash lookup a cell, and a centre and
// an exp gathered from the scene per candidate, took 2.4 us a search at 6M Gaussians.)
class LinkGrid {
 public:
  // `members`: ids of `scene`'s Gaussians; two touch when their centres lie within
  // link_sigmas x (the largest scale of one + that of the other).
  LinkGrid(const GaussianScene& scene, const std::vector<uint32_t>& members, double link_sigmas);
  // f(j) for every member j != g that touches g (g need not be a member). False, calling
  // nothing, when g reaches over more than max_cells cells two link reaches wide (a Gaussian
  // far broader than the members: its search would read a large part of them).
  template <class F>
  bool for_each(uint32_t g, F&& f, int64_t max_cells = INT64_MAX) const {
    if (sorted_.empty()) return true;
    const double sg = scene_.largest_scale(g), r = link_ * (sg + reach_);
    const Vec3 p = scene_.position(g);
    const int64_t span = int64_t(std::floor((p.x + r) / span_cell_)) - int64_t(std::floor((p.x - r) / span_cell_)) + 1;
    if (span > max_cells || span * span > max_cells / span) return false;
    const int64_t xa = std::max<int64_t>(cell_of(p.x - r) - x0_, 0), xb = std::min(cell_of(p.x + r) - x0_, nx_ - 1);
    const int64_t ya = std::max<int64_t>(cell_of(p.y - r) - y0_, 0), yb = std::min(cell_of(p.y + r) - y0_, ny_ - 1);
    const int64_t za = std::max<int64_t>(cell_of(p.z - r) - z0_, 0), zb = std::min(cell_of(p.z + r) - z0_, nz_ - 1);
    if (xa > xb) return true;
    // Past r in x by a margin: the distance test below decides, as for every other candidate.
    const float x_lo = float(p.x - r * (1 + 1e-5)), x_hi = float(p.x + r * (1 + 1e-5));
    const double r2 = r * r;
    // The touching candidates of a row are gathered without a branch on the test (which goes
    // either way unpredictably), then handed to f.
    uint32_t found[kFoundBatch];
    for (int64_t z = za; z <= zb; ++z)
      for (int64_t y = ya; y <= yb; ++y) {
        const size_t row = size_t((z * ny_ + y) * nx_);
        uint32_t i = start_[row + size_t(xa)];
        const uint32_t end = start_[row + size_t(xb) + 1];
        while (i < end && sorted_[i].x < x_lo) ++i;
        uint32_t last = i;
        while (last < end && sorted_[last].x <= x_hi) ++last;
        while (i < last) {
          const uint32_t batch_end = std::min(last, i + kFoundBatch);
          size_t count = 0;
          for (; i < batch_end; ++i) {
            const Member& m = sorted_[i];
            const double dx = double(m.x) - p.x, dy = double(m.y) - p.y, dz = double(m.z) - p.z;
            const double d2 = dx * dx + dy * dy + dz * dz;
            const double l = link_ * (sg + double(m.scale));
            found[count] = m.g;
            count += size_t((d2 <= r2) & (d2 <= l * l) & (m.g != g));
          }
          for (size_t k = 0; k < count; ++k) f(found[k]);
        }
      }
    return true;
  }

 private:
  static constexpr uint32_t kFoundBatch = 64;
  int64_t cell_of(double v) const { return int64_t(std::floor(v / cell_)); }
  struct Member {
    float x, y, z, scale;
    uint32_t g;
  };
  const GaussianScene& scene_;
  double link_, reach_ = 0, span_cell_ = 1, cell_ = 1;
  int64_t x0_ = 0, y0_ = 0, z0_ = 0, nx_ = 0, ny_ = 0, nz_ = 0;
  std::vector<uint32_t> start_;  // the members of cell c: sorted_[start_[c], start_[c + 1])
  std::vector<Member> sorted_;
};

}  // namespace isegman::segment
