#include "segment/epipolar.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace isegman::segment {

namespace {
// Liang-Barsky clip of segment a->b to [0, w] x [0, h].
bool clip_to_rect(Point2& a, Point2& b, double w, double h) {
  double t0 = 0, t1 = 1;
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {a.x, w - a.x, a.y, h - a.y};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0) {
      if (q[i] < 0) return false;
      continue;
    }
    const double r = q[i] / p[i];
    if (p[i] < 0) t0 = std::max(t0, r);
    else t1 = std::min(t1, r);
    if (t0 > t1) return false;
  }
  Point2 na{a.x + t0 * dx, a.y + t0 * dy}, nb{a.x + t1 * dx, a.y + t1 * dy};
  a = na;
  b = nb;
  return true;
}
}  // namespace

bool epipolar_segment(const Camera& src, double u, double v, const Camera& dst, double t_min, double t_max,
                      Point2& a, Point2& b, double near_plane) {
  const Vec3 c = src.center();
  const Vec3 d = src.ray_direction(u, v);
  // In dst's camera frame the ray is q0 + t q1.
  const Vec3 q0 = dst.world_to_camera(c);
  const Vec3 q1 = dst.R * d;
  double lo = t_min, hi = t_max;
  if (std::fabs(q1.z) < 1e-12) {
    if (q0.z <= near_plane) return false;
  } else {
    const double t_near = (near_plane - q0.z) / q1.z;
    if (q1.z > 0) lo = std::max(lo, t_near);
    else hi = std::min(hi, t_near);
  }
  if (!(lo < hi)) return false;
  auto proj = [&](double t) {
    const Vec3 q = q0 + q1 * t;
    return Point2{dst.fx * q.x / q.z + dst.cx, dst.fy * q.y / q.z + dst.cy};
  };
  a = proj(lo);
  b = proj(hi);
  return clip_to_rect(a, b, dst.width, dst.height);
}

bool epipolar_line(const Camera& src, double u, double v, const Camera& dst, double line[3]) {
  Point2 a, b;
  // Two points of the ray anywhere in front of dst define the line; use a huge range.
  if (!epipolar_segment(src, u, v, dst, 1e-6, 1e9, a, b, 1e-9)) {
    // The visible part may be clipped away by the image; still compute the line.
    const Vec3 c = src.center(), d = src.ray_direction(u, v);
    double u1, v1, u2, v2;
    if (!dst.project(c + d * 1.0, u1, v1) || !dst.project(c + d * 2.0, u2, v2)) return false;
    a = {u1, v1};
    b = {u2, v2};
  }
  const double nx = a.y - b.y, ny = b.x - a.x;
  const double n = std::hypot(nx, ny);
  if (n < 1e-12) return false;
  line[0] = nx / n;
  line[1] = ny / n;
  line[2] = -(line[0] * a.x + line[1] * a.y);
  return true;
}

std::vector<std::pair<int, int>> grid_cells_on_segment(Point2 a, Point2 b, int w, int h) {
  std::vector<std::pair<int, int>> cells;
  int cx = int(std::floor(a.x)), cy = int(std::floor(a.y));
  const int ex = int(std::floor(b.x)), ey = int(std::floor(b.y));
  const double dx = b.x - a.x, dy = b.y - a.y;
  const int sx = dx > 0 ? 1 : (dx < 0 ? -1 : 0), sy = dy > 0 ? 1 : (dy < 0 ? -1 : 0);
  // Parametric distance to the next vertical / horizontal grid line, and per cell.
  const double inf = std::numeric_limits<double>::infinity();
  double t_max_x = sx > 0 ? (cx + 1 - a.x) / dx : (sx < 0 ? (a.x - cx) / -dx : inf);
  double t_max_y = sy > 0 ? (cy + 1 - a.y) / dy : (sy < 0 ? (a.y - cy) / -dy : inf);
  const double t_dx = sx != 0 ? 1.0 / std::fabs(dx) : inf, t_dy = sy != 0 ? 1.0 / std::fabs(dy) : inf;
  const size_t limit = size_t(std::abs(ex - cx) + std::abs(ey - cy)) + 2;
  for (size_t step = 0; step < limit; ++step) {
    if (cx >= 0 && cy >= 0 && cx < w && cy < h) cells.emplace_back(cx, cy);
    if (cx == ex && cy == ey) break;
    if (t_max_x < t_max_y) {
      cx += sx;
      t_max_x += t_dx;
    } else if (t_max_y < t_max_x) {
      cy += sy;
      t_max_y += t_dy;
    } else {  // through a corner: both neighbours are touched, include them
      if (cx + sx >= 0 && cy >= 0 && cx + sx < w && cy < h) cells.emplace_back(cx + sx, cy);
      cx += sx;
      cy += sy;
      t_max_x += t_dx;
      t_max_y += t_dy;
    }
  }
  return cells;
}

}  // namespace isegman::segment
