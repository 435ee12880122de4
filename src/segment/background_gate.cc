#include "segment/background_gate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/parallel.h"
#include "core/prefetch.h"
#include "core/random.h"

namespace isegman::segment {

namespace {

// The bounding box of a mask's pixels (> 0.5) and their centre; x1 < 0 when there are none.
struct MaskBounds {
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  double cx = 0, cy = 0, area = 0;
};

MaskBounds mask_bounds(const Image& mask) {
  MaskBounds m;
  m.x0 = mask.width, m.y0 = mask.height;
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x)
      if (mask.at(x, y) > 0.5f) {
        m.x0 = std::min(m.x0, x), m.y0 = std::min(m.y0, y);
        m.x1 = std::max(m.x1, x), m.y1 = std::max(m.y1, y);
        m.cx += x + 0.5, m.cy += y + 0.5, m.area += 1;
      }
  return m;
}

// The first value of (value, weight) pairs sorted by value whose running weight reaches
// share q of the total (the last value when rounding keeps it short).
double weighted_quantile(const std::vector<std::pair<double, double>>& sorted, double q) {
  double total = 0, run = 0;
  for (const auto& s : sorted) total += s.second;
  for (const auto& s : sorted)
    if ((run += s.second) >= q * total) return s.first;
  return sorted.back().first;
}

// What the lines of one direction give.
struct LineEstimates {
  // (pixel, inverse depth) interpolated in a run: a pixel lies on one line of each
  // direction and in at most one run of it, so it appears at most once.
  std::vector<std::pair<uint32_t, float>> values;
  // Every usable sample at a run's end, nearer than the target or not: (pixel, inverse
  // depth), the ring the surroundings' plane is fitted to.
  std::vector<std::pair<uint32_t, float>> ring;
};

// One line of pixels (in order along the direction): every run of mask pixels gets the
// inverse depth interpolated between the usable outside samples at both of its ends.
void interpolate_line(const std::vector<uint32_t>& line, const Image& mask, const Image& depth, const Image& alpha,
                      double near_limit, const BackgroundOptions& o, int max_span, LineEstimates& e) {
  const size_t n = line.size();
  auto inside = [&](size_t i) { return mask.data[line[i]] > 0.5f; };
  auto inverse = [&](long i, double limit) -> float {
    if (i < 0 || i >= long(n)) return 0.f;
    const uint32_t p = line[size_t(i)];
    const float z = depth.data[p];
    return alpha.data[p] > 0.5f && z > 0 && z >= limit ? 1.f / z : 0.f;
  };
  // The inverse depth of line pixel i as a background sample, or 0 when it cannot serve:
  // the surface must go on smoothly for 2 x `extent` pixels further out (a surface, not a
  // thin bar in front of one: the rail of a screen whose one slat is the mask).
  auto sample = [&](size_t i, long outward, double limit) -> float {
    const float v = inverse(long(i), limit);
    if (o.extent <= 0 || v <= 0) return v;
    // The continuation only shows the surface goes on: a floor seen at a grazing angle comes
    // nearer than the target's near side a few pixels on, and is still the floor.
    const float v1 = inverse(long(i) + outward * o.extent, 0), v2 = inverse(long(i) + 2 * outward * o.extent, 0);
    // Smooth: no bend between the three (a plane's inverse depth is linear along the line).
    if (v1 <= 0 || v2 <= 0 || std::abs(v - 2 * v1 + v2) > o.agreement * v) return 0.f;
    return v;
  };
  size_t i = 0;
  while (i < n) {
    if (!inside(i)) {
      ++i;
      continue;
    }
    size_t j = i;
    while (j < n && inside(j)) ++j;  // run [i, j)
    // Samples `skip` pixels past each border, with every pixel up to them outside the mask.
    const long a = long(i) - 1 - o.skip, b = long(j) + o.skip;
    bool ok = a >= 0 && b < long(n) && long(j - i) + 2 * o.skip + 2 <= max_span;
    for (long k = a; ok && k < long(i); ++k) ok = !inside(size_t(k));
    for (long k = long(j); ok && k <= b; ++k) ok = !inside(size_t(k));
    const float s0 = ok ? sample(size_t(a), -1, near_limit) : 0.f, s1 = ok ? sample(size_t(b), +1, near_limit) : 0.f;
    if (ok && o.plane) {
      const float r0 = s0 > 0 ? s0 : sample(size_t(a), -1, 0), r1 = s1 > 0 ? s1 : sample(size_t(b), +1, 0);
      if (r0 > 0) e.ring.push_back({line[size_t(a)], r0});
      if (r1 > 0) e.ring.push_back({line[size_t(b)], r1});
    }
    if (s0 > 0 && s1 > 0) {
      const double span = double(b - a);
      for (size_t k = i; k < j; ++k) {
        const double t = double(long(k) - a) / span;
        e.values.push_back({line[k], float((1 - t) * s0 + t * s1)});
      }
    }
    i = j;
  }
}

// Camera-space point of pixel (x, y) on the background surface (inverse depth inv).
Vec3 surface_point(const Camera& camera, double x, double y, double inv) {
  const double z = 1.0 / inv;
  return {(x + 0.5 - camera.cx) / camera.fx * z, (y + 0.5 - camera.cy) / camera.fy * z, z};
}

// Whether flat Gaussian g (one scale well below the others: a piece of surface) is turned
// away from the background surface at pixel (x, y): an object resting on the floor touches
// the floor's surface with its side, whose Gaussians stand across it, while the floor seen
// through a gap lies in it. Gaussians that are not flat tell nothing (false); where the
// surface's orientation cannot be estimated, the Gaussian is left alone (true).
bool crosses_surface(const GaussianScene& scene, const Camera& camera, const Image& bg, uint32_t g, int x, int y,
                     double min_alignment) {
  if (min_alignment <= 0 || scene.scales.size() < 3 * (size_t(g) + 1) || scene.rotations.size() < 4 * (size_t(g) + 1))
    return false;
  const float* sc = &scene.scales[3 * size_t(g)];
  int thin = 0;
  for (int a = 1; a < 3; ++a)
    if (sc[a] < sc[thin]) thin = a;
  const float mid = std::min(sc[(thin + 1) % 3], sc[(thin + 2) % 3]);
  if (mid - sc[thin] < std::log(2.0f)) return false;  // not flat: less than 2x thinner (log scales)
  // The surface's normal from its estimate at the neighbouring pixels (one-sided at edges).
  auto at = [&](int px, int py) { return px >= 0 && py >= 0 && px < bg.width && py < bg.height ? bg.at(px, py) : 0.f; };
  // A baseline of several pixels: the estimate is only good to `agreement`, which over one
  // pixel would tilt the normal arbitrarily.
  // Without enough estimate around the pixel to tell, the Gaussian stays where it is.
  auto offset = [&](int ux, int uy) {  // the longest step (8, 4, then 2 pixels) with an estimate
    for (int step : {8, 4, 2})
      for (int sign : {1, -1})
        if (at(x + sign * step * ux, y + sign * step * uy) > 0) return sign * step;
    return 0;
  };
  const int dx = offset(1, 0), dy = offset(0, 1);
  if (!dx || !dy) return true;
  const float i0 = at(x, y), ix = at(x + dx, y), iy = at(x, y + dy);
  const Vec3 p0 = surface_point(camera, x, y, i0);
  const Vec3 n_surface = normalized(cross((surface_point(camera, x + dx, y, ix) - p0) * double(dx),
                                          (surface_point(camera, x, y + dy, iy) - p0) * double(dy)));
  const float* q = &scene.rotations[4 * size_t(g)];
  const Mat3 r = Quat(q[0], q[1], q[2], q[3]).to_matrix();
  const Vec3 n_world{r.m[0][thin], r.m[1][thin], r.m[2][thin]};
  const Vec3 n_gaussian = camera.R * n_world;
  return std::abs(dot(n_surface, n_gaussian)) < min_alignment;
}

// A plane's inverse depth is affine in the pixel: 1/z = a x + b y + c.
struct InversePlane {
  double a = 0, b = 0, c = 0;
  double at(double x, double y) const { return a * x + b * y + c; }
};

// Least squares over the given samples; false when they do not span a plane.
bool fit_plane(const std::vector<std::array<double, 3>>& pts, InversePlane& plane) {
  double m[3][4] = {};
  for (const auto& p : pts) {
    const double r[3] = {p[0], p[1], 1.0};
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) m[i][j] += r[i] * r[j];
      m[i][3] += r[i] * p[2];
    }
  }
  for (int col = 0; col < 3; ++col) {  // Gauss-Jordan with partial pivoting
    int piv = col;
    for (int r = col + 1; r < 3; ++r)
      if (std::abs(m[r][col]) > std::abs(m[piv][col])) piv = r;
    if (std::abs(m[piv][col]) < 1e-12) return false;
    std::swap(m[piv], m[col]);
    for (int r = 0; r < 3; ++r) {
      if (r == col) continue;
      const double f = m[r][col] / m[col][col];
      for (int k = col; k < 4; ++k) m[r][k] -= f * m[col][k];
    }
  }
  plane = {m[0][3] / m[0][0], m[1][3] / m[1][1], m[2][3] / m[2][2]};
  return true;
}

