#include "segment/propagation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "segment/epipolar.h"

namespace isegman::segment {

PropagationMode parse_mode(const std::string& name) {
  if (name == "epipolar") return PropagationMode::Epipolar;
  if (name == "depth") return PropagationMode::Depth;
  if (name == "hybrid") return PropagationMode::Hybrid;
  throw Error("--mode: '" + name + "' is not one of hybrid, epipolar, depth");
}

const char* mode_name(PropagationMode m) {
  switch (m) {
    case PropagationMode::Epipolar: return "epipolar";
    case PropagationMode::Depth: return "depth";
    case PropagationMode::Hybrid: return "hybrid";
  }
  return "?";
}

namespace {
bool pixel_of(const SegmentView& v, double u, double w, int& x, int& y) {
  x = int(std::floor(u));
  y = int(std::floor(w));
  return x >= 0 && y >= 0 && x < v.camera.width && y < v.camera.height;
}
}  // namespace

bool surface_point(const SegmentView& view, double u, double v, double min_alpha, Vec3& point) {
  int x, y;
  if (!pixel_of(view, u, v, x, y)) return false;
  if (view.alpha.at(x, y) < min_alpha) return false;
  const double d = view.depth.at(x, y);
  if (!(d > 0)) return false;
  const Camera& c = view.camera;
  point = c.camera_to_world({(u - c.cx) / c.fx * d, (v - c.cy) / c.fy * d, d});
  return true;
}

Propagated propagate(const SegmentView& from, const Click& click, const SegmentView& to,
                     const PropagationOptions& opt, double scene_extent) {
  Propagated out;
  out.click.label = click.label;
  Vec3 X;
  bool have_point = opt.mode != PropagationMode::Epipolar && surface_point(from, click.x, click.y, opt.min_alpha, X);
  double pu = 0, pv = 0;
  if (have_point) {
    double z;
    if (!to.camera.project(X, pu, pv, &z) || pu < 0 || pv < 0 || pu >= to.camera.width || pv >= to.camera.height) {
      out.reason = "outside the view";
      return out;
    }
    int x, y;
    pixel_of(to, pu, pv, x, y);
    const double surface = to.depth.at(x, y);
    if (to.alpha.at(x, y) >= opt.min_alpha && z > surface * (1 + opt.occlusion_tolerance)) {
      if (opt.mode == PropagationMode::Depth || !opt.hidden_fallback) {
        char why[128];
        std::snprintf(why, sizeof why, "hidden: the clicked point lies at depth %.3g behind the surface at %.3g", z,
                      surface);
        out.reason = why;
        return out;
      }
      // Hybrid: the clicked surface point is hidden here, but the object may still show
      // (its far side, around an occluder): search the whole epipolar line as the paper
      // does, and let inspection drop the view if the match lands on something else.
      have_point = false;
    }
    const bool consistent = have_point && opt.depth_agreement > 0 && to.alpha.at(x, y) >= opt.min_alpha &&
                            std::abs(z - surface) <= opt.depth_agreement * surface;
    if (have_point && (opt.mode == PropagationMode::Depth || consistent)) {
      out.sent = true;
      out.click.x = pu;
      out.click.y = pv;
      out.affinity = 1.f;
      return out;
    }
  } else if (opt.mode == PropagationMode::Depth) {
    out.reason = "no surface under the click";
    return out;
  }

  // Epipolar search over the target view's feature grid (maps over the embeddings, which
  // normalise only the cells the search reads).
  const models::FeatureMap src_features = from.embedding.feature_map();
  const models::FeatureMap dst_features = to.embedding.feature_map();
  Point2 a, b;
  const double t_max = std::max(1.0, scene_extent) * 1e3;
  if (!epipolar_segment(from.camera, click.x, click.y, to.camera, 1e-6, t_max, a, b)) {
    out.reason = "epipolar line outside the view";
    return out;
  }
  double gax, gay, gbx, gby;
  dst_features.pixel_to_grid(a.x, a.y, gax, gay);
  dst_features.pixel_to_grid(b.x, b.y, gbx, gby);
  const auto cells = grid_cells_on_segment({gax, gay}, {gbx, gby}, dst_features.valid_columns(),
                                           dst_features.valid_rows());
  double wx = 0, wy = 0;
  if (have_point) dst_features.pixel_to_grid(pu, pv, wx, wy);
  const std::vector<float> query = src_features.sample(click.x, click.y);
  float best = -2.f;
  int bx = -1, by = -1;
  for (const auto& [gx, gy] : cells) {
    if (have_point) {  // hybrid: only near the depth reprojection
      const double dx = gx + 0.5 - wx, dy = gy + 0.5 - wy;
      if (dx * dx + dy * dy > opt.window_cells * opt.window_cells) continue;
    }
    const float aff = dst_features.affinity(query, gx, gy);
    if (aff > best) {
      best = aff;
      bx = gx;
      by = gy;
    }
  }
  if (bx < 0) {
    if (have_point) {  // the window holds no line cell (rounding at the border): trust depth
      out.sent = true;
      out.click.x = pu;
      out.click.y = pv;
      out.affinity = 0.f;
      return out;
    }
    out.reason = "epipolar line outside the view";
    return out;
  }
  double px, py;
  dst_features.cell_centre(bx, by, px, py);
  if (have_point) {
    // The reprojection is sub-cell accurate: keep it when its own cell matches about as
    // well as the best one, so the feature search only corrects real depth errors.
    int rx, ry;
    dst_features.pixel_to_cell(pu, pv, rx, ry);
    const float own = dst_features.affinity(query, rx, ry);
    if (own >= best - 0.05f) {
      px = pu;
      py = pv;
      best = own;
    }
  }
  out.sent = true;
  out.click.x = std::clamp(px, 0.0, double(to.camera.width) - 1e-3);
  out.click.y = std::clamp(py, 0.0, double(to.camera.height) - 1e-3);
  out.affinity = best;
  return out;
}

}  // namespace isegman::segment
