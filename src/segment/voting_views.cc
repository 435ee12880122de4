#include "segment/voting_views.h"

#include <algorithm>
#include <cmath>

#include "segment/line_of_sight.h"
#include "segment/propagation.h"
#include "segment/view_selection.h"

namespace isegman::segment {

std::vector<Vec3> object_samples(const SegmentView& view, const models::SamModel& sam, const Click& click,
                                 double min_alpha) {
  std::vector<Vec3> out;
  const Mask mask = sam.decode(view.embedding, {click}).mask();
  size_t area = 0;
  for (uint8_t m : mask.data) area += m != 0;
  if (area == 0) return out;
  const int step = std::max(1, int(std::sqrt(double(area) / 64.0)));
  for (int y = step / 2; y < mask.height; y += step)
    for (int x = step / 2; x < mask.width; x += step) {
      Vec3 X;
      if (mask.at(x, y) && surface_point(view, x + 0.5, y + 0.5, min_alpha, X)) out.push_back(X);
    }
  return out;
}

std::vector<int> choose_voting_views(const GaussianScene& scene, const CentreIndex& index,
                                     const std::vector<Camera>& cameras, int anchor, const SegmentView& clicked,
                                     const Click& click, const models::SamModel& sam, double min_alpha, int k,
                                     bool* found_surface) {
  Vec3 X;
  const bool surface = surface_point(clicked, click.x, click.y, min_alpha, X);
  if (found_surface) *found_surface = surface;
  if (!surface) return spread_views(cameras, anchor, k);
  const LineOfSight sight(scene, index);
  return select_views_for_object(cameras, anchor, X, object_samples(clicked, sam, click, min_alpha),
                                 [&](const Vec3& a, const Vec3& b) { return sight.transmittance(a, b); }, k);
}

}  // namespace isegman::segment