// The plane most of the ring lies on (RANSAC over sample triples, then refitted to its
// inliers), when that is at least `min_share` of the ring and its inliers lie on three or
// more sides of the mask (around its centre): a floor or a wall the object stands before,
// not one side's surface extrapolated across the object.
bool surroundings_plane(const std::vector<std::pair<uint32_t, float>>& ring, int width, double cx, double cy,
                        const BackgroundOptions& o, InversePlane& plane) {
  if (ring.size() < 16) return false;
  std::vector<std::array<double, 3>> pts(ring.size());
  for (size_t i = 0; i < ring.size(); ++i)
    pts[i] = {double(ring[i].first % uint32_t(width)) + 0.5, double(ring[i].first / uint32_t(width)) + 0.5,
              double(ring[i].second)};
  auto inliers = [&](const InversePlane& pl, std::vector<std::array<double, 3>>* out) {
    size_t count = 0;
    for (const auto& p : pts)
      if (std::abs(pl.at(p[0], p[1]) - p[2]) <= o.agreement * p[2]) {
        ++count;
        if (out) out->push_back(p);
      }
    return count;
  };
  SplitMix64 rng(0x5EEDull + ring.size());
  InversePlane best;
  size_t best_count = 0;
  for (int it = 0; it < o.plane_trials; ++it) {
    std::vector<std::array<double, 3>> triple;
    for (int k = 0; k < 3; ++k) triple.push_back(pts[size_t(rng.next() % pts.size())]);
    InversePlane pl;
    if (!fit_plane(triple, pl)) continue;
    const size_t count = inliers(pl, nullptr);
    if (count > best_count) best_count = count, best = pl;
  }
  if (double(best_count) < o.plane_min_share * double(pts.size())) return false;
  std::vector<std::array<double, 3>> in;
  inliers(best, &in);
  if (!fit_plane(in, plane)) return false;
  in.clear();
  if (double(inliers(plane, &in)) < o.plane_min_share * double(pts.size())) return false;
  int sides = 0;  // left, right, above, below the mask's centre: a side holds 1/12 of the inliers
  size_t left = 0, right = 0, above = 0, below = 0;
  for (const auto& p : in) {
    const double dx = p[0] - cx, dy = p[1] - cy;
    if (std::abs(dx) >= std::abs(dy)) ++(dx < 0 ? left : right);
    else ++(dy < 0 ? above : below);
  }
  for (size_t n : {left, right, above, below}) sides += 12 * n >= in.size() ? 1 : 0;
  return sides >= 3;
}

}  // namespace

