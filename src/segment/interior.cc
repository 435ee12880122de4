#include "segment/interior.h"

#include <algorithm>
#include <cmath>

namespace isegman::segment {

std::vector<int> chamfer_distance(const std::vector<uint8_t>& inside, int w, int h, bool border_outside) {
  const int inf = 1 << 28;
  std::vector<int> dist(size_t(w) * h, 0);
  for (size_t i = 0; i < dist.size(); ++i)
    if (inside[i]) dist[i] = inf;
  const int edge = border_outside ? 0 : inf;  // what lies beyond the border
  auto at = [&](int x, int y) -> int& { return dist[size_t(y) * w + x]; };
  auto get = [&](int x, int y) { return x >= 0 && y >= 0 && x < w && y < h ? at(x, y) : edge; };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      int& d = at(x, y);
      if (!d) continue;
      d = std::min({d, get(x - 1, y) + 3, get(x, y - 1) + 3, get(x - 1, y - 1) + 4, get(x + 1, y - 1) + 4});
    }
  for (int y = h - 1; y >= 0; --y)
    for (int x = w - 1; x >= 0; --x) {
      int& d = at(x, y);
      if (!d) continue;
      d = std::min({d, get(x + 1, y) + 3, get(x, y + 1) + 3, get(x + 1, y + 1) + 4, get(x - 1, y + 1) + 4});
    }
  return dist;
}

Click interior_anchor(const Image& mask, const Image& depth, const Image& alpha, const Click& click,
                      const AnchorOptions& o) {
  const int w = mask.width, h = mask.height;
  if (w <= 0 || h <= 0 || depth.width != w || depth.height != h || alpha.width != w || alpha.height != h)
    return click;
  const int cx = int(std::floor(click.x)), cy = int(std::floor(click.y));
  if (cx < 0 || cy < 0 || cx >= w || cy >= h) return click;
  const double d0 = depth.at(cx, cy);
  auto on_surface = [&](int x, int y) {
    const double d = depth.at(x, y);
    return mask.at(x, y) > 0.5f && alpha.at(x, y) >= o.min_alpha && d >= d0 * (1 - o.nearer_tolerance) &&
           d <= d0 * (1 + o.farther_tolerance);
  };
  if (!(d0 > 0) || !on_surface(cx, cy)) return click;

  // Distances matter up to the radius: a window twice as wide holds every outline pixel
  // nearer than that to a pixel the anchor may move to.
  const int r = std::max(2, int(std::lround(o.radius * w)));
  const int x0 = std::max(0, cx - 2 * r), y0 = std::max(0, cy - 2 * r);
  const int x1 = std::min(w - 1, cx + 2 * r), y1 = std::min(h - 1, cy + 2 * r);
  const int ww = x1 - x0 + 1, wh = y1 - y0 + 1;
  std::vector<uint8_t> in(size_t(ww) * wh);
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) in[size_t(y - y0) * ww + (x - x0)] = on_surface(x, y);
  // The image's border is no outline: an object leaving the frame goes on beyond it.
  const std::vector<int> dist = chamfer_distance(in, ww, wh, false);
  const int cap = 3 * r;
  auto dist_at = [&](int x, int y) { return std::min(cap, dist[size_t(y - y0) * ww + (x - x0)]); };

  // The clicked surface's pixels within the radius, connected to the click.
  std::vector<uint8_t> seen(in.size(), 0);
  std::vector<std::pair<int, int>> queue = {{cx, cy}};
  seen[size_t(cy - y0) * ww + (cx - x0)] = 1;
  int best = dist_at(cx, cy), bx = cx, by = cy;
  long best_d2 = 0;
  for (size_t q = 0; q < queue.size(); ++q) {
    const auto [x, y] = queue[q];
    const long d2 = long(x - cx) * (x - cx) + long(y - cy) * (y - cy);
    const int d = dist_at(x, y);
    if (d > best || (d == best && d2 < best_d2)) {
      best = d;
      best_d2 = d2;
      bx = x;
      by = y;
    }
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = x + dx, ny = y + dy;
        if (nx < x0 || ny < y0 || nx > x1 || ny > y1) continue;
        const size_t i = size_t(ny - y0) * ww + (nx - x0);
        if (seen[i] || !in[i] || long(nx - cx) * (nx - cx) + long(ny - cy) * (ny - cy) > long(r) * r) continue;
        seen[i] = 1;
        queue.push_back({nx, ny});
      }
  }
  if (bx == cx && by == cy) return click;
  // Continuous pixel coordinates (core/click.h): the centre of pixel i is i + 0.5.
  return {bx + 0.5, by + 0.5, click.label};
}

}  // namespace isegman::segment
