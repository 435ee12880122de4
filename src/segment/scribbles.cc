#include "segment/scribbles.h"

#include <cmath>
#include <limits>

namespace isegman::segment {

std::vector<Click> clicks_from_scribble(const Image& scribble, int count, int label) {
  std::vector<std::pair<int, int>> px;
  for (int y = 0; y < scribble.height; ++y)
    for (int x = 0; x < scribble.width; ++x) {
      bool on = false;
      for (int c = 0; c < scribble.channels; ++c) on |= scribble.at(x, y, c) > 0.f;
      if (on) px.emplace_back(x, y);
    }
  std::vector<Click> out;
  if (px.empty() || count <= 0) return out;
  double mx = 0, my = 0;
  for (auto& [x, y] : px) {
    mx += x;
    my += y;
  }
  mx /= double(px.size());
  my /= double(px.size());
  std::vector<double> dist(px.size(), std::numeric_limits<double>::infinity());
  size_t pick = 0;
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < px.size(); ++i) {
    const double d = std::hypot(px[i].first - mx, px[i].second - my);
    if (d < best) {
      best = d;
      pick = i;
    }
  }
  while (int(out.size()) < count) {
    out.push_back(pixel_centre_click(px[pick].first, px[pick].second, label));
    size_t next = 0;
    double far = -1;
    for (size_t i = 0; i < px.size(); ++i) {
      dist[i] = std::min(dist[i], std::hypot(double(px[i].first - px[pick].first), double(px[i].second - px[pick].second)));
      if (dist[i] > far) {
        far = dist[i];
        next = i;
      }
    }
    if (far <= 0) break;  // every scribble pixel is already a click
    pick = next;
  }
  return out;
}

}  // namespace isegman::segment