double near_depth(const GaussianScene& scene, const Camera& camera, const ViewVotes& votes, double share, int threads) {
  const size_t n = votes.index.size();
  const size_t grain = list_grain(n);
  if (n == 0) return 0.0;
  std::vector<std::pair<double, double>> dw(n);
  parallel_chunks(n, grain, threads, [&](size_t, size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) {
      prefetch_centre_ahead(scene, votes.index, k);
      const uint32_t g = votes.index[k];
      dw[k] = {camera.world_to_camera({scene.positions[3 * g], scene.positions[3 * g + 1], scene.positions[3 * g + 2]}).z,
               double(votes.weight[k])};
    }
  });
  // The first entry in (depth, weight) order whose running weight reaches the target, as a
  // walk over the sorted list would find it, without a sort (a large scene's mask holds ~10^6
  // Gaussians a view). The weights are whole numbers of fixed-point units, so their sums are
  // exact in any order. A histogram over depth (bins in depth order: the binning is monotone)
  // finds the bin the running weight reaches the target in; only that bin's entries are
  // then ordered, by selection.
  // Each of the three passes runs in parallel chunks, merged in chunk order (whole-number
  // sums and extrema: the same in any order).
  const size_t chunks = chunk_count(n, grain);
  std::vector<double> chunk_total(chunks, 0.0), chunk_lo(chunks, dw[0].first), chunk_hi(chunks, dw[0].first);
  parallel_chunks(n, grain, threads, [&](size_t c, size_t begin, size_t end) {
    double t = 0, lo_d = dw[begin].first, hi_d = dw[begin].first;
    for (size_t k = begin; k < end; ++k) {
      t += dw[k].second;
      lo_d = std::min(lo_d, dw[k].first);
      hi_d = std::max(hi_d, dw[k].first);
    }
    chunk_total[c] = t;
    chunk_lo[c] = lo_d;
    chunk_hi[c] = hi_d;
  });
  double total = 0, lo_depth = dw[0].first, hi_depth = dw[0].first;
  for (size_t c = 0; c < chunks; ++c) {
    total += chunk_total[c];
    lo_depth = std::min(lo_depth, chunk_lo[c]);
    hi_depth = std::max(hi_depth, chunk_hi[c]);
  }
  const double target = share * total;
  constexpr int kBins = 4096;
  const double per_depth = hi_depth > lo_depth ? kBins / (hi_depth - lo_depth) : 0.0;
  auto bin_of = [&](double d) { return std::min(kBins - 1, int((d - lo_depth) * per_depth)); };
  std::vector<std::vector<double>> chunk_hist(chunks);
  parallel_chunks(n, grain, threads, [&](size_t chunk, size_t begin, size_t end) {
    std::vector<double> h(kBins, 0.0);  // a local, moved in at the end
    for (size_t k = begin; k < end; ++k) h[size_t(bin_of(dw[k].first))] += dw[k].second;
    chunk_hist[chunk] = std::move(h);
  });
  std::vector<double> hist(kBins, 0.0);
  for (const std::vector<double>& h : chunk_hist)
    for (int b = 0; b < kBins; ++b) hist[size_t(b)] += h[size_t(b)];
  int bin = 0;
  double before = 0;  // the weight of the entries ordered before the bin's
  while (bin < kBins - 1 && before + hist[size_t(bin)] < target) before += hist[size_t(bin++)];
  std::vector<std::vector<std::pair<double, double>>> chunk_in_bin(chunks);
  parallel_chunks(n, grain, threads, [&](size_t chunk, size_t begin, size_t end) {
    std::vector<std::pair<double, double>> found;  // a local, moved in at the end
    for (size_t k = begin; k < end; ++k)
      if (bin_of(dw[k].first) == bin) found.push_back(dw[k]);
    chunk_in_bin[chunk] = std::move(found);
  });
  std::vector<std::pair<double, double>> in_bin;
  for (const auto& f : chunk_in_bin) in_bin.insert(in_bin.end(), f.begin(), f.end());
  size_t lo = 0, hi = in_bin.size();
  double found = hi_depth;
  while (lo < hi) {
    const size_t mid = lo + (hi - lo) / 2;
    std::nth_element(in_bin.begin() + std::ptrdiff_t(lo), in_bin.begin() + std::ptrdiff_t(mid),
                     in_bin.begin() + std::ptrdiff_t(hi));
    double through = before;
    for (size_t k = lo; k <= mid; ++k) through += in_bin[k].second;
    if (through >= target) {
      found = in_bin[mid].first;
      hi = mid;
    } else {
      before = through;
      lo = mid + 1;
    }
  }
  return found;
}

