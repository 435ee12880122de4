// Software prefetch for passes over a list of Gaussian indices (a view's votes, ascending).
// A trained scene keeps its Gaussians in no spatial order (densification appends its clones
// at the end), so the ~10^5-10^6 Gaussians a mask shows lie scattered over the scene's
// arrays, and a pass that reads their centres or sums waits on memory at every entry: the
// hardware prefetchers do not follow an index list. Issuing the load kPrefetchAhead entries
// early hides that wait: a pass over 400k of 6M scattered centres 6.7-7.4 -> 3.8-4.1 ms; over
// an index range, as the synthetic scenes' objects lie, it costs 0.61-0.65 -> 1.0 ms (Zen 5,
// `build/bench/scene_bench --benchmark_filter=CentresThroughList`). A prefetch never faults
// and changes no result. (`segment` puts a loaded scene in space order, core/spatial_order.h,
// where these lists read nearly in order; `serve` keeps the file's order.)
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/scene.h"

namespace isegman {

// (The tile kernel walks its tile lists with its own distance, kTileListPrefetchAhead.)
constexpr size_t kPrefetchAhead = 16;

// Before reading entry k of `index`: the centre of the Gaussian kPrefetchAhead entries on
// (its 12 bytes may straddle two cache lines).
inline void prefetch_centre_ahead(const GaussianScene& scene, const std::vector<uint32_t>& index, size_t k) {
  if (k + kPrefetchAhead >= index.size()) return;
  const float* p = scene.positions.data() + 3 * size_t(index[k + kPrefetchAhead]);
  __builtin_prefetch(p);
  __builtin_prefetch(p + 2);
}

// Before updating into[index[k]]: the element kPrefetchAhead entries on, for writing.
template <class T>
inline void prefetch_element_ahead(T* into, const std::vector<uint32_t>& index, size_t k) {
  if (k + kPrefetchAhead < index.size()) __builtin_prefetch(into + index[k + kPrefetchAhead], 1);
}

}  // namespace isegman
