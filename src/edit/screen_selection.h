// Selection in the screen space of a camera (the web app's rectangle, lasso and brush,
// SuperSplat's tools): a 2D shape in the camera's image picks the Gaussians whose
// projected centres fall inside it, optionally only those on the visible surface.
//
// Shapes use the project's continuous pixel coordinates (core/click.h): pixel (i, j)
// covers [i, i+1) x [j, j+1) of the camera's full-size image. They are rasterised into a
// pixel region: a pixel is in when its centre (i + 0.5, j + 0.5) is inside the shape.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/scene.h"
#include "core/selection.h"
#include "render/rasterizer.h"

namespace isegman::edit {

using isegman::Point2;  // core/math.h

enum class ShapeKind { kRect, kLasso, kBrush };

struct ScreenShape {
  ShapeKind kind = ShapeKind::kRect;
  // kRect: two opposite corners; kLasso: the polygon's vertices (closed implicitly,
  // even-odd rule); kBrush: the stroke's points, each a disc of `radius` pixels, with
  // the segments between consecutive points swept too.
  std::vector<Point2> points;
  double radius = 0;  // kBrush
};

// "rect" / "lasso" / "brush"; throws Error otherwise.
ShapeKind parse_shape_kind(const std::string& text);
const char* shape_kind_name(ShapeKind kind);
// Checks point counts (rect 2, lasso >= 3, brush >= 1; at most 100000), finite
// coordinates within +-1e6 and a brush radius in (0, 1e5]; throws Error naming the field.
void check_shape(const ScreenShape& shape);

// A width x height pixel mask.
struct PixelRegion {
  int width = 0, height = 0;
  std::vector<uint8_t> inside;  // row-major, 1 = in
  bool contains(int x, int y) const {
    return x >= 0 && y >= 0 && x < width && y < height && inside[size_t(y) * size_t(width) + size_t(x)];
  }
  size_t count() const;
};

// Rasterises `shape` (in pixels of a `full_width` x `full_height` image) into a
// width x height region (the same image at another resolution: coordinates scale).
PixelRegion rasterize_shape(const ScreenShape& shape, int full_width, int full_height, int width, int height);

struct ScreenSelectOptions {
  // Only Gaussians that show: besides its centre falling in the shape, a Gaussian must
  // reach a blending weight (alpha * transmittance, what it adds to a pixel's colour) of
  // at least `min_weight` in one of the region's pixels; hidden ones reach ~0.
  bool visible_only = false;
  double min_weight = 0.1;
  // The visibility pass renders at most this longest side (the camera is scaled down;
  // the centre test always uses the full-size camera).
  int max_side = 1024;
  RenderSettings render;  // near plane (also culls centres), blur, threads
};

// Gaussians whose centres project (in front of the near plane) into a pixel of the shape.
Selection select_in_shape(const GaussianScene& scene, const Camera& camera, const ScreenShape& shape,
                          const ScreenSelectOptions& options = {});

// The Gaussian that contributes most (largest blending weight) to the pixel containing
// continuous coordinates (u, v) of `camera`'s image; -1 when nothing covers it.
int64_t gaussian_at(const GaussianScene& scene, const Camera& camera, double u, double v,
                    const RenderSettings& settings = {});

}  // namespace isegman::edit