Image background_inverse_depth(const Image& mask, const Image& depth, const Image& alpha, double near_limit,
                               const BackgroundOptions& o, int threads) {
  const int w = mask.width, h = mask.height;
  Image out(w, h, 1);
  const size_t npx = size_t(w) * h;
  if (w == 0 || h == 0 || depth.data.size() != npx || alpha.data.size() != npx) return out;
  const int max_span = o.max_span > 0 ? o.max_span : std::max(w, h) * 2;
  // Only the mask's bounding box, widened by the farthest pixel a sample reads, matters:
  // lines are walked within it (the same result as over the whole image, for less work).
  // The same pass gives the mask's centre, around which the plane's sides are counted.
  const MaskBounds m = mask_bounds(mask);
  const int bx0 = m.x0, by0 = m.y0, bx1 = m.x1, by1 = m.y1;
  const double cx = m.cx, cy = m.cy, area = m.area;
  if (bx1 < 0) return out;
  const int reach = 1 + o.skip + 2 * std::max(0, o.extent);
  const int x0 = std::max(0, bx0 - reach), y0 = std::max(0, by0 - reach);
  const int x1 = std::min(w - 1, bx1 + reach), y1 = std::min(h - 1, by1 + reach);
  // The four directions on their own (in parallel), then combined in a fixed order: rows,
  // columns, diagonals, anti-diagonals, so the float sums do not depend on the threads.
  std::array<LineEstimates, 4> dir;
  parallel_for(4, threads, [&](int, size_t d) {
    std::vector<uint32_t> line;
    auto walk = [&](int x, int y, int dx, int dy) {
      line.clear();
      for (; x >= x0 && y >= y0 && x <= x1 && y <= y1; x += dx, y += dy)
        line.push_back(uint32_t(y) * uint32_t(w) + uint32_t(x));
      interpolate_line(line, mask, depth, alpha, near_limit, o, max_span, dir[d]);
    };
    if (d == 0) {
      for (int y = y0; y <= y1; ++y) walk(x0, y, 1, 0);  // rows
    } else if (d == 1) {
      for (int x = x0; x <= x1; ++x) walk(x, y0, 0, 1);  // columns
    } else if (d == 2) {
      for (int y = y0; y <= y1; ++y) walk(x0, y, 1, 1);  // diagonals
      for (int x = x0 + 1; x <= x1; ++x) walk(x, y0, 1, 1);
    } else {
      for (int y = y0; y <= y1; ++y) walk(x0, y, 1, -1);  // anti-diagonals
      for (int x = x0 + 1; x <= x1; ++x) walk(x, y1, 1, -1);
    }
  });
  // Per pixel of the box: the sum, range and count of its directions' values.
  const int bw = x1 - x0 + 1;
  const size_t box = size_t(bw) * size_t(y1 - y0 + 1);
  std::vector<float> sum(box, 0.f), lo(box, 1e30f), hi(box, -1e30f);
  std::vector<uint8_t> count(box, 0);
  std::vector<std::pair<uint32_t, float>> ring;
  for (const LineEstimates& e : dir) {
    for (const auto& [p, v] : e.values) {
      const size_t b = size_t(int(p / uint32_t(w)) - y0) * size_t(bw) + size_t(int(p % uint32_t(w)) - x0);
      sum[b] += v;
      lo[b] = std::min(lo[b], v);
      hi[b] = std::max(hi[b], v);
      ++count[b];
    }
    ring.insert(ring.end(), e.ring.begin(), e.ring.end());
  }
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const size_t b = size_t(y - y0) * size_t(bw) + size_t(x - x0);
      if (count[b] < o.min_directions) continue;
      const float mean = sum[b] / float(count[b]);
      if (hi[b] - lo[b] <= o.agreement * mean) out.data[size_t(y) * size_t(w) + size_t(x)] = mean;
    }
  // Where the lines give no estimate (a ring's hole: its lines cross the near floor in front
  // of it, which is nearer than the target), the plane the surroundings lie on, when they
  // lie on one, beyond the target's near side.
  InversePlane plane;
  if (o.plane && area > 0 && surroundings_plane(ring, w, cx / area, cy / area, o, plane)) {
    const double far_inverse = near_limit > 0 ? 1.0 / near_limit : 1e30;
    for (int y = by0; y <= by1; ++y)
      for (int x = bx0; x <= bx1; ++x) {
        const size_t p = size_t(y) * size_t(w) + size_t(x);
        if (mask.data[p] <= 0.5f || out.data[p] > 0) continue;
        const double v = plane.at(x + 0.5, y + 0.5);
        if (v > 0 && v <= far_inverse) out.data[p] = float(v);
      }
  }
  return out;
}

