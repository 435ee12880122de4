#include "edit/screen_selection.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>

#include "core/error.h"

namespace isegman::edit {

namespace {

constexpr size_t kMaxPoints = 100000;
constexpr double kCoordLimit = 1e6;

uint32_t float_bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

// The largest blending weight of each Gaussian over the region's pixels. Weights are
// positive floats, whose bit patterns order like the values, so an atomic max on the
// bits is safe across the rasteriser's worker threads.
class RegionWeights : public ContributionVisitor {
 public:
  RegionWeights(const PixelRegion& region, size_t gaussians) : region_(region), best_(gaussians) {
    for (auto& b : best_) b.store(0, std::memory_order_relaxed);
  }
  void visit(int, int x, int y, uint32_t g, float w) override {
    if (!region_.contains(x, y) || !(w > 0)) return;
    const uint32_t bits = float_bits(w);
    uint32_t cur = best_[g].load(std::memory_order_relaxed);
    while (bits > cur && !best_[g].compare_exchange_weak(cur, bits, std::memory_order_relaxed)) {
    }
  }
  float best(size_t g) const {
    const uint32_t bits = best_[g].load(std::memory_order_relaxed);
    float f;
    std::memcpy(&f, &bits, 4);
    return f;
  }

 private:
  const PixelRegion& region_;
  std::vector<std::atomic<uint32_t>> best_;
};

// The Gaussian with the largest weight at one pixel (one tile: one worker thread).
class PixelArgmax : public ContributionVisitor {
 public:
  PixelArgmax(int x, int y) : x_(x), y_(y) {}
  void visit(int, int x, int y, uint32_t g, float w) override {
    if (x != x_ || y != y_) return;
    if (w > weight || (w == weight && int64_t(g) < gaussian)) {
      weight = w;
      gaussian = g;
    }
  }
  float weight = 0;
  int64_t gaussian = -1;

 private:
  int x_, y_;
};

std::vector<uint8_t> tiles_of(const PixelRegion& region, int grid_x, int grid_y) {
  std::vector<uint8_t> tiles(size_t(grid_x) * size_t(grid_y), 0);
  for (int y = 0; y < region.height; ++y)
    for (int x = 0; x < region.width; ++x)
      if (region.inside[size_t(y) * size_t(region.width) + size_t(x)])
        tiles[size_t(y / kTileSize) * size_t(grid_x) + size_t(x / kTileSize)] = 1;
  return tiles;
}

void fill_rect(PixelRegion& r, double x0, double y0, double x1, double y1) {
  if (x0 > x1) std::swap(x0, x1);
  if (y0 > y1) std::swap(y0, y1);
  // Pixel i is in when x0 <= i + 0.5 <= x1.
  const int i0 = std::max(0, int(std::ceil(x0 - 0.5))), i1 = std::min(r.width - 1, int(std::floor(x1 - 0.5)));
  const int j0 = std::max(0, int(std::ceil(y0 - 0.5))), j1 = std::min(r.height - 1, int(std::floor(y1 - 0.5)));
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) r.inside[size_t(j) * size_t(r.width) + size_t(i)] = 1;
}

void fill_polygon(PixelRegion& r, const std::vector<Point2>& p) {
  std::vector<double> xs;
  for (int j = 0; j < r.height; ++j) {
    const double cy = j + 0.5;
    xs.clear();
    for (size_t a = 0; a < p.size(); ++a) {
      const Point2& u = p[a];
      const Point2& v = p[(a + 1) % p.size()];
      if ((u.y <= cy) != (v.y <= cy)) xs.push_back(u.x + (cy - u.y) / (v.y - u.y) * (v.x - u.x));
    }
    std::sort(xs.begin(), xs.end());
    for (size_t k = 0; k + 1 < xs.size(); k += 2) {
      // Pixel centres with xs[k] <= i + 0.5 < xs[k + 1] (even-odd rule).
      const int i0 = std::max(0, int(std::ceil(xs[k] - 0.5)));
      const int i1 = std::min(r.width - 1, int(std::ceil(xs[k + 1] - 0.5)) - 1);
      for (int i = i0; i <= i1; ++i) r.inside[size_t(j) * size_t(r.width) + size_t(i)] = 1;
    }
  }
}

void fill_capsule(PixelRegion& r, const Point2& a, const Point2& b, double radius) {
  const int i0 = std::max(0, int(std::floor(std::min(a.x, b.x) - radius)));
  const int i1 = std::min(r.width - 1, int(std::ceil(std::max(a.x, b.x) + radius)));
  const int j0 = std::max(0, int(std::floor(std::min(a.y, b.y) - radius)));
  const int j1 = std::min(r.height - 1, int(std::ceil(std::max(a.y, b.y) + radius)));
  const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy, r2 = radius * radius;
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const double px = i + 0.5 - a.x, py = j + 0.5 - a.y;
      const double t = len2 > 0 ? std::clamp((px * dx + py * dy) / len2, 0.0, 1.0) : 0.0;
      const double ex = px - t * dx, ey = py - t * dy;
      if (ex * ex + ey * ey <= r2) r.inside[size_t(j) * size_t(r.width) + size_t(i)] = 1;
    }
}

}  // namespace

ShapeKind parse_shape_kind(const std::string& text) {
  if (text == "rect") return ShapeKind::kRect;
  if (text == "lasso") return ShapeKind::kLasso;
  if (text == "brush") return ShapeKind::kBrush;
  throw Error("shape", "expected rect, lasso or brush, got '" + text.substr(0, 40) + "'");
}

