#include "segment/view_selection.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "core/error.h"

namespace isegman::segment {

bool parse_auto_views(const std::string& spec, int& k) {
  if (spec == "auto") {
    k = kDefaultVotingViews;
    return true;
  }
  if (spec.rfind("auto:", 0) != 0) return false;
  const std::string n = spec.substr(5);
  char* end = nullptr;
  const long v = n.empty() ? 0 : std::strtol(n.c_str(), &end, 10);
  if (n.empty() || end != n.c_str() + n.size() || v < 1 || v > 100000)
    throw Error("--views: '" + spec + "' needs a view count >= 1 (auto:K)");
  k = int(v);
  return true;
}

namespace {

// Whether `p` projects inside the camera's frame, in front of it (at pixel (u, v)).
bool in_frame(const Camera& c, const Vec3& p, double& u, double& v) {
  double z = 0;
  return c.project(p, u, v, &z) && z > 0 && u >= 0 && v >= 0 && u < c.width && v < c.height;
}

}  // namespace

std::vector<ViewCandidate> score_views(const std::vector<Camera>& cameras, int clicked, const Vec3& point) {
  std::vector<ViewCandidate> out(cameras.size());
  double d0 = 0;
  if (clicked >= 0 && clicked < int(cameras.size())) d0 = norm(cameras[size_t(clicked)].center() - point);
  for (size_t i = 0; i < cameras.size(); ++i) {
    const Camera& c = cameras[i];
    ViewCandidate& v = out[i];
    v.camera = int(i);
    const Vec3 to_cam = c.center() - point;
    v.distance = norm(to_cam);
    v.direction = normalized(to_cam);
    double u = 0, w = 0;
    if (!(v.distance > 0) || !in_frame(c, point, u, w)) continue;
    v.sees = true;
    // Resolution on the target: a camera much nearer or farther than the clicked one
    // sees it at another scale (SAM and the voting prefer similar footprints).
    const double ratio = d0 > 0 ? std::max(v.distance / d0, d0 / v.distance) : 1.0;
    // Centrality: a point near the frame border may leave most of the object outside.
    const double ex = std::abs(u - 0.5 * c.width) / (0.5 * c.width);
    const double ey = std::abs(w - 0.5 * c.height) / (0.5 * c.height);
    v.quality = (1.0 / ratio) * (1.0 - 0.5 * std::min(1.0, std::max(ex, ey)));
  }
  if (clicked >= 0 && clicked < int(out.size())) {
    out[size_t(clicked)].sees = true;  // the click is in it, whatever the rounding
    out[size_t(clicked)].quality = std::max(out[size_t(clicked)].quality, 1e-3);
  }
  return out;
}

namespace {

double angle(const Vec3& a, const Vec3& b) { return std::acos(std::clamp(dot(a, b), -1.0, 1.0)); }

// Greedy farthest-point sampling: `first` in, then repeatedly the candidate with the
// largest weight * distance-to-nearest-chosen. dist(i, j) and weight(i) over `pool`.
template <typename Dist, typename Weight>
std::vector<int> farthest_points(const std::vector<int>& pool, int first, int k, Dist dist, Weight weight) {
  std::vector<int> chosen;
  if (pool.empty() || k <= 0) return chosen;
  std::vector<double> nearest(pool.size(), std::numeric_limits<double>::infinity());
  std::vector<bool> taken(pool.size(), false);
  size_t pick = 0;
  for (size_t i = 0; i < pool.size(); ++i)
    if (pool[i] == first) pick = i;
  while (true) {
    taken[pick] = true;
    chosen.push_back(pool[pick]);
    if (int(chosen.size()) >= k) break;
    double best = -1;
    size_t next = pool.size();
    for (size_t i = 0; i < pool.size(); ++i) {
      if (taken[i]) continue;
      nearest[i] = std::min(nearest[i], dist(pool[pick], pool[i]));
      const double s = weight(pool[i]) * nearest[i];
      if (s > best) best = s, next = i;  // ties: the lowest index
    }
    if (next == pool.size()) break;
    pick = next;
  }
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

}  // namespace

namespace {

std::vector<int> spread_over(const std::vector<ViewCandidate>& cand, int clicked, int k) {
  std::vector<int> pool;
  for (const ViewCandidate& c : cand)
    if (c.sees) pool.push_back(c.camera);
  // A floor on the weight keeps a poor but far-off view from losing to a good duplicate.
  return farthest_points(
      pool, clicked, k,
      [&](int a, int b) { return angle(cand[size_t(a)].direction, cand[size_t(b)].direction); },
      [&](int i) { return 0.25 + 0.75 * cand[size_t(i)].quality; });
}

}  // namespace

std::vector<int> select_views_for_point(const std::vector<Camera>& cameras, int clicked, const Vec3& point, int k) {
  if (clicked < 0 || clicked >= int(cameras.size())) throw Error("view selection: no clicked camera");
  return spread_over(score_views(cameras, clicked, point), clicked, k);
}

void weigh_by_object(std::vector<ViewCandidate>& candidates, const std::vector<Camera>& cameras, int clicked,
                     const std::vector<Vec3>& samples, const LineOpen& open, double min_seen) {
  if (samples.empty()) return;
  Vec3 centre{0, 0, 0};
  for (const Vec3& p : samples) centre += p;
  centre = centre * (1.0 / double(samples.size()));
  double radius = 0;
  for (const Vec3& p : samples) radius = std::max(radius, norm(p - centre));
  radius *= 1.1;
  for (ViewCandidate& c : candidates) {
    if (!c.sees || c.camera == clicked) continue;
    const Camera& cam = cameras[size_t(c.camera)];
    const Vec3 eye = cam.center();
    double seen = 0;
    for (const Vec3& p : samples) {
      double u = 0, v = 0;
      if (!in_frame(cam, p, u, v)) continue;
      // The line of sight up to where it enters the object's sphere.
      const Vec3 d = p - eye;
      const double len = norm(d);
      if (!(len > 0)) continue;
      const Vec3 dir = d * (1.0 / len);
      const Vec3 oc = eye - centre;
      const double b = dot(oc, dir), cc = dot(oc, oc) - radius * radius;
      const double disc = b * b - cc;
      double enter = len;
      if (cc <= 0) enter = 0;  // the camera is inside the sphere: nothing between
      else if (disc > 0) enter = std::min(len, -b - std::sqrt(disc));
      seen += enter > 0 ? open(eye, eye + dir * enter) : 1.0;
    }
    seen /= double(samples.size());
    if (seen < min_seen) c.sees = false;
    c.quality *= seen;
  }
}

std::vector<int> select_views_for_object(const std::vector<Camera>& cameras, int clicked, const Vec3& point,
                                         const std::vector<Vec3>& samples, const LineOpen& open, int k) {
  if (clicked < 0 || clicked >= int(cameras.size())) throw Error("view selection: no clicked camera");
  std::vector<ViewCandidate> cand = score_views(cameras, clicked, point);
  weigh_by_object(cand, cameras, clicked, samples, open);
  return spread_over(cand, clicked, k);
}

std::vector<int> spread_views(const std::vector<Camera>& cameras, int clicked, int k) {
  std::vector<int> pool(cameras.size());
  for (size_t i = 0; i < pool.size(); ++i) pool[i] = int(i);
  std::vector<Vec3> centres(cameras.size());
  for (size_t i = 0; i < cameras.size(); ++i) centres[i] = cameras[i].center();
  const int first = clicked >= 0 && clicked < int(cameras.size()) ? clicked : 0;
  return farthest_points(
      pool, first, k, [&](int a, int b) { return norm(centres[size_t(a)] - centres[size_t(b)]); },
      [](int) { return 1.0; });
}

}  // namespace isegman::segment
