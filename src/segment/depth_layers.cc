#include "segment/depth_layers.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/parallel.h"
#include "core/prefetch.h"
#include "render/projection.h"

namespace isegman::segment {

namespace {
// A sample that counts toward the layers' weight (and their total): in front of the camera,
// with weight.
bool counts(float depth, double weight) { return depth > 0 && weight > 0; }
// Whether depth_layers reads a sample's depth extent, given the total weight of the samples
// it splits: only one holding at least empty_share of it fills bins with its extent.
// gate_by_depth computes extents only where this holds.
bool reads_extent(float depth, double weight, double total, const DepthLayerOptions& o) {
  return depth > 0 && !(weight < o.empty_share * total);
}
}  // namespace

std::vector<DepthLayer> depth_layers(const std::vector<float>& depth, const std::vector<double>& weight,
                                     const DepthLayerOptions& o, const std::vector<float>* extent, int threads) {
  std::vector<DepthLayer> layers;
  // Chunks of samples in parallel, each with its own partial figures. The weights are whole
  // numbers of fixed-point units, so their sums are exact in any order, and so is the result.
  const size_t n = depth.size();
  const size_t grain = list_grain(n);
  const size_t chunks = std::max<size_t>(1, chunk_count(n, grain));
  struct Span {
    double total = 0, lo = 1e300, hi = 0;
  };
  std::vector<Span> spans(chunks);
  parallel_chunks(n, grain, threads, [&](size_t chunk, size_t begin, size_t end) {
    Span sp;  // in registers: the chunks' spans share cache lines
    for (size_t i = begin; i < end; ++i) {
      if (!counts(depth[i], weight[i])) continue;
      sp.total += weight[i];
      sp.lo = std::min(sp.lo, double(depth[i]));
      sp.hi = std::max(sp.hi, double(depth[i]));
    }
    spans[chunk] = sp;
  });
  double total = 0, lo = 1e300, hi = 0;
  for (const Span& sp : spans) {
    total += sp.total;
    lo = std::min(lo, sp.lo);
    hi = std::max(hi, sp.hi);
  }
  if (total <= 0) return layers;
  // Histogram over log depth: a gap of min_gap is the same share of depth near and far.
  const double step = std::log1p(o.bin);
  const int bins = std::max(1, int(std::ceil((std::log(hi) - std::log(lo)) / step)) + 1);
  const double log_lo = std::log(lo);  // once, not per sample (the same value)
  auto bin_of = [&](double z) { return std::clamp(int((std::log(z) - log_lo) / step), 0, bins - 1); };
  // Bins inside the depth extent of a Gaussian that matters are not empty either.
  const bool extents = extent && o.extent_sigmas > 0;
  std::vector<std::vector<double>> hists(chunks);
  std::vector<std::vector<char>> covers(chunks);
  parallel_chunks(n, grain, threads, [&](size_t chunk, size_t begin, size_t end) {
    std::vector<double>& h = hists[chunk];
    std::vector<char>& c = covers[chunk];
    h.assign(size_t(bins), 0.0);
    c.assign(size_t(bins), 0);
    for (size_t i = begin; i < end; ++i) {
      if (counts(depth[i], weight[i])) h[size_t(bin_of(depth[i]))] += weight[i];
      if (!extents || !reads_extent(depth[i], weight[i], total, o)) continue;
      const double r = o.extent_sigmas * double((*extent)[i]);
      const int b0 = bin_of(std::max(lo, double(depth[i]) - r)), b1 = bin_of(std::min(hi, double(depth[i]) + r));
      for (int b = b0; b <= b1; ++b) c[size_t(b)] = 1;
    }
  });
  std::vector<double> hist(size_t(bins), 0.0);
  std::vector<char> covered(size_t(bins), 0);
  for (size_t k = 0; k < chunks; ++k) {
    if (hists[k].empty()) continue;
    for (int b = 0; b < bins; ++b) {
      hist[size_t(b)] += hists[k][size_t(b)];
      covered[size_t(b)] |= covers[k][size_t(b)];
    }
  }
  const int gap_bins = std::max(1, int(std::ceil(std::log1p(o.min_gap) / step)));
  int start = -1, last = -1;
  double w = 0;
  auto close = [&]() {
    layers.push_back({lo * std::exp(start * step), lo * std::exp((last + 1) * step), w / total});
  };
  for (int b = 0; b < bins; ++b) {
    if (hist[size_t(b)] < o.empty_share * total && !covered[size_t(b)]) continue;
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

float depth_extent(const GaussianScene& scene, const Camera& camera, size_t g) {
  if (scene.scales.size() < 3 * (g + 1) || scene.rotations.size() < 4 * (g + 1)) return 0.f;  // centres only
  float cov[6];
  covariance_3d(&scene.scales[3 * g], &scene.rotations[4 * g], cov);
  // Variance of camera z = a^T Sigma a, a = the camera's z axis in world coordinates.
  const double a[3] = {camera.R.m[2][0], camera.R.m[2][1], camera.R.m[2][2]};
  const double v = a[0] * a[0] * cov[0] + a[1] * a[1] * cov[3] + a[2] * a[2] * cov[5] +
                   2 * (a[0] * a[1] * cov[1] + a[0] * a[2] * cov[2] + a[1] * a[2] * cov[4]);
  return float(std::sqrt(std::max(0.0, v)));
}

namespace {

int layer_of(const std::vector<DepthLayer>& layers, double z) {
  for (size_t l = 0; l < layers.size(); ++l)
    if (z >= layers[l].near && z <= layers[l].far) return int(l);
  return -1;
}

// Per-region decision (see the header). keep[k] says whether mask entry k stays positive;
// false when the selection has no weight in the mask (nothing to decide by).
// `region[k]`: the region of entry k's centre (-1 behind the camera: no region, neutral).
bool keep_local_layers(int gx, int gy, const std::vector<int32_t>& region, const std::vector<float>& depth,
                       const std::vector<float>& extent, const std::vector<double>& weight,
                       const std::vector<char>& selected,
                       const DepthLayerOptions& o, std::vector<uint8_t>& keep, int threads) {
  // Each region's entries, ascending, and their samples gathered beside them: one array per
  // figure, a range per region. A region's members lie scattered over the view's entries
  // (megabytes at millions of Gaussians), and reading them in place missed the cache at
  // nearly every sample; so did a list apiece, an allocation per region and view.
  // A counting sort in parallel chunks: each chunk counts its entries per region, takes its
  // place in every region after the chunks before it, and fills it, so a region's entries
  // stay ascending, as one pass in order would leave them.
  const size_t regions = size_t(gx) * gy;
  const size_t n = region.size(), grain = list_grain(n), chunks = chunk_count(n, grain);
  std::vector<std::vector<uint32_t>> chunk_next(chunks);  // per chunk and region: its next slot
  parallel_chunks(n, grain, threads, [&](size_t chunk, size_t begin, size_t end) {
    std::vector<uint32_t> count(regions, 0);
    for (size_t k = begin; k < end; ++k)
      if (region[k] >= 0) ++count[size_t(region[k])];
    chunk_next[chunk] = std::move(count);
  });
  std::vector<uint32_t> first(regions + 1, 0);
  uint32_t placed_so_far = 0;
  for (size_t r = 0; r < regions; ++r) {
    first[r] = placed_so_far;
    for (std::vector<uint32_t>& next : chunk_next) placed_so_far += std::exchange(next[r], placed_so_far);
  }
  first[regions] = placed_so_far;
  const size_t placed = first[regions];
  std::vector<uint32_t> entries(placed);
  std::vector<float> z(placed), e(placed);
  std::vector<double> w(placed);
  std::vector<char> sel_entry(placed);
  parallel_chunks(n, grain, threads, [&](size_t chunk, size_t begin, size_t end) {
    std::vector<uint32_t>& next = chunk_next[chunk];
    for (size_t k = begin; k < end; ++k) {
      if (region[k] < 0) continue;
      const uint32_t p = next[size_t(region[k])]++;
      entries[p] = uint32_t(k);
      z[p] = depth[k];
      e[p] = extent[k];
      w[p] = weight[k];
      sel_entry[p] = selected[k];
    }
  });
  struct Range { double lo = 1e300, hi = -1e300; bool set() const { return hi >= lo; } };
  std::vector<std::vector<DepthLayer>> layers(regions);
  std::vector<int> layer_index(placed, -1);
  std::vector<Range> source(regions);
  std::vector<int> distance(regions, -1);
  keep.assign(region.size(), 0);
  // Regions on their own, in parallel: each writes its own entries and its members' keep.
  parallel_for(regions, threads, [&](int, size_t r) {
    const size_t b = first[r], end = first[r + 1];
    if (b == end) return;
    const std::vector<float> rz(z.begin() + std::ptrdiff_t(b), z.begin() + std::ptrdiff_t(end)),
        re(e.begin() + std::ptrdiff_t(b), e.begin() + std::ptrdiff_t(end));
    const std::vector<double> rw(w.begin() + std::ptrdiff_t(b), w.begin() + std::ptrdiff_t(end));
    layers[r] = depth_layers(rz, rw, o, &re);
    std::vector<double> sel(layers[r].size(), 0.0), all(layers[r].size(), 0.0);
    for (size_t p = b; p < end; ++p) {
      const int l = layer_of(layers[r], z[p]);
      layer_index[p] = l;
      if (l < 0) continue;
      all[size_t(l)] += w[p];
      if (sel_entry[p]) sel[size_t(l)] += w[p];
    }
    // A layer only a few stray selected Gaussians reach (a leak) is not kept: a region
    // none of whose layers is mostly selected is judged like a region the selection misses.
    std::vector<char> kept_layer(layers[r].size(), 0);
    for (size_t l = 0; l < sel.size(); ++l) {
      if (!(all[l] > 0 && sel[l] >= o.keep_share * all[l])) continue;
      kept_layer[l] = 1;
      source[r].lo = std::min(source[r].lo, layers[r][l].near);
      source[r].hi = std::max(source[r].hi, layers[r][l].far);
    }
    if (!source[r].set()) return;
    for (size_t p = b; p < end; ++p)
      if (layer_index[p] >= 0 && kept_layer[size_t(layer_index[p])]) keep[entries[p]] = 1;
    distance[r] = 0;
  });
  std::vector<size_t> wave;
  for (size_t r = 0; r < regions; ++r)
    if (distance[r] == 0) wave.push_back(r);
  if (wave.empty()) return false;
  // Regions the selection does not reach take the kept depth range of the nearest regions
  // it reaches (breadth-first over the grid, a wave at a time so the order cannot matter).
  std::vector<Range> reference = source;
  for (int d = 1; !wave.empty() && d <= o.reach; ++d) {
    std::vector<size_t> next;
    for (size_t r : wave) {
      const int x = int(r % size_t(gx)), y = int(r / size_t(gx));
      const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
      for (int i = 0; i < 4; ++i) {
        if (nx[i] < 0 || ny[i] < 0 || nx[i] >= gx || ny[i] >= gy) continue;
        const size_t n = size_t(ny[i]) * gx + size_t(nx[i]);
        if (distance[n] >= 0 && distance[n] < d) continue;
        if (distance[n] < 0) {
          distance[n] = d;
          next.push_back(n);
        }
        reference[n].lo = std::min(reference[n].lo, reference[r].lo);
        reference[n].hi = std::max(reference[n].hi, reference[r].hi);
      }
    }
    wave = std::move(next);
  }
  for (size_t r = 0; r < regions; ++r) {
    if (first[r] == first[r + 1] || source[r].set() || !reference[r].set()) continue;
    const double lo = reference[r].lo * (1 - o.margin), hi = reference[r].hi * (1 + o.margin);
    for (size_t p = first[r]; p < first[r + 1]; ++p) {
      const int l = layer_index[p];
      if (l >= 0 && layers[r][size_t(l)].far >= lo && layers[r][size_t(l)].near <= hi) keep[entries[p]] = 1;
    }
  }
  return true;
}

}  // namespace

GateReport gate_by_depth(const GaussianScene& scene, const Camera& camera, ViewVotes& positive, ViewVotes& neutral,
                         const std::vector<double>& seed_depths, const std::vector<bool>* selection,
                         const DepthLayerOptions& o, int threads) {
  GateReport rep;
  neutral = ViewVotes{};
  const size_t n = positive.index.size();
  const size_t grain = list_grain(n);
  const int R = std::max(1, o.region);
  const int gx = std::max(1, (camera.width + R - 1) / R), gy = std::max(1, (camera.height + R - 1) / R);
  std::vector<float> depth(n), extent(n);
  std::vector<double> weight(n);
  std::vector<char> selected(n, 0);
  std::vector<int32_t> region(n, -1);
  // Per entry, independent: chunks in parallel.
  parallel_chunks(n, grain, threads, [&](size_t, size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) {
      prefetch_centre_ahead(scene, positive.index, k);
      const uint32_t g = positive.index[k];
      const Vec3 centre{scene.positions[3 * g], scene.positions[3 * g + 1], scene.positions[3 * g + 2]};
      depth[k] = float(camera.world_to_camera(centre).z);
      weight[k] = double(positive.weight[k]);
      if (selection) selected[k] = (*selection)[g];
      double u = 0, v = 0;
      if (camera.project(centre, u, v))
        region[k] = std::clamp(int(std::floor(v / R)), 0, gy - 1) * gx + std::clamp(int(std::floor(u / R)), 0, gx - 1);
    }
  });
  // Depth extents (a covariance each) only where depth_layers reads them: a sample holding at
  // least empty_share of the weight of the layers it is split into, all of the mask's or (for
  // local layers) its region's. The totals are sums of whole numbers, the same as
  // depth_layers' own; elsewhere the extent stays 0, unread.
  if (o.extent_sigmas > 0) {
    const bool local = selection && o.region > 0;
    const size_t regions = local ? size_t(gx) * gy : 0, chunks = chunk_count(n, grain);
    std::vector<double> chunk_total(chunks, 0.0);
    std::vector<std::vector<double>> chunk_regions(chunks);
    parallel_chunks(n, grain, threads, [&](size_t chunk, size_t begin, size_t end) {
      double t = 0;
      std::vector<double> r(regions, 0.0);  // a local, moved in at the end
      for (size_t k = begin; k < end; ++k) {
        if (!counts(depth[k], weight[k])) continue;
        t += weight[k];
        if (local && region[k] >= 0) r[size_t(region[k])] += weight[k];
      }
      chunk_total[chunk] = t;
      chunk_regions[chunk] = std::move(r);
    });
    double total = 0;  // sums of whole numbers: the same in any order
    std::vector<double> region_total(regions, 0.0);
    for (size_t c = 0; c < chunks; ++c) {
      total += chunk_total[c];
      for (size_t r = 0; r < regions; ++r) region_total[r] += chunk_regions[c][r];
    }
    parallel_chunks(n, grain, threads, [&](size_t, size_t begin, size_t end) {
      for (size_t k = begin; k < end; ++k) {
        const bool read = reads_extent(depth[k], weight[k], total, o) ||
                          (local && region[k] >= 0 && reads_extent(depth[k], weight[k], region_total[size_t(region[k])], o));
        if (read) extent[k] = depth_extent(scene, camera, positive.index[k]);
      }
    });
  }
  const std::vector<DepthLayer> layers = depth_layers(depth, weight, o, &extent, threads);
  rep.layers = int(layers.size());
  std::vector<uint8_t> keep;
  if (selection && o.region > 0 && keep_local_layers(gx, gy, region, depth, extent, weight, selected, o, keep, threads)) {
    rep.local = true;
  } else {
    if (layers.size() <= 1) {
      if (!layers.empty()) rep.kept = layers[0];
      return rep;
    }
    int best_layer = -1;
    if (selection) {  // the layer holding most of the selection seen through this mask
      std::vector<double> sel(layers.size(), 0.0);
      for (size_t k = 0; k < n; ++k) {
        const int l = layer_of(layers, depth[k]);
        if (l >= 0 && selected[k]) sel[size_t(l)] += weight[k];
      }
      const auto best = std::max_element(sel.begin(), sel.end());
      if (*best > 0) best_layer = int(best - sel.begin());
    }
    if (best_layer < 0) {  // the layer nearest to a seed depth
      double best = 1e300;
      for (double z : seed_depths)
        for (size_t l = 0; l < layers.size(); ++l) {
          const double dist = z < layers[l].near ? layers[l].near - z : z > layers[l].far ? z - layers[l].far : 0.0;
          if (dist < best) {
            best = dist;
            best_layer = int(l);
          }
        }
    }
    if (best_layer < 0) return rep;  // nothing to decide by: keep every layer
    rep.kept = layers[size_t(best_layer)];
    keep.assign(n, 0);
    for (size_t k = 0; k < n; ++k) keep[k] = layer_of(layers, depth[k]) == best_layer;
  }
  SplitWeights split = split_in_order(positive, keep, threads);
  // The weights are whole numbers: the sums do not depend on the order.
  double gated = 0, total = 0;
  for (int64_t w : split.rest.weight) gated += double(w);
  for (int64_t w : positive.weight) total += double(w);
  positive = std::move(split.flagged);
  neutral = std::move(split.rest);
  rep.gated_share = total > 0 ? gated / total : 0;
  return rep;
}

}  // namespace isegman::segment
