#include "segment/link_grid.h"

#include <algorithm>

#include "segment/whole_islands.h"

namespace isegman::segment {

LinkGrid::LinkGrid(const GaussianScene& scene, const std::vector<uint32_t>& members, double link_sigmas)
    : scene_(scene), link_(link_sigmas) {
  if (members.empty()) return;
  std::vector<float> scales;
  scales.reserve(members.size());
  for (uint32_t g : members) scales.push_back(scene.largest_scale(g));
  {
    std::vector<float> reordered = scales;  // touch_reach reorders what it is given
    reach_ = touch_reach(reordered);
  }
  span_cell_ = std::max(2 * link_ * reach_, 1e-9);
  // Coarser cells where the box would hold more of them than a few per member (members
  // scattered far apart): the cell size changes what a search reads, never what it finds.
  cell_ = span_cell_;
  Vec3 lo = scene.position(members[0]), hi = lo;
  for (uint32_t g : members) {
    const Vec3 p = scene.position(g);
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  auto extent = [&](double a, double b) { return std::floor(b / cell_) - std::floor(a / cell_) + 1; };
  while (extent(lo.x, hi.x) * extent(lo.y, hi.y) * extent(lo.z, hi.z) > 4.0 * double(members.size()) + 1024)
    cell_ *= 2;
  x0_ = cell_of(lo.x), y0_ = cell_of(lo.y), z0_ = cell_of(lo.z);
  nx_ = cell_of(hi.x) - x0_ + 1, ny_ = cell_of(hi.y) - y0_ + 1, nz_ = cell_of(hi.z) - z0_ + 1;
  start_.assign(size_t(nx_ * ny_ * nz_) + 1, 0);
  std::vector<uint32_t> cell_at(members.size());
  for (size_t i = 0; i < members.size(); ++i) {
    const Vec3 p = scene.position(members[i]);
    cell_at[i] = uint32_t(((cell_of(p.z) - z0_) * ny_ + (cell_of(p.y) - y0_)) * nx_ + (cell_of(p.x) - x0_));
    ++start_[cell_at[i] + 1];
  }
  for (size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
  sorted_.resize(members.size());
  std::vector<uint32_t> next(start_.begin(), start_.end() - 1);
  for (size_t i = 0; i < members.size(); ++i) {
    const uint32_t g = members[i];
    sorted_[next[cell_at[i]]++] = {scene.positions[3 * size_t(g)], scene.positions[3 * size_t(g) + 1],
                                   scene.positions[3 * size_t(g) + 2], scales[i], g};
  }
  // In order of x along each row (a cell's members stay together: x orders the cells too).
  for (size_t row = 0; row + 1 < start_.size(); row += size_t(nx_))
    std::sort(sorted_.begin() + start_[row], sorted_.begin() + start_[row + size_t(nx_)],
              [](const Member& a, const Member& b) { return a.x < b.x; });
}

}  // namespace isegman::segment