namespace {

// Pixels within `r` (Chebyshev distance) of a mask pixel, over the box [x0, x1] x [y0, y1]
// (row-major in it): a separable running maximum.
std::vector<uint8_t> dilated(const Image& mask, int x0, int y0, int x1, int y1, int r) {
  const int bw = x1 - x0 + 1, bh = y1 - y0 + 1;
  std::vector<uint8_t> rows(size_t(bw) * size_t(bh), 0), out(rows.size(), 0);
  for (int y = 0; y < bh; ++y) {
    int last = -(1 << 20);  // the last mask pixel seen on the row, sweeping right then left
    for (int x = 0; x < bw; ++x) {
      if (mask.at(x0 + x, y0 + y) > 0.5f) last = x;
      rows[size_t(y) * size_t(bw) + size_t(x)] = x - last <= r;
    }
    last = 1 << 20;
    for (int x = bw - 1; x >= 0; --x) {
      if (mask.at(x0 + x, y0 + y) > 0.5f) last = x;
      rows[size_t(y) * size_t(bw) + size_t(x)] |= last - x <= r;
    }
  }
  for (int x = 0; x < bw; ++x) {
    int last = -(1 << 20);
    for (int y = 0; y < bh; ++y) {
      if (rows[size_t(y) * size_t(bw) + size_t(x)]) last = y;
      out[size_t(y) * size_t(bw) + size_t(x)] = y - last <= r;
    }
    last = 1 << 20;
    for (int y = bh - 1; y >= 0; --y) {
      if (rows[size_t(y) * size_t(bw) + size_t(x)]) last = y;
      out[size_t(y) * size_t(bw) + size_t(x)] |= last - y <= r;
    }
  }
  return out;
}

}  // namespace

namespace {
// Of a view's list of votes, surroundings_surface reads every stride-th: a large scene's view
// shows ~10^6 Gaussians, and every stride-th of them is plenty for a median and a spread (a
// view of up to 2^18 Gaussians is read whole).
size_t surroundings_stride(size_t votes) { return std::max<size_t>(1, votes >> 18); }
}  // namespace

SurroundingsIndex surroundings_index(const GaussianScene& scene, const Camera& camera, const ViewVotes& total) {
  SurroundingsIndex out;
  out.votes = total.index.size();
  out.width = camera.width;
  out.height = camera.height;
  out.grid_x = (camera.width + SurroundingsIndex::kCell - 1) / SurroundingsIndex::kCell;
  out.grid_y = (camera.height + SurroundingsIndex::kCell - 1) / SurroundingsIndex::kCell;
  const size_t cells = size_t(out.grid_x) * size_t(out.grid_y), stride = surroundings_stride(out.votes);
  std::vector<int32_t> cell_of;  // per sample, -1 where its centre is outside the image
  cell_of.reserve(out.votes / stride + 1);
  out.start.assign(cells + 1, 0);
  for (size_t k = 0; k < out.votes; k += stride) {
    double u, v;
    int32_t c = -1;
    // The same test surroundings_surface applies first, with x0 = y0 = 0 at the widest.
    if (camera.project(scene.position(total.index[k]), u, v) && u >= 0 && v >= 0 && u < camera.width &&
        v < camera.height)
      c = int32_t((int(v) / SurroundingsIndex::kCell) * out.grid_x + int(u) / SurroundingsIndex::kCell);
    cell_of.push_back(c);
    if (c >= 0) ++out.start[size_t(c) + 1];
  }
  for (size_t c = 0; c < cells; ++c) out.start[c + 1] += out.start[c];
  out.entries.resize(out.start[cells]);
  std::vector<uint32_t> fill(out.start.begin(), out.start.end() - 1);
  for (size_t s = 0; s < cell_of.size(); ++s)
    if (cell_of[s] >= 0) out.entries[fill[size_t(cell_of[s])]++] = uint32_t(s * stride);
  return out;
}

