#include "segment/see_through.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <utility>

#include "core/parallel.h"
#include "segment/whole_islands.h"

namespace isegman::segment {

namespace {

class FirstSurface : public ContributionVisitor {
 public:
  // `probe`: a pixel (y * width + x) whose contributions up to its surface are kept.
  FirstSurface(const GaussianScene& scene, const Camera& camera, Image& out, int64_t probe = -1)
      : scene_(scene), camera_(camera), out_(out), accumulated_(size_t(out.width) * out.height, 0.f), probe_(probe) {}
  void visit(int, int x, int y, uint32_t g, float weight) override {
    const size_t i = size_t(y) * out_.width + x;
    float& a = accumulated_[i];
    if (a >= 0.5f) return;
    a += weight;
    const bool probed = int64_t(i) == probe_;
    if (!probed && a < 0.5f) return;
    const Vec3 p{scene_.positions[3 * g], scene_.positions[3 * g + 1], scene_.positions[3 * g + 2]};
    const float z = float(camera_.world_to_camera(p).z);
    if (probed) probed_.push_back({z, weight});
    if (a >= 0.5f) out_.at(x, y) = z;
  }
  // The probed pixel's (depth, weight) contributions in blending order, up to its surface.
  const std::vector<std::pair<float, float>>& probed() const { return probed_; }

