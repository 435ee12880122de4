#include "edit/semantic_edit.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>

#include "core/error.h"
#include "render/rasterizer.h"
#include "render/rasterizer_backward.h"

namespace isegman::edit {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// INRIA's spatial learning-rate scale: 1.1 x the largest camera distance from their mean.
double camera_extent(const std::vector<Camera>& cams) {
  Vec3 mean;
  for (const Camera& c : cams) mean += c.center();
  mean = mean / double(cams.size());
  double r = 0;
  for (const Camera& c : cams) r = std::max(r, norm(c.center() - mean));
  return r > 0 ? 1.1 * r : 1.0;
}

RenderSettings render_settings(const SemanticEditOptions& o) {
  RenderSettings s;
  for (int c = 0; c < 3; ++c) s.background[c] = o.background[c];
  s.threads = o.threads;
  return s;
}

}  // namespace

double masked_psnr(const Image& a, const Image& b, const Image& mask, float threshold) {
  if (a.width != b.width || a.height != b.height || a.width != mask.width || a.height != mask.height)
    throw Error("masked PSNR: image sizes differ");
  double se = 0;
  size_t n = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (!(mask.at(x, y) > threshold)) continue;
      for (int c = 0; c < 3; ++c) {
        const double d = std::min(1.f, std::max(0.f, a.at(x, y, c))) - std::min(1.f, std::max(0.f, b.at(x, y, c)));
        se += d * d;
      }
      n += 3;
    }
  if (n == 0) throw Error("masked PSNR: the mask is empty");
  if (se == 0) return std::numeric_limits<double>::infinity();
  return 10 * std::log10(double(n) / se);
}

