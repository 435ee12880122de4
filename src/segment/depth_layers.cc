#include "segment/depth_layers.h"

#include <algorithm>
#include <cmath>

namespace isegman::segment {

std::vector<DepthLayer> depth_layers(const std::vector<float>& depth, const std::vector<double>& weight,
                                     const DepthLayerOptions& o) {
  std::vector<DepthLayer> layers;
  double total = 0, lo = 1e300, hi = 0;
  for (size_t i = 0; i < depth.size(); ++i) {
    if (!(depth[i] > 0) || !(weight[i] > 0)) continue;
    total += weight[i];
    lo = std::min(lo, double(depth[i]));
    hi = std::max(hi, double(depth[i]));
  }
  if (total <= 0) return layers;
  // Histogram over log depth: a gap of min_gap is the same share of depth near and far.
  const double step = std::log1p(o.bin);
  const int bins = std::max(1, int(std::ceil((std::log(hi) - std::log(lo)) / step)) + 1);
  std::vector<double> hist(size_t(bins), 0.0);
  auto bin_of = [&](double z) { return std::clamp(int((std::log(z) - std::log(lo)) / step), 0, bins - 1); };
  for (size_t i = 0; i < depth.size(); ++i)
    if (depth[i] > 0 && weight[i] > 0) hist[size_t(bin_of(depth[i]))] += weight[i];
  const int gap_bins = std::max(1, int(std::ceil(std::log1p(o.min_gap) / step)));
  int start = -1, last = -1;
  double w = 0;
  auto close = [&]() {
    layers.push_back({lo * std::exp(start * step), lo * std::exp((last + 1) * step), w / total});
  };
  for (int b = 0; b < bins; ++b) {
    if (hist[size_t(b)] < o.empty_share * total) continue;
    if (start >= 0 && b - last - 1 >= gap_bins) {
      close();
      start = -1;
      w = 0;
    }
    if (start < 0) start = b;
    last = b;
    w += hist[size_t(b)];
  }
  if (start >= 0) close();
  return layers;
}

GateReport gate_by_depth(const GaussianScene& scene, const Camera& camera, ViewVotes& positive, ViewVotes& neutral,
                         const std::vector<double>& seed_depths, const std::vector<bool>* selection,
                         const DepthLayerOptions& o) {
  GateReport rep;
  neutral = ViewVotes{};
  const size_t n = positive.index.size();
  std::vector<float> depth(n);
  std::vector<double> weight(n);
  for (size_t k = 0; k < n; ++k) {
    const uint32_t g = positive.index[k];
    const Vec3 p{scene.positions[3 * g], scene.positions[3 * g + 1], scene.positions[3 * g + 2]};
    depth[k] = float(camera.world_to_camera(p).z);
    weight[k] = double(positive.weight[k]);
  }
  const std::vector<DepthLayer> layers = depth_layers(depth, weight, o);
  rep.layers = int(layers.size());
  if (layers.size() <= 1) {
    if (!layers.empty()) rep.kept = layers[0];
    return rep;
  }
  auto layer_of = [&](double z) {
    for (size_t l = 0; l < layers.size(); ++l)
      if (z >= layers[l].near && z <= layers[l].far) return int(l);
    return -1;
  };
  int keep = -1;
  if (selection) {  // the layer holding most of the selection seen through this mask
    std::vector<double> selected(layers.size(), 0.0);
    for (size_t k = 0; k < n; ++k) {
      const int l = layer_of(depth[k]);
      if (l >= 0 && (*selection)[positive.index[k]]) selected[size_t(l)] += weight[k];
    }
    const auto best = std::max_element(selected.begin(), selected.end());
    if (*best > 0) keep = int(best - selected.begin());
  }
  if (keep < 0) {  // the layer nearest to a seed depth
    double best = 1e300;
    for (double z : seed_depths)
      for (size_t l = 0; l < layers.size(); ++l) {
        const double dist = z < layers[l].near ? layers[l].near - z : z > layers[l].far ? z - layers[l].far : 0.0;
        if (dist < best) {
          best = dist;
          keep = int(l);
        }
      }
  }
  if (keep < 0) return rep;  // nothing to decide by: keep every layer
  rep.kept = layers[size_t(keep)];
  ViewVotes kept;
  double gated = 0, total = 0;
  for (size_t k = 0; k < n; ++k) {
    total += weight[k];
    if (layer_of(depth[k]) == keep) {
      kept.index.push_back(positive.index[k]);
      kept.weight.push_back(positive.weight[k]);
    } else {
      neutral.index.push_back(positive.index[k]);
      neutral.weight.push_back(positive.weight[k]);
      gated += weight[k];
    }
  }
  positive = std::move(kept);
  rep.gated_share = total > 0 ? gated / total : 0;
  return rep;
}

}  // namespace isegman::segment