SurroundingsSurface surroundings_surface(const GaussianScene& scene, const Camera& camera, const Image& mask,
                                         const Image& depth, const Image& alpha, const ViewVotes& total,
                                         double near_limit, const BackgroundOptions& o, int threads,
                                         const SurroundingsIndex* index) {
  const int w = mask.width, h = mask.height;
  const size_t npx = size_t(w) * size_t(h);
  if (o.spread_scale <= 0 || w == 0 || h == 0 || depth.data.size() != npx || alpha.data.size() != npx)
    return {};
  const MaskBounds m = mask_bounds(mask);
  const int bx0 = m.x0, by0 = m.y0, bx1 = m.x1, by1 = m.y1;
  if (bx1 < 0) return {};
  // The ring the line estimates sample: past the `skip` pixels whose depth blends both
  // sides, out to where a sample's continuation is checked.
  const int inner = std::max(0, o.skip), outer = inner + 2 * std::max(1, o.extent);
  const int x0 = std::max(0, bx0 - outer), y0 = std::max(0, by0 - outer);
  const int x1 = std::min(w - 1, bx1 + outer), y1 = std::min(h - 1, by1 + outer);
  const int bw = x1 - x0 + 1;
  const std::vector<uint8_t> near_mask = dilated(mask, x0, y0, x1, y1, inner);
  const std::vector<uint8_t> ring_reach = dilated(mask, x0, y0, x1, y1, outer);
  // The positions in `total` read: every stride-th, or of those the ones the index files in
  // the cells around the ring (a centre in [x0, x1 + 1) lies in a cell of [x0, x1] / kCell).
  std::vector<uint32_t> filed;
  const bool indexed = index && index->votes == total.index.size() && index->width == w && index->height == h;
  if (indexed) {
    constexpr int C = SurroundingsIndex::kCell;
    for (int cy = y0 / C; cy <= y1 / C; ++cy)
      for (int cx = x0 / C; cx <= x1 / C; ++cx) {
        const size_t c = size_t(cy) * size_t(index->grid_x) + size_t(cx);
        filed.insert(filed.end(), index->entries.begin() + index->start[c], index->entries.begin() + index->start[c + 1]);
      }
  }
  const size_t stride = surroundings_stride(total.index.size());
  const size_t n = indexed ? filed.size() : (total.index.size() + stride - 1) / stride;
  const size_t grain = list_grain(n);
  // (offset, weight) of the Gaussians centred on the ring, per chunk, then sorted: the
  // order they are found in does not matter.
  const size_t chunks = chunk_count(n, grain);
  std::vector<std::vector<std::pair<double, double>>> found(chunks);
  parallel_chunks(n, grain, threads, [&](size_t chunk, size_t begin, size_t end) {
    std::vector<std::pair<double, double>> out;  // moved in at the end: the chunks' vectors share cache lines
    for (size_t s = begin; s < end; ++s) {
      // The filed samples read the list at random, and their centres through it: the list's
      // entry kPrefetchAhead samples on, and the centre of the one half as far on.
      if (indexed && s + kPrefetchAhead < n) __builtin_prefetch(&total.index[filed[s + kPrefetchAhead]]);
      if (s + kPrefetchAhead / 2 < n) {
        const size_t ka = indexed ? filed[s + kPrefetchAhead / 2] : (s + kPrefetchAhead / 2) * stride;
        __builtin_prefetch(scene.positions.data() + 3 * size_t(total.index[ka]));
        __builtin_prefetch(&total.weight[ka]);
      }
      const size_t k = indexed ? filed[s] : s * stride;
      double u, v, cz;
      if (!camera.project(scene.position(total.index[k]), u, v, &cz)) continue;
      if (!(u >= x0 && v >= y0 && u < x1 + 1 && v < y1 + 1)) continue;
      const int px = int(u), py = int(v);
      const size_t b = size_t(py - y0) * size_t(bw) + size_t(px - x0);
      if (near_mask[b] || !ring_reach[b]) continue;
      const size_t p = size_t(py) * size_t(w) + size_t(px);
      const double z = depth.data[p];
      if (!(alpha.data[p] > 0.5f) || !(z > 0) || z < near_limit) continue;
      out.push_back({z / cz - 1, double(total.weight[k])});  // (1/cz) / (1/z) - 1
    }
    found[chunk] = std::move(out);
  });
  std::vector<std::pair<double, double>> all;
  for (auto& f : found) all.insert(all.end(), f.begin(), f.end());
  if (int(all.size()) < std::max(1, o.min_spread_samples)) return {};
  std::sort(all.begin(), all.end());
  SurroundingsSurface out;
  out.offset = weighted_quantile(all, 0.5);
  out.tolerance = std::clamp(o.spread_scale * (weighted_quantile(all, 0.75) - weighted_quantile(all, 0.25)),
                             std::min(o.min_tolerance, o.tolerance), o.tolerance);
  return out;
}