SemanticEditResult semantic_edit(const GaussianScene& input, const std::vector<Camera>& cameras,
                                 const Selection& selection, ImageEditor& editor, const SemanticEditOptions& o) {
  selection.check_matches(input, "selection");
  if (selection.empty()) throw Error("semantic edit", "the selection is empty");
  if (cameras.empty()) throw Error("semantic edit", "the scene has no cameras to render views from");
  if (o.steps < 0) throw Error("semantic edit", "--steps must be >= 0");
  if (o.instruction.empty()) throw Error("semantic edit", "the instruction is empty");
  const RenderSettings rs = render_settings(o);
  SemanticEditResult result;
  result.scene = input;
  GaussianScene& scene = result.scene;

  // Views that see the selection, optionally resized and sampled evenly.
  std::vector<bool> mask = selection.mask;
  std::vector<SemanticView> views;
  for (const Camera& c0 : cameras) {
    Camera cam = c0;
    if (o.width > 0 && o.width != c0.width)
      cam = c0.resized(o.width, std::max(1, int(std::lround(double(c0.height) * o.width / c0.width))));
    Image cov = render_selection(input, cam, mask, rs);
    int covered = 0;
    for (float v : cov.data) covered += v > 0.5f;
    if (covered < o.min_mask_pixels) continue;
    SemanticView v;
    v.camera = cam;
    v.mask = std::move(cov);
    views.push_back(std::move(v));
  }
  if (views.empty())
    throw Error("semantic edit", "no camera sees the selection (at least " + std::to_string(o.min_mask_pixels) +
                                     " covered pixels are needed)");
  if (o.max_views > 0 && int(views.size()) > o.max_views) {
    std::vector<SemanticView> sampled;
    for (int k = 0; k < o.max_views; ++k) sampled.push_back(std::move(views[size_t(k) * views.size() / o.max_views]));
    views = std::move(sampled);
  }

  // Per view: the frozen Gaussians' render (the image wherever no selected Gaussian
  // reaches: tiles the optimisation step does not rasterise).
  std::vector<bool> keep(mask.size());
  for (size_t i = 0; i < mask.size(); ++i) keep[i] = !mask[i];
  const GaussianScene frozen = input.subset(keep);
  std::vector<std::vector<float>> base(views.size());
  DiffRenderSettings ds;
  for (int c = 0; c < 3; ++c) ds.background[c] = o.background[c];
  ds.threads = o.threads;
  {
    const std::vector<int32_t> none(frozen.size(), -1);
    for (size_t v = 0; v < views.size(); ++v) {
      DiffRender<float> r;
      diff_render_forward(params_of(frozen), views[v].camera, none, ds, r);
      base[v] = std::move(r.color);
    }
  }

  // Initial targets: the editor on the input's renders.
  auto t_edit = Clock::now();
  for (SemanticView& v : views) {
    v.original = render(input, v.camera, rs).color;
    EditRequest req{&v.original, &v.mask, o.instruction, v.camera.name};
    v.target = editor.edit(req);
    ++result.editor_calls;
  }
  result.seconds_editing += seconds_since(t_edit);

  std::vector<uint32_t> selected;
  for (size_t i = 0; i < mask.size(); ++i)
    if (mask[i]) selected.push_back(uint32_t(i));
  SelectionAdam adam(scene, selected, o.rates, camera_extent(cameras));
  const std::vector<int32_t>& slot = adam.slots();
  GaussianGrads<float> grads;
  grads.resize(selected.size(), scene.sh_degree);
  ds.only_diff_tiles = true;

  std::mt19937 rng(o.seed);
  std::vector<size_t> order(views.size());
  std::iota(order.begin(), order.end(), 0);
  size_t next_refresh = 0;
  std::vector<float> dcolor;
  double loss_sum = 0;
  int loss_n = 0;
  DiffRender<float> fwd;
  auto t_opt = Clock::now();
  double editing_in_loop = 0;
  for (int step = 0; step < o.steps; ++step) {
    if (o.stop && o.stop->load()) {
      result.interrupted = true;
      break;
    }
    if (step % int(views.size()) == 0) std::shuffle(order.begin(), order.end(), rng);
    const size_t vi = order[size_t(step) % views.size()];
    SemanticView& view = views[vi];
    const int W = view.camera.width, H = view.camera.height;
    diff_render_forward(params_of(scene), view.camera, slot, ds, fwd);
    // Compose: frozen-only pixels where no selected Gaussian reached.
    PixelRect region{W, H, 0, 0};
    for (int ty = 0; ty < fwd.grid_y; ++ty)
      for (int tx = 0; tx < fwd.grid_x; ++tx) {
        const int x0 = tx * kTileSize, y0 = ty * kTileSize;
        const int x1 = std::min(W, x0 + kTileSize), y1 = std::min(H, y0 + kTileSize);
        if (fwd.tile_active[size_t(ty) * fwd.grid_x + tx]) {
          region = {std::min(region.x0, x0), std::min(region.y0, y0), std::max(region.x1, x1), std::max(region.y1, y1)};
          continue;
        }
        for (int y = y0; y < y1; ++y)
          std::copy(base[vi].begin() + (size_t(y) * W + x0) * 3, base[vi].begin() + (size_t(y) * W + x1) * 3,
                    fwd.color.begin() + (size_t(y) * W + x0) * 3);
      }
    const double lr = schedule_factor(o.schedule, step, o.steps);
    if (!region.empty()) {
      dcolor.assign(size_t(W) * H * 3, 0.f);
      const LossValue L = image_loss(fwd.color.data(), view.target.data.data(), W, H, o.loss, dcolor.data(), region);
      loss_sum += L.total;
      ++loss_n;
      grads.zero();
      diff_render_backward(params_of(scene), view.camera, slot, ds, fwd, dcolor.data(), grads);
      adam.step(scene, grads, lr);
    }
    result.steps_done = step + 1;

    // Iterative dataset update: re-edit views from the current renders.
    if (o.refresh_every > 0 && (step + 1) % o.refresh_every == 0 && step + 1 < o.steps) {
      const auto t0 = Clock::now();
      for (int k = 0; k < std::min<int>(o.refresh_views, int(views.size())); ++k) {
        SemanticView& rv = views[next_refresh];
        next_refresh = (next_refresh + 1) % views.size();
        const Image current = render(scene, rv.camera, rs).color;
        const Image cov = render_selection(scene, rv.camera, mask, rs);
        EditRequest req{&current, &cov, o.instruction, rv.camera.name};
        rv.target = editor.edit(req);
        ++result.editor_calls;
      }
      const double dt = seconds_since(t0);
      editing_in_loop += dt;
      result.seconds_editing += dt;
    }
    if (o.progress && o.progress_every > 0 && ((step + 1) % o.progress_every == 0 || step + 1 == o.steps)) {
      SemanticProgress p;
      p.step = step + 1;
      p.steps = o.steps;
      p.loss = loss_n ? loss_sum / loss_n : 0;
      p.lr_factor = lr;
      p.seconds = seconds_since(t_opt) - editing_in_loop;
      p.editor_calls = result.editor_calls;
      o.progress(p);
      loss_sum = 0;
      loss_n = 0;
    }
  }
  result.seconds_optimising = seconds_since(t_opt) - editing_in_loop;
  scene.validate("semantic edit result");

  double psnr_sum = 0;
  int psnr_n = 0;
  for (const SemanticView& v : views) {
    const Image now = render(scene, v.camera, rs).color;
    const double p = masked_psnr(now, v.target, v.mask);
    psnr_sum += std::isfinite(p) ? p : 100.0;
    ++psnr_n;
  }
  result.mean_mask_psnr = psnr_n ? psnr_sum / psnr_n : 0;
  result.views = std::move(views);
  return result;
}

}  // namespace isegman::edit
