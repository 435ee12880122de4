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
  const size_t chunk = size_t(1) << 16;
  parallel_for((n + chunk - 1) / chunk, 0, [&](int, size_t c) {
    const size_t end = std::min(n, (c + 1) * chunk);
    for (size_t i = c * chunk; i < end; ++i) {
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
  // One array at a time through a buffer of its size, so the scene's memory grows by its
  // largest array (the SH coefficients) at most, for the moment of its gather.
  auto gather = [&](uint8_t* data, size_t row_bytes) {
    ZeroedArray<uint8_t> moved(n * row_bytes);  // huge pages: a fresh 4 KiB page faults at ~25 us here
    const size_t chunk = size_t(1) << 15;
    parallel_for((n + chunk - 1) / chunk, 0, [&](int, size_t c) {
      const size_t end = std::min(n, (c + 1) * chunk);
      for (size_t k = c * chunk; k < end; ++k) {
        if (k + kPrefetchAhead < end) __builtin_prefetch(data + size_t(order[k + kPrefetchAhead]) * row_bytes);
        std::memcpy(moved.data() + k * row_bytes, data + size_t(order[k]) * row_bytes, row_bytes);
      }
    });
    std::memcpy(data, moved.data(), n * row_bytes);
  };
  gather(reinterpret_cast<uint8_t*>(scene.positions.data()), 3 * sizeof(float));
  gather(reinterpret_cast<uint8_t*>(scene.sh.data()), size_t(scene.coeffs()) * 3 * sizeof(float));
  gather(reinterpret_cast<uint8_t*>(scene.opacity.data()), sizeof(float));
  gather(reinterpret_cast<uint8_t*>(scene.scales.data()), 3 * sizeof(float));
  gather(reinterpret_cast<uint8_t*>(scene.rotations.data()), 4 * sizeof(float));
  if (!scene.normals.empty()) gather(reinterpret_cast<uint8_t*>(scene.normals.data()), 3 * sizeof(float));
  for (auto& e : scene.extras) gather(e.data.data(), size_t(e.size));
}

SpaceOrder put_in_space_order(GaussianScene& scene) {
  SpaceOrder space{spatial_order(scene)};
  reorder(scene, space.order);
  return space;
}

}  // namespace isegman