namespace {
// How far pixel (u, v) lies from the nearest click, per axis (the larger of |du| and |dv|):
// it lies within a radius r of a click when this is <= r. Infinite without clicks.
double distance_to_seeds(const BackgroundTarget& target, double u, double v) {
  double d = std::numeric_limits<double>::infinity();
  for (const BackgroundTarget::Seed& seed : target.seeds)
    d = std::min(d, std::max(std::abs(u - seed.x), std::abs(v - seed.y)));
  return d;
}

// Whether a click's rendered depth lies on or behind the surroundings' rendered surface at
// its pixel (both as rendered, so no offset between them): a coarse pillar running from the
// floor to the ceiling around it, clicked where no Gaussian is centred near the click.
bool clicked_pixel_in_or_behind(const BackgroundTarget& target, const Image& background, double tolerance) {
  for (const BackgroundTarget::Seed& seed : target.seeds) {
    const int x = int(seed.x), y = int(seed.y);
    if (seed.depth <= 0 || x < 0 || y < 0 || x >= background.width || y >= background.height) continue;
    const float bg = background.at(x, y);
    if (bg > 0 && (1.0 / seed.depth) / bg - 1 <= tolerance) return true;
  }
  return false;
}
}  // namespace

size_t gate_background(const GaussianScene& scene, const Camera& camera, const Image& background,
                       const BackgroundTarget& target, ViewVotes& positive, ViewVotes& neutral,
                       const BackgroundOptions& o, int threads, const SurroundingsSurface& surface) {
  // Each Gaussian's centre against the surface estimate at its pixel: its inverse depth
  // relative to the surface's, minus 1 (> 0: in front of it; NaN: no estimate there).
  // Per Gaussian and independent, so in parallel chunks (the two passes below).
  const size_t n = positive.index.size();
  const size_t grain = list_grain(n);
  std::vector<double> offset(n, std::nan(""));
  std::vector<int32_t> pixel(2 * n, -1);  // where the centre projects
  std::vector<double> seed_distance(n, std::numeric_limits<double>::infinity());  // distance_to_seeds
  std::vector<uint8_t> at_seed(n, 0);
  parallel_chunks(n, grain, threads, [&](size_t, size_t begin, size_t end) {
    // In blocks: the block's centres are projected first and the estimate at their pixels
    // prefetched (a scattered list's centres fall anywhere in the view), then read.
    constexpr size_t kBlock = 32;
    double cz[kBlock];
    bool projects[kBlock];
    for (size_t b0 = begin; b0 < end; b0 += kBlock) {
      const size_t b1 = std::min(end, b0 + kBlock);
      for (size_t k = b0; k < b1; ++k) {
        prefetch_centre_ahead(scene, positive.index, k);
        double u, v;
        projects[k - b0] = camera.project(scene.position(positive.index[k]), u, v, &cz[k - b0]);
        if (!projects[k - b0]) continue;
        if (u >= 0 && v >= 0 && u < background.width && v < background.height) {
          __builtin_prefetch(&background.data[size_t(v) * size_t(background.width) + size_t(u)]);
          pixel[2 * k] = int32_t(u);
          pixel[2 * k + 1] = int32_t(v);
        }
        seed_distance[k] = distance_to_seeds(target, u, v);
        at_seed[k] = seed_distance[k] <= o.seed_radius;
      }
      for (size_t k = b0; k < b1; ++k) {
        if (!projects[k - b0] || pixel[2 * k] < 0) continue;
        const float bg = background.at(pixel[2 * k], pixel[2 * k + 1]);
        if (bg > 0) offset[k] = (1.0 / cz[k - b0]) / bg - 1 - surface.offset;
      }
    }
  });
  std::vector<std::pair<double, double>> seed_offsets;  // (offset, weight) of the clicked Gaussians
  auto clicked_offsets = [&]() {
    seed_offsets.clear();
    for (size_t k = 0; k < n; ++k)
      if (at_seed[k] && !std::isnan(offset[k])) seed_offsets.push_back({offset[k], double(positive.weight[k])});
  };
  clicked_offsets();
  // Clicked Gaussians with no estimate at their pixels (too few lines across the mask agree
  // there) say nothing of where the target lies against the surroundings, and the rest of it
  // would be judged by a tolerance no clicked Gaussian checked (a rule 4 mm proud of a bench
  // lost its ends as bench): the target is then the Gaussians nearest the clicks that have
  // one, within twice, four times ... max_seed_radius / seed_radius times the radius, and
  // where they lie in or behind the surface the view does not tell it from the surroundings.
  // With none that near, the view is judged as one without Gaussians at its clicks.
  bool widened = false;
  if (seed_offsets.empty() && std::find(at_seed.begin(), at_seed.end(), 1) != at_seed.end())
    for (double r = 2 * o.seed_radius; seed_offsets.empty() && r <= o.max_seed_radius; r *= 2) {
      for (size_t k = 0; k < n; ++k) at_seed[k] = !std::isnan(offset[k]) && seed_distance[k] <= r;
      clicked_offsets();
      widened = true;
    }
  // A target only just in front of the background (slats 6 cm before a wall 4 m away lie
  // ~0.8 % nearer in inverse depth) would count as lying on it: the tolerance shrinks to
  // half the clicked Gaussians' (weighted median) offset, when that is at least min_tolerance
  // (a target lying in the surface, a poster on a wall, is not told from it by depth at all).
  const double surroundings_tolerance = surface.tolerance >= 0 ? surface.tolerance : o.tolerance;
  double tolerance = surroundings_tolerance;
  std::sort(seed_offsets.begin(), seed_offsets.end());
  const double seed_median = seed_offsets.empty() ? std::nan("") : weighted_quantile(seed_offsets, 0.5);
  if (!seed_offsets.empty() && o.min_tolerance > 0 && o.min_tolerance < tolerance &&
      seed_median >= 2 * o.min_tolerance && seed_median <= tolerance)
    tolerance = 0.5 * seed_median;
  // "Far" behind is measured against how the surroundings' Gaussians scatter, not against a
  // tolerance narrowed to a target just in front of them.
  const double far = o.far_behind * surroundings_tolerance;
  std::vector<uint8_t> behind_surface(n, 0);
  parallel_chunks(n, grain, threads, [&](size_t, size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k)
      if (!std::isnan(offset[k]) && offset[k] <= tolerance)  // an estimate there: the centre projects in the frame
        behind_surface[k] = !crosses_surface(scene, camera, background, positive.index[k], pixel[2 * k],
                                             pixel[2 * k + 1], o.min_alignment);
  });
  // The sums per chunk, in parallel; the weights are whole numbers, so they do not depend
  // on the order.
  struct Sums {
    double selected = 0, selected_moved = 0, at_seeds = 0, at_seeds_moved = 0, moved_weight = 0, far_weight = 0;
    size_t moved = 0;
    Sums& operator+=(const Sums& o) {
      selected += o.selected, selected_moved += o.selected_moved, at_seeds += o.at_seeds;
      at_seeds_moved += o.at_seeds_moved, moved_weight += o.moved_weight, far_weight += o.far_weight;
      moved += o.moved;
      return *this;
    }
  };
  std::vector<Sums> chunk_sums(chunk_count(n, grain));
  parallel_chunks(n, grain, threads, [&](size_t chunk, size_t begin, size_t end) {
    Sums sums;  // in registers, stored at the end: the chunks' sums share cache lines
    for (size_t k = begin; k < end; ++k) {
      const bool behind = behind_surface[k];
      const double wk = double(positive.weight[k]);
      if (behind) {
        ++sums.moved;
        sums.moved_weight += wk;
        if (offset[k] < -far) sums.far_weight += wk;
      }
      if (at_seed[k]) {
        sums.at_seeds += wk;
        if (behind) sums.at_seeds_moved += wk;
      }
      if (target.selection && (*target.selection)[positive.index[k]]) {
        sums.selected += wk;
        if (behind) sums.selected_moved += wk;
      }
    }
    chunk_sums[chunk] = sums;
  });
  Sums all;
  for (const Sums& c : chunk_sums) all += c;
  const double selected = all.selected, selected_moved = all.selected_moved, at_seeds = all.at_seeds,
               at_seeds_moved = all.at_seeds_moved, moved_weight = all.moved_weight, far_weight = all.far_weight;
  const size_t moved_entries = all.moved;
  // What the target is: the Gaussians at this view's clicks when it has any (a selection
  // may already hold what an earlier view's gaps showed: the wall inside a bicycle's
  // wheels), else the selection.
  const bool by_seeds = at_seeds > 0;
  // Far behind the surface lies either what a clearly nearer target's gaps show (a fence's
  // pickets 14 % in front of it) or, where the clicked Gaussians lie near it or no Gaussian
  // is centred at the clicks, the target itself.
  const bool target_clearly_in_front = seed_median >= far;  // false for NaN
  if (moved_entries == 0 || (!target_clearly_in_front && far_weight > o.max_far_behind * moved_weight) ||
      (by_seeds && at_seeds_moved > 0.5 * at_seeds) || (widened && !seed_offsets.empty() && seed_median <= tolerance) ||
      (!by_seeds && clicked_pixel_in_or_behind(target, background, tolerance)) ||
      (!by_seeds && selected > 0 && selected_moved > 0.5 * selected))
    return 0;
  SplitWeights split = split_in_order(positive, behind_surface, threads);
  const ViewVotes& moved = split.flagged;
  // Merge into `neutral`, keeping it ascending.
  ViewVotes merged;
  size_t a = 0, b = 0;
  while (a < neutral.index.size() || b < moved.index.size()) {
    const bool take_a = b >= moved.index.size() || (a < neutral.index.size() && neutral.index[a] < moved.index[b]);
    const ViewVotes& src = take_a ? neutral : moved;
    size_t& i = take_a ? a : b;
    merged.index.push_back(src.index[i]);
    merged.weight.push_back(src.weight[i]);
    ++i;
  }
  neutral = std::move(merged);
  positive = std::move(split.rest);
  return moved_entries;
}

}  // namespace isegman::segment
