// The scene fingerprint against the legacy one (FNV-1a over the bytes) at 1M and 6M
// Gaussians of SH degree 3: the server hashes the scene when a click's selection is
// recorded and on every edit.
//   build/bench/scene_bench --benchmark_filter=Fingerprint
// Building the neighbour index of the centres (view choice's lines of sight, coherence,
// grow/shrink) on one thread and on every core: the same tree either way.
//   build/bench/scene_bench --benchmark_filter=CentreIndex
// A pass over a view's list of ~400k of 6M Gaussians that reads their centres (as the depth
// layers, the background gate and the centre evidence do), with the list scattered over the
// scene (a trained scene's order) or in one index range (an object of the synthetic scenes),
// with and without core/prefetch.h's prefetch ahead; caches are flushed before each pass.
//   build/bench/scene_bench --benchmark_filter=CentresThroughList
#include <benchmark/benchmark.h>

#include <cstdint>
#include <vector>

#include "core/centre_index.h"
#include "core/prefetch.h"
#include "core/scene.h"

namespace isegman {
namespace {

GaussianScene filled_scene(size_t n) {
  GaussianScene g;
  g.resize(n, 3);
  uint64_t s = 12345;
  auto fill = [&](std::vector<float>& v) {
    for (float& x : v) {
      s = s * 6364136223846793005ull + 1442695040888963407ull;
      x = float(double(s >> 40) / double(1 << 24));
    }
  };
  fill(g.positions);
  fill(g.sh);
  fill(g.opacity);
  fill(g.scales);
  fill(g.rotations);
  return g;
}

const GaussianScene& scene_of(size_t n) {
  static size_t built = 0;
  static GaussianScene g;
  if (built != n) {
    g = filled_scene(n);
    built = n;
  }
  return g;
}

void BM_Fingerprint(benchmark::State& state) {
  const GaussianScene& g = scene_of(size_t(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(g.fingerprint());
}

void BM_LegacyFingerprint(benchmark::State& state) {
  const GaussianScene& g = scene_of(size_t(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(g.legacy_fingerprint());
}

// Arguments: Gaussians, threads (0: every core).
void BM_CentreIndexBuild(benchmark::State& state) {
  const GaussianScene& g = scene_of(size_t(state.range(0)));
  for (auto _ : state) {
    CentreIndex index(g, int(state.range(1)));
    benchmark::DoNotOptimize(index);
  }
}

// Arguments: scattered (1) or one index range (0); prefetch (1) or not (0).
void BM_CentresThroughList(benchmark::State& state) {
  const GaussianScene& g = scene_of(6000000);
  const bool scattered = state.range(0) != 0, prefetch = state.range(1) != 0;
  std::vector<uint32_t> list;  // ascending, like a view's votes
  uint64_t s = 777;
  for (uint32_t i = 0; i < g.size(); ++i) {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    const uint32_t r = uint32_t(s >> 33);
    if (scattered ? r % 15 == 0 : (i >= 1000000 && i < 1533333 && r % 4 != 0)) list.push_back(i);
  }
  std::vector<double> out(list.size());
  std::vector<char> flush(size_t(256) << 20);
  for (auto _ : state) {
    state.PauseTiming();
    for (size_t i = 0; i < flush.size(); i += 64) ++flush[i];
    state.ResumeTiming();
    for (size_t k = 0; k < list.size(); ++k) {
      if (prefetch) prefetch_centre_ahead(g, list, k);
      const Vec3 c = g.position(list[k]);
      const double z = 0.3 * c.x + 0.2 * c.y + 0.9 * c.z + 3;  // a projection's arithmetic
      out[k] = (0.8 * c.x + 0.1 * c.y) / z + (0.1 * c.x + 0.7 * c.y) / z;
    }
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["entries"] = double(list.size());
}

BENCHMARK(BM_CentresThroughList)
    ->Args({1, 0})
    ->Args({1, 1})
    ->Args({0, 0})
    ->Args({0, 1})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CentreIndexBuild)
    ->Args({1000000, 1})
    ->Args({1000000, 0})
    ->Args({6000000, 1})
    ->Args({6000000, 0})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Fingerprint)->Arg(1000000)->Arg(6000000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_LegacyFingerprint)->Arg(1000000)->Arg(6000000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace isegman

// main(): bench_main.cc
