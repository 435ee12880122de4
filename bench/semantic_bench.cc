// Semantic editing benchmark: optimisation steps per second (forward, loss, backward,
// Adam; editor calls excluded) on the fern fixture at its training resolution 504x378,
// with a selection of ~10 % of the Gaussians (the compact blob nearest the scene's
// median point), 1 and 2 threads, with the built-in editor.
// SEMANTIC_BENCH_SELECTION=FILE also writes that selection as an .isel file.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <numeric>

#include "core/selection.h"
#include "edit/image_editor.h"
#include "edit/semantic_edit.h"
#include "io/scene_loader.h"

namespace isegman {
namespace {

struct Fern {
  SceneBundle bundle;
  Selection selection;
  bool ok = false;
};

const Fern& fern() {
  static Fern f = [] {
    Fern f;
    const std::filesystem::path dir = std::filesystem::path(ISEGMAN_FIXTURES_DIR) / "fern" / "scene";
    if (!std::filesystem::exists(dir)) return f;
    f.bundle = load_scene(dir.string());
    const GaussianScene& g = f.bundle.gaussians;
    const size_t n = g.size();
    Vec3 median;
    for (int a = 0; a < 3; ++a) {
      std::vector<float> v(n);
      for (size_t i = 0; i < n; ++i) v[i] = g.positions[3 * i + a];
      std::nth_element(v.begin(), v.begin() + n / 2, v.end());
      median[a] = v[n / 2];
    }
    std::vector<uint32_t> idx(n);
    std::iota(idx.begin(), idx.end(), 0u);
    auto d2 = [&](uint32_t i) { const Vec3 d = g.position(i) - median; return dot(d, d); };
    std::nth_element(idx.begin(), idx.begin() + n / 10, idx.end(), [&](uint32_t a, uint32_t b) { return d2(a) < d2(b); });
    std::vector<bool> mask(n, false);
    for (size_t k = 0; k < n / 10; ++k) mask[idx[k]] = true;
    f.selection = Selection::from_mask(g, mask);
    if (const char* out = std::getenv("SEMANTIC_BENCH_SELECTION")) write_selection(out, f.selection);
    f.ok = true;
    return f;
  }();
  return f;
}

void BM_SemanticEditFern(benchmark::State& state) {
  const Fern& f = fern();
  if (!f.ok) {
    state.SkipWithError("fern fixture not found in ../shared/fixtures");
    return;
  }
  auto editor = edit::make_builtin_editor("builtin:recolor");
  edit::SemanticEditOptions o;
  o.instruction = "turn the leaves into gold";
  o.steps = 40;
  o.refresh_every = 10;
  o.threads = int(state.range(0));
  o.background[0] = 0.6130f;
  o.background[1] = 0.0101f;
  o.background[2] = 0.3984f;
  int steps = 0;
  size_t views = 0;
  for (auto _ : state) {
    const edit::SemanticEditResult r = edit::semantic_edit(f.bundle.gaussians, f.bundle.cameras, f.selection, *editor, o);
    state.SetIterationTime(r.seconds_optimising);
    steps += r.steps_done;
    views = r.views.size();
  }
  state.counters["steps_per_s"] = benchmark::Counter(double(steps), benchmark::Counter::kIsRate);
  state.counters["selected"] = double(f.selection.count());
  state.counters["views"] = double(views);
}
BENCHMARK(BM_SemanticEditFern)->Arg(1)->Arg(2)->UseManualTime()->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
}  // namespace isegman

// main(): bench_main.cc
