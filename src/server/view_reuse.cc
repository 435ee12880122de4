#include "server/view_reuse.h"

#include <algorithm>
#include <cstring>

#include "render/projection.h"
#include "segment/votes.h"

namespace isegman::server {

namespace {

// The parameters a render reads of Gaussian i, as bytes to hash and compare.
struct Record {
  const GaussianScene* scene;
  size_t index;
  uint64_t hash;
};

template <typename F>
void for_each_field(const GaussianScene& g, size_t i, F f) {
  f(&g.positions[3 * i], 3 * sizeof(float));
  f(&g.opacity[i], sizeof(float));
  f(&g.scales[3 * i], 3 * sizeof(float));
  f(&g.rotations[4 * i], 4 * sizeof(float));
  f(g.sh_of(i), size_t(g.coeffs()) * 3 * sizeof(float));
}

uint64_t hash_of(const GaussianScene& g, size_t i) {
  uint64_t h = 1469598103934665603ull;
  for_each_field(g, i, [&](const void* p, size_t n) {
    const auto* b = static_cast<const uint8_t*>(p);
    for (size_t k = 0; k < n; ++k) h = (h ^ b[k]) * 1099511628211ull;
  });
  return h;
}

bool same(const GaussianScene& a, size_t i, const GaussianScene& b, size_t j) {
  const float* fa[5] = {&a.positions[3 * i], &a.opacity[i], &a.scales[3 * i], &a.rotations[4 * i], a.sh_of(i)};
  const float* fb[5] = {&b.positions[3 * j], &b.opacity[j], &b.scales[3 * j], &b.rotations[4 * j], b.sh_of(j)};
  const size_t n[5] = {3, 1, 3, 4, size_t(a.coeffs()) * 3};
  for (int k = 0; k < 5; ++k)
    if (std::memcmp(fa[k], fb[k], n[k] * sizeof(float)) != 0) return false;
  return true;
}

std::vector<Record> records(const GaussianScene& g) {
  std::vector<Record> r(g.size());
  for (size_t i = 0; i < g.size(); ++i) r[i] = {&g, i, hash_of(g, i)};
  std::sort(r.begin(), r.end(), [](const Record& x, const Record& y) {
    return x.hash < y.hash || (x.hash == y.hash && x.index < y.index);
  });
  return r;
}

}  // namespace

SceneDiff diff_scenes(const GaussianScene& before, const GaussianScene& after) {
  SceneDiff d;
  if (before.sh_degree != after.sh_degree) {
    d.everything = true;
    return d;
  }
  const std::vector<Record> a = records(before), b = records(after);
  size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    if (j == b.size() || (i < a.size() && a[i].hash < b[j].hash)) {
      d.removed.push_back(uint32_t(a[i++].index));
    } else if (i == a.size() || b[j].hash < a[i].hash) {
      d.added.push_back(uint32_t(b[j++].index));
    } else {
      // Equal hashes: match the runs pairwise by content (a collision stays unmatched).
      const uint64_t h = a[i].hash;
      size_t ie = i, je = j;
      while (ie < a.size() && a[ie].hash == h) ++ie;
      while (je < b.size() && b[je].hash == h) ++je;
      std::vector<bool> used(je - j, false);
      for (size_t x = i; x < ie; ++x) {
        bool matched = false;
        for (size_t y = j; y < je && !matched; ++y)
          if (!used[y - j] && same(before, a[x].index, after, b[y].index)) used[y - j] = matched = true;
        if (!matched) d.removed.push_back(uint32_t(a[x].index));
      }
      for (size_t y = j; y < je; ++y)
        if (!used[y - j]) d.added.push_back(uint32_t(b[y].index));
      i = ie;
      j = je;
    }
  }
  std::sort(d.removed.begin(), d.removed.end());
  std::sort(d.added.begin(), d.added.end());
  return d;
}

bool diff_reaches_view(const GaussianScene& before, const GaussianScene& after, const SceneDiff& diff,
                       const Camera& camera, const RenderSettings& settings) {
  if (diff.everything) return true;
  const ProjectionCamera cam(camera);
  auto reaches = [&](const GaussianScene& g, uint32_t i) {
    float cov3[6];
    covariance_3d(&g.scales[3 * i], &g.rotations[4 * i], cov3);
    Footprint f;
    if (!project_footprint(cam, &g.positions[3 * i], cov3, settings.near_plane, settings.blur, f)) return false;
    // The footprint box (pixel index coordinates) against the image, with a pixel of slack.
    const float r = float(f.radius) + 1.f;
    return f.mean_x + r >= 0 && f.mean_y + r >= 0 && f.mean_x - r < camera.width && f.mean_y - r < camera.height;
  };
  for (uint32_t i : diff.removed)
    if (reaches(before, i)) return true;
  for (uint32_t i : diff.added)
    if (reaches(after, i)) return true;
  return false;
}

RenderSettings view_render_settings(const segment::ViewOptions& opt) {
  RenderSettings rs;
  rs.threads = opt.threads;
  for (int c = 0; c < 3; ++c) rs.background[c] = opt.background[c];
  return rs;
}

segment::SegmentView reuse_view(const segment::SegmentView& donor, const GaussianScene& after,
                                const segment::ViewOptions& opt) {
  segment::SegmentView v;
  v.name = donor.name;
  v.camera_index = donor.camera_index;
  v.camera = donor.camera;
  v.rgb8 = donor.rgb8;
  v.depth = donor.depth;
  v.alpha = donor.alpha;
  v.embedding = donor.embedding;
  v.frame = prepare_frame(after, v.camera, view_render_settings(opt));
  segment::set_all_votes(v, after, opt.threads);
  return v;
}

}  // namespace isegman::server
