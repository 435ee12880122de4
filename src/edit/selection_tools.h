// Selection tools beside the 2D clicks: geometric shapes, attribute thresholds, set
// algebra and growing by nearest neighbours. Every tool returns a Selection tied to
// the scene (fingerprint and Gaussian count), and the set operations refuse to mix
// selections of different scenes.
#pragma once

#include "core/centre_index.h"
#include "core/math.h"
#include "core/scene.h"
#include "core/selection.h"

namespace isegman::edit {

enum class Region { kInside, kOutside };

// Centres inside the axis-aligned box [lo, hi] (bounds included) or outside it.
Selection select_box(const GaussianScene& scene, const Vec3& lo, const Vec3& hi, Region region = Region::kInside);
// Centres within distance r of c (boundary included) or beyond it.
Selection select_sphere(const GaussianScene& scene, const Vec3& center, double radius,
                        Region region = Region::kInside);
// Activated opacity sigmoid(logit) in [min, max].
Selection select_opacity(const GaussianScene& scene, double min_opacity, double max_opacity);
// Largest axis scale exp(max log-scale) in [min, max] (world units).
Selection select_size(const GaussianScene& scene, double min_size, double max_size);

Selection invert(const Selection& a);
Selection unite(const Selection& a, const Selection& b);
Selection subtract(const Selection& a, const Selection& b);
Selection intersect(const Selection& a, const Selection& b);

// Neighbours of a Gaussian for grow/shrink: its k nearest centres within `max_distance`
// (k >= 1; max_distance <= 0: no limit), or with k = 0 every centre within
// `max_distance` (> 0 then: a radius in scene units).
// Adds, `steps` times over, the neighbours of every selected Gaussian.
Selection grow(const GaussianScene& scene, const Selection& selection, int k, double max_distance = 0, int steps = 1);
// The opposite (an erosion): `steps` times over, drops every selected Gaussian that has
// an unselected neighbour (same neighbour rule as grow).
Selection shrink(const GaussianScene& scene, const Selection& selection, int k, double max_distance = 0,
                 int steps = 1);

// Base colour of Gaussian i: the SH DC term as the renderer shows it head-on,
// clamp(0.5 + C0 f_dc, 0, 1) per channel.
Vec3 base_color(const GaussianScene& scene, size_t i);
// Gaussians whose base colour lies within `tolerance` (Euclidean distance in RGB, [0, 1]
// per channel, so 0..sqrt(3)) of `color` (the eyedropper).
Selection select_similar_color(const GaussianScene& scene, const Vec3& color, double tolerance);

// The nearest-centre index grow/shrink use (core/centre_index.h).
using ::isegman::CentreIndex;

}  // namespace isegman::edit
