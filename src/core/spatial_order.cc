#include "core/spatial_order.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include "core/error.h"
#include "core/parallel.h"
#include "core/prefetch.h"
#include "core/zeroed_array.h"

namespace isegman {
namespace {

// Spreads the low 16 bits of v to every third bit (bit i to bit 3i).
uint64_t spread_bits(uint64_t v) {
  v &= 0xffff;
  v = (v | (v << 16)) & 0x0000ff0000ffULL;
  v = (v | (v << 8)) & 0x00f00f00f00fULL;
  v = (v | (v << 4)) & 0x0c30c30c30c3ULL;
  v = (v | (v << 2)) & 0x249249249249ULL;
  return v;
}

}  // namespace

std::vector<uint32_t> spatial_order(const GaussianScene& scene) {
  const size_t n = scene.size();
  if (n > std::numeric_limits<uint32_t>::max()) throw Error("spatial_order: more than 2^32 Gaussians");
  std::vector<uint32_t> order(n);
  if (n == 0) return order;
  Vec3 lo, hi;
  scene.bounds(lo, hi);
  const double lo_axis[3] = {lo.x, lo.y, lo.z}, hi_axis[3] = {hi.x, hi.y, hi.z};
  double cells_per_unit[3];
  for (int a = 0; a < 3; ++a) {
    const double extent = hi_axis[a] - lo_axis[a];
    cells_per_unit[a] = extent > 0 ? 65535.0 / extent : 0.0;
  }
  // Temporaries in huge pages: the 4 KiB pages of ~150 MB at 6M Gaussians took ~0.5 s to fault in.
  ZeroedArray<uint64_t> keys(n), keys_out(n);
  ZeroedArray<uint32_t> sorted(n), sorted_out(n);
  parallel_chunks(n, kListGrain, 0, [&](size_t, size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      uint64_t code = 0;
      for (int a = 0; a < 3; ++a) {
        const double cell = (scene.positions[3 * i + a] - lo_axis[a]) * cells_per_unit[a];
        code |= spread_bits(uint64_t(std::clamp(cell, 0.0, 65535.0))) << a;
      }
      keys[i] = code;
    }
  });
  // Least significant digit first, 12 bits a pass (4096 buckets stay in the caches): stable,
  // so ties keep index order.
  for (size_t i = 0; i < n; ++i) sorted[i] = uint32_t(i);
  constexpr int kDigitBits = 12;
  constexpr uint64_t kDigitMask = (uint64_t(1) << kDigitBits) - 1;
  std::vector<size_t> start(size_t(kDigitMask) + 2);
  for (int shift = 0; shift < 48; shift += kDigitBits) {
    std::fill(start.begin(), start.end(), 0);
    for (size_t i = 0; i < n; ++i) ++start[((keys[i] >> shift) & kDigitMask) + 1];
    for (size_t d = 1; d < start.size(); ++d) start[d] += start[d - 1];
    for (size_t i = 0; i < n; ++i) {
      const size_t to = start[(keys[i] >> shift) & kDigitMask]++;
      keys_out[to] = keys[i];
      sorted_out[to] = sorted[i];
    }
    std::swap(keys, keys_out);
    std::swap(sorted, sorted_out);
  }
  std::copy(sorted.begin(), sorted.end(), order.begin());
  return order;
}

void reorder(GaussianScene& scene, const std::vector<uint32_t>& order) {
  const size_t n = scene.size();
  if (order.size() != n) throw Error("reorder: the order does not cover the scene");
  if (n == 0) return;
  {
    std::vector<bool> seen(n, false);
    for (uint32_t from : order) {
      if (from >= n || seen[from]) throw Error("reorder: the order is not a permutation");
      seen[from] = true;
    }
  }
  // Each array moves in slices of its rows, at most a cache line wide: a slice of every row
  // is gathered into a buffer, then written back in place (the other slices are untouched).
  // The buffer holds 64 bytes a Gaussian (384 MB at 6M, 0.27x a scene with SH degree 3), so
  // the scene's memory never doubles; a row's cache lines are read in three passes instead
  // of one, about as many misses.
  std::vector<std::pair<uint8_t*, size_t>> arrays = {  // (data, bytes a row)
      {reinterpret_cast<uint8_t*>(scene.positions.data()), 3 * sizeof(float)},
      {reinterpret_cast<uint8_t*>(scene.sh.data()), size_t(scene.coeffs()) * 3 * sizeof(float)},
      {reinterpret_cast<uint8_t*>(scene.opacity.data()), sizeof(float)},
      {reinterpret_cast<uint8_t*>(scene.scales.data()), 3 * sizeof(float)},
      {reinterpret_cast<uint8_t*>(scene.rotations.data()), 4 * sizeof(float)}};
  if (!scene.normals.empty()) arrays.emplace_back(reinterpret_cast<uint8_t*>(scene.normals.data()), 3 * sizeof(float));
  for (auto& e : scene.extras) arrays.emplace_back(e.data.data(), size_t(e.size));
  constexpr size_t kSlice = 64;
  size_t widest = 0;
  for (const auto& a : arrays) widest = std::max(widest, std::min(kSlice, a.second));
  ZeroedArray<uint8_t> buffer(n * widest);  // huge pages: a fresh 4 KiB page faults at ~25 us here
  auto gather = [&](uint8_t* data, size_t row_bytes) {
    for (size_t offset = 0; offset < row_bytes; offset += kSlice) {
      const size_t width = std::min(kSlice, row_bytes - offset);
      const uint8_t* from = data + offset;
      parallel_chunks(n, kListGrain, 0, [&](size_t, size_t begin, size_t end) {
        for (size_t k = begin; k < end; ++k) {
          if (k + kPrefetchAhead < end) __builtin_prefetch(from + size_t(order[k + kPrefetchAhead]) * row_bytes);
          std::memcpy(buffer.data() + k * width, from + size_t(order[k]) * row_bytes, width);
        }
      });
      parallel_chunks(n, kListGrain, 0, [&](size_t, size_t begin, size_t end) {
        for (size_t k = begin; k < end; ++k) std::memcpy(data + k * row_bytes + offset, buffer.data() + k * width, width);
      });
    }
  };
  for (const auto& [data, row_bytes] : arrays) gather(data, row_bytes);
}

SpaceOrder put_in_space_order(GaussianScene& scene) {
  SpaceOrder space{spatial_order(scene)};
  reorder(scene, space.order);
  return space;
}

}  // namespace isegman
