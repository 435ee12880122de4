// Rasteriser benchmarks: frame time and nanoseconds per evaluated (pixel, Gaussian) pair
// for synthetic scenes of 100k and 1M Gaussians at 1008x567 with 1 and 2 threads, and
// the fern fixture at its training resolution when ../shared/fixtures is present.
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <map>

#include "core/sh.h"
#include "io/scene_loader.h"
#include "render/rasterizer.h"

namespace isegman {
namespace {

// A trained-scene-like cloud: Gaussians on a set of random surfaces filling a 6 x 4 x 4
// box in front of the camera, anisotropic, scales shrinking with density as a trainer's
// densification does, SH degree 3.
GaussianScene synthetic_scene(size_t n) {
  GaussianScene g;
  g.resize(n, 3);
  uint64_t s = 12345;
  auto rnd = [&] {
    s = s * 6364136223846793005ull + 1442695040888963407ull;
    return double(s >> 11) / 9007199254740992.0;
  };
  const double base = 0.02 * std::cbrt(1e6 / double(n));
  for (size_t i = 0; i < n; ++i) {
    // Surfaces: planes at random depths, so depth complexity resembles a real scene.
    const int plane = int(rnd() * 24);
    const double z = 2.0 + plane * 0.25 + 0.03 * (rnd() - 0.5);
    g.positions[3 * i] = float((rnd() - 0.5) * 6);
    g.positions[3 * i + 1] = float((rnd() - 0.5) * 3.6);
    g.positions[3 * i + 2] = float(z);
    const double sc = base * std::exp(0.6 * (rnd() - 0.5) * 2);
    g.scales[3 * i] = float(std::log(sc * (0.5 + rnd())));
    g.scales[3 * i + 1] = float(std::log(sc * (0.5 + rnd())));
    g.scales[3 * i + 2] = float(std::log(sc * 0.2));
    for (int k = 0; k < 4; ++k) g.rotations[4 * i + k] = float(rnd() * 2 - 1);
    g.opacity[i] = float((rnd() - 0.3) * 6);
    float* sh = g.sh_of(i);
    for (int c = 0; c < 3; ++c) sh[c] = rgb_to_sh_dc(float(rnd()));
    for (int k = 3; k < 48; ++k) sh[k] = float((rnd() - 0.5) * 0.2);
  }
  return g;
}

const GaussianScene& cached_scene(size_t n) {
  static std::map<size_t, GaussianScene> cache;
  auto it = cache.find(n);
  if (it == cache.end()) it = cache.emplace(n, synthetic_scene(n)).first;
  return it->second;
}

void BM_RenderSynthetic(benchmark::State& state) {
  const size_t n = size_t(state.range(0));
  const GaussianScene& g = cached_scene(n);
  Camera cam;
  cam.width = 1008;
  cam.height = 567;
  cam.fx = cam.fy = 800;
  cam.cx = 504;
  cam.cy = 283.5;
  RenderSettings rs;
  rs.threads = int(state.range(1));
  RenderStats last;
  for (auto _ : state) {
    RenderOutput r = render(g, cam, rs);
    benchmark::DoNotOptimize(r.color.data.data());
    last = r.stats;
  }
  state.counters["visible"] = double(last.visible);
  state.counters["tile_pairs"] = double(last.tile_pairs);
  state.counters["evaluated"] = double(last.evaluated);
  state.counters["ns_per_pair"] =
      benchmark::Counter(double(last.evaluated) * double(state.iterations()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["preprocess_ms"] = last.ms_preprocess;
  state.counters["sort_ms"] = last.ms_sort;
  state.counters["raster_ms"] = last.ms_raster;
}
BENCHMARK(BM_RenderSynthetic)
    ->ArgsProduct({{100000, 1000000}, {1, 2}})
    ->ArgNames({"gaussians", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_RenderFern(benchmark::State& state) {
  const std::filesystem::path scene = std::filesystem::path(ISEGMAN_FIXTURES_DIR) / "fern/scene";
  if (!std::filesystem::exists(scene)) {
    state.SkipWithError("fixtures not found; skipping fern");
    return;
  }
  static SceneBundle b = load_scene(scene.string());
  RenderSettings rs;
  rs.threads = int(state.range(0));
  RenderStats last;
  for (auto _ : state) {
    RenderOutput r = render(b.gaussians, b.cameras[0], rs);
    benchmark::DoNotOptimize(r.color.data.data());
    last = r.stats;
  }
  state.counters["evaluated"] = double(last.evaluated);
  state.counters["ns_per_pair"] = benchmark::Counter(double(last.evaluated) * double(state.iterations()),
                                                     benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_RenderFern)->Arg(1)->Arg(2)->ArgName("threads")->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace isegman

// main(): bench_main.cc
