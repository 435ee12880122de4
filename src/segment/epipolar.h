// Epipolar geometry for click propagation: the image of a click's viewing ray in another
// view, and the walk over the feature-grid cells that line crosses.
#pragma once

#include <utility>
#include <vector>

#include "core/camera.h"

namespace isegman::segment {

// The segment of `dst` showing the ray through pixel (u, v) of `src` (continuous pixel
// coordinates), for ray depths t in [t_min, t_max] along the unit ray, kept in front of
// dst's near plane and clipped to dst's image rectangle. False when none of it is visible.
bool epipolar_segment(const Camera& src, double u, double v, const Camera& dst, double t_min, double t_max,
                      Point2& a, Point2& b, double near_plane = 0.05);

// Line coefficients (l0 x + l1 y + l2 = 0, with l0^2 + l1^2 = 1) of the epipolar line in
// dst of pixel (u, v) of src: F-matrix free, from two points of the ray.
bool epipolar_line(const Camera& src, double u, double v, const Camera& dst, double line[3]);

// Every grid cell a segment crosses (grid coordinates: cell (i, j) spans [i, i+1) x
// [j, j+1)), in order from a to b: a supercover walk (Amanatides-Woo), so no crossed cell
// is skipped, unlike a plain Bresenham line. Cells outside [0, w) x [0, h) are left out.
std::vector<std::pair<int, int>> grid_cells_on_segment(Point2 a, Point2 b, int w, int h);

}  // namespace isegman::segment
