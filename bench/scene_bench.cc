// The scene fingerprint against the legacy one (FNV-1a over the bytes) at 1M and 6M
// Gaussians of SH degree 3: the server hashes the scene when a click's selection is
// recorded and on every edit.
//   build/bench/scene_bench --benchmark_filter=Fingerprint
// Building the neighbour index of the centres (view choice's lines of sight, coherence,
// grow/shrink) on one thread and on every core: the same tree either way.
//   build/bench/scene_bench --benchmark_filter=CentreIndex
#include <benchmark/benchmark.h>

#include <cstdint>

#include "core/centre_index.h"
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
