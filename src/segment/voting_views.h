// The K voting views for a click, chosen before the other views are built (a capture of
// 100-300 photos votes with K of them): the surface under the click, SAM's mask there
// lifted to points of the object, and the cameras that see those points best, spread
// around them (view_selection.h). One function for `segment`, `eval` and the web app.
#pragma once

#include <vector>

#include "core/camera.h"
#include "core/centre_index.h"
#include "core/click.h"
#include "core/scene.h"
#include "models/sam.h"
#include "segment/views.h"

namespace isegman::segment {

// Up to ~64 points of the clicked object: pixels of SAM's mask at `click` (the view's
// working pixels) on a grid, lifted to the surface the view renders there.
std::vector<Vec3> object_samples(const SegmentView& view, const models::SamModel& sam, const Click& click,
                                 double min_alpha);

// Cameras (indices into `cameras`, sorted, `anchor` in) for a click in `clicked`. `anchor`
// is the clicked camera, or for a free camera the training camera nearest it. Without a
// surface under the click: k cameras spread over the scene, and `*found_surface` false.
std::vector<int> choose_voting_views(const GaussianScene& scene, const CentreIndex& index,
                                     const std::vector<Camera>& cameras, int anchor, const SegmentView& clicked,
                                     const Click& click, const models::SamModel& sam, double min_alpha, int k,
                                     bool* found_surface = nullptr);

}  // namespace isegman::segment