 private:
  const GaussianScene& scene_;
  const Camera& camera_;
  Image& out_;
  std::vector<float> accumulated_;  // each pixel is visited by one worker only (its tile's)
  int64_t probe_;
  std::vector<std::pair<float, float>> probed_;
};

}  // namespace

Occluders find_occluders(const GaussianScene& scene, const PreparedFrame& frame, double x, double y,
                         const SeeThroughOptions& o, int threads) {
  Occluders out;
  const int w = frame.camera.width, h = frame.camera.height;
  const int cx = std::clamp(int(std::floor(x)), 0, w - 1), cy = std::clamp(int(std::floor(y)), 0, h - 1);
  const int longer = std::max(w, h);
  const int r = std::max(4, int(std::lround(o.window * longer)));
  const int flank = std::max(2, int(std::lround(o.flank * longer)));
  // Only the tiles of the window (and its flanks) are rasterised.
  const int x0 = std::max(0, cx - r - flank), x1 = std::min(w - 1, cx + r + flank);
  const int y0 = std::max(0, cy - r - flank), y1 = std::min(h - 1, cy + r + flank);
  std::vector<uint8_t> tiles(size_t(frame.grid_x) * frame.grid_y, 0);
  for (int ty = y0 / kTileSize; ty <= y1 / kTileSize && ty < frame.grid_y; ++ty)
    for (int tx = x0 / kTileSize; tx <= x1 / kTileSize && tx < frame.grid_x; ++tx) tiles[size_t(ty) * frame.grid_x + tx] = 1;
  Image z(w, h, 1);
  FirstSurface visitor(scene, frame.camera, z, int64_t(cy) * w + cx);
  RenderSettings rs;
  rs.color = rs.depth = false;
  rs.threads = threads;
  rasterize(frame, rs, nullptr, &visitor, &tiles);
  const double d0 = z.at(cx, cy);
  if (!(d0 > 0)) return out;  // nothing solid clicked
  out.surface = d0;
  const double front = d0 * (1 - o.gap), back = d0 * (1 + o.band);
  for (const auto& [depth, weight] : visitor.probed()) out.click_front_weight += depth < front ? weight : 0.f;
  auto is_surface = [&](int xx, int yy) {
    const float v = z.at(xx, yy);
    return v >= front && v <= back;
  };
  // The clicked surface within `flank` pixels on both sides along (dx, dy).
  auto flanked = [&](int xx, int yy, int dx, int dy) {
    bool a = false, b = false;
    for (int s = 1; s <= flank && !a; ++s) {
      const int px = xx - s * dx, py = yy - s * dy;
      if (px < 0 || py < 0 || px >= w || py >= h) break;
      a = is_surface(px, py);
    }
    for (int s = 1; s <= flank && !b; ++s) {
      const int px = xx + s * dx, py = yy + s * dy;
      if (px < 0 || py < 0 || px >= w || py >= h) break;
      b = is_surface(px, py);
    }
    return a && b;
  };
  int pixels = 0;
  std::vector<std::pair<float, uint32_t>> flanked_pixels;  // (surface depth, y * width + x)
  for (int yy = std::max(0, cy - r); yy <= std::min(h - 1, cy + r); ++yy)
    for (int xx = std::max(0, cx - r); xx <= std::min(w - 1, cx + r); ++xx) {
      const float v = z.at(xx, yy);
      if (!(v > 0)) continue;
      ++pixels;
      if (v >= front) continue;
      if (flanked(xx, yy, 1, 0) || flanked(xx, yy, 0, 1))
        flanked_pixels.push_back({v, uint32_t(yy) * uint32_t(w) + uint32_t(xx)});
    }
  // The occluders end at the widest relative depth gap among the flanked pixels and the
  // clicked surface, one leaving at least min_share of the window's pixels in front: beyond
  // a wider gap than the one to the surface, flanked pixels are the clicked surface's own
  // nearer parts (a coarse pillar's Gaussians scattered a few per cent in depth, crossed by
  // fronds far in front of it), not occluders.
  std::sort(flanked_pixels.begin(), flanked_pixels.end());
  const size_t n = flanked_pixels.size();
  const size_t min_count = std::max<size_t>(1, size_t(std::ceil(o.min_share * pixels)));
  size_t occluding = n;
  if (n > 0) {
    double widest = (d0 - flanked_pixels[n - 1].first) / d0;
    for (size_t k = min_count; k < n; ++k) {
      const double gap = double(flanked_pixels[k].first - flanked_pixels[k - 1].first) / flanked_pixels[k].first;
      if (gap > widest) {
        widest = gap;
        occluding = k;
      }
    }
  }
  const double nearest_behind = occluding > 0 ? flanked_pixels[occluding - 1].first : 0;  // the deepest occluder
  const double surface_front = occluding < n ? double(flanked_pixels[occluding].first) : d0;
  for (size_t k = 0; k < occluding; ++k) out.pixels.push_back(flanked_pixels[k].second);
  out.share = pixels ? double(occluding) / pixels : 0.0;
  if (out.share < o.min_share) return out;
  // The clicked pixel itself gives much of its weight to something nearer: it is no clear
  // gap. On a coarse surface of few large Gaussians (a far pillar in a real capture) the
  // surface's own nearer Gaussians do so, and they are flanked by its farther ones: a cut
  // among them would peel the clicked object's front away.
  if (out.click_front_weight > o.max_click_front_weight) return out;
  // Just behind the occluders (whose Gaussians have some thickness), well before the
  // clicked surface, so the object's own nearer parts stay.
  out.cut = nearest_behind + 0.3 * (surface_front - nearest_behind);
  out.found = true;
  return out;
}

double enclosure_contact(const GaussianScene& scene, const CentreIndex& index, const Camera& camera,
                         const std::vector<uint32_t>& shown, const Occluders& occ, double x, double y,
                         const SeeThroughOptions& o, int threads) {
  std::vector<bool> nearer(scene.size(), false);
  std::vector<uint32_t> there;
  const double reach = o.window * std::max(camera.width, camera.height);
  for (uint32_t j : shown) {
    const Vec3 p = scene.position(j);
    const double z = camera.world_to_camera(p).z;
    if (z < occ.cut) {
      nearer[j] = true;
      continue;
    }
    double u = 0, v = 0;
    if (z <= occ.surface * (1 + o.band) && camera.project(p, u, v) && std::hypot(u - x, v - y) <= reach)
      there.push_back(j);
  }
  if (there.empty()) return 0.0;
  const TouchingGaussians touching(scene, index, nearer, o.link_sigmas, threads);
  std::atomic<size_t> touched{0};
  parallel_chunks(there.size(), 256, threads, [&](size_t, size_t begin, size_t end) {
    size_t n = 0;
    for (size_t i = begin; i < end; ++i) {
      bool any = false;
      touching.for_each(there[i], [&](uint32_t) { any = true; });
      n += any;
    }
    touched += n;
  });
  return double(touched) / double(there.size());
}

}  // namespace isegman::segment