const char* shape_kind_name(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::kRect: return "rect";
    case ShapeKind::kLasso: return "lasso";
    case ShapeKind::kBrush: return "brush";
  }
  return "?";
}

void check_shape(const ScreenShape& s) {
  const std::string name = shape_kind_name(s.kind);
  const size_t n = s.points.size();
  if (n > kMaxPoints) throw Error(name, "points: more than " + std::to_string(kMaxPoints));
  if (s.kind == ShapeKind::kRect && n != 2) throw Error(name, "points: a rectangle takes two corners");
  if (s.kind == ShapeKind::kLasso && n < 3) throw Error(name, "points: a lasso needs at least three points");
  if (s.kind == ShapeKind::kBrush && n < 1) throw Error(name, "points: a brush stroke needs at least one point");
  for (const Point2& p : s.points)
    if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::fabs(p.x) <= kCoordLimit && std::fabs(p.y) <= kCoordLimit))
      throw Error(name, "points: coordinates must be finite and within +-1e6 pixels");
  if (s.kind == ShapeKind::kBrush && !(std::isfinite(s.radius) && s.radius > 0 && s.radius <= 1e5))
    throw Error(name, "radius: must be in (0, 1e5] pixels");
}

size_t PixelRegion::count() const { return size_t(std::count(inside.begin(), inside.end(), uint8_t(1))); }

PixelRegion rasterize_shape(const ScreenShape& shape, int full_width, int full_height, int width, int height) {
  check_shape(shape);
  if (full_width <= 0 || full_height <= 0 || width <= 0 || height <= 0)
    throw Error(shape_kind_name(shape.kind), "the image has no pixels");
  PixelRegion r;
  r.width = width;
  r.height = height;
  r.inside.assign(size_t(width) * size_t(height), 0);
  const double sx = double(width) / full_width, sy = double(height) / full_height;
  std::vector<Point2> p;
  for (const Point2& q : shape.points) p.push_back({q.x * sx, q.y * sy});
  switch (shape.kind) {
    case ShapeKind::kRect: fill_rect(r, p[0].x, p[0].y, p[1].x, p[1].y); break;
    case ShapeKind::kLasso: fill_polygon(r, p); break;
    case ShapeKind::kBrush: {
      const double radius = shape.radius * 0.5 * (sx + sy);
      if (p.size() == 1) fill_capsule(r, p[0], p[0], radius);
      for (size_t k = 0; k + 1 < p.size(); ++k) fill_capsule(r, p[k], p[k + 1], radius);
      break;
    }
  }
  return r;
}

Selection select_in_shape(const GaussianScene& scene, const Camera& camera, const ScreenShape& shape,
                          const ScreenSelectOptions& o) {
  const std::string name = std::string(shape_kind_name(shape.kind)) + " selection";
  if (!(std::isfinite(o.min_weight) && o.min_weight >= 0 && o.min_weight <= 1))
    throw Error(name, "minimum weight must be in [0, 1]");
  const PixelRegion full = rasterize_shape(shape, camera.width, camera.height, camera.width, camera.height);
  std::vector<bool> m(scene.size(), false);
  bool any = false;
  for (size_t i = 0; i < scene.size(); ++i) {
    const Vec3 pc = camera.world_to_camera(scene.position(i));
    if (!(pc.z > o.render.near_plane)) continue;
    double u, v;
    camera.project_camera_point(pc, u, v);
    if (!(u >= 0 && v >= 0 && u < camera.width && v < camera.height)) continue;
    if (full.contains(int(u), int(v))) m[i] = any = true;
  }
  if (o.visible_only && any) {
    Camera work = camera;
    const int longest = std::max(camera.width, camera.height);
    if (o.max_side > 0 && longest > o.max_side) {
      const double s = double(o.max_side) / longest;
      work = camera.resized(std::max(1, int(std::lround(camera.width * s))),
                            std::max(1, int(std::lround(camera.height * s))));
    }
    const PixelRegion region = rasterize_shape(shape, camera.width, camera.height, work.width, work.height);
    RenderSettings rs = o.render;
    rs.color = false;
    rs.depth = false;
    const PreparedFrame frame = prepare_frame(scene, work, rs);
    const std::vector<uint8_t> tiles = tiles_of(region, frame.grid_x, frame.grid_y);
    RegionWeights weights(region, scene.size());
    rasterize(frame, rs, nullptr, &weights, &tiles);
    for (size_t i = 0; i < m.size(); ++i)
      if (m[i] && !(weights.best(i) >= o.min_weight)) m[i] = false;
  }
  return Selection::from_mask(scene, std::move(m));
}

int64_t gaussian_at(const GaussianScene& scene, const Camera& camera, double u, double v,
                    const RenderSettings& settings) {
  if (!(std::isfinite(u) && std::isfinite(v) && u >= 0 && v >= 0 && u < camera.width && v < camera.height))
    throw Error("eyedropper", "x, y: must lie in the camera's image, [0, " + std::to_string(camera.width) + ") x [0, " +
                                  std::to_string(camera.height) + ")");
  const int x = int(u), y = int(v);
  RenderSettings rs = settings;
  rs.color = false;
  rs.depth = false;
  const PreparedFrame frame = prepare_frame(scene, camera, rs);
  std::vector<uint8_t> tiles(size_t(frame.grid_x) * size_t(frame.grid_y), 0);
  tiles[size_t(y / kTileSize) * size_t(frame.grid_x) + size_t(x / kTileSize)] = 1;
  PixelArgmax best(x, y);
  rasterize(frame, rs, nullptr, &best, &tiles);
  return best.gaussian;
}

}  // namespace isegman::edit
