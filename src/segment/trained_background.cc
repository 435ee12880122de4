#include "segment/trained_background.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/error.h"
#include "io/image_io.h"
#include "io/image_size.h"
#include "render/rasterizer.h"

namespace isegman::segment {

std::string TrainedBackground::summary() const {
  char line[200];
  if (found)
    std::snprintf(line, sizeof line, "trained background (%.3f, %.3f, %.3f): %zu uncovered pixels of %d photos, %.0f%% agree",
                  rgb[0], rgb[1], rgb[2], pixels, photos, 100 * agreeing);
  else if (photos == 0)
    std::snprintf(line, sizeof line, "trained background unknown: no photos to compare");
  else
    std::snprintf(line, sizeof line, "trained background unknown: %zu uncovered pixels of %d photos, %.0f%% agree",
                  pixels, photos, 100 * agreeing);
  return line;
}

namespace {

// Up to `count` cameras with a readable photo, spread evenly over the list.
std::vector<size_t> cameras_with_photos(const std::vector<Camera>& cameras, int count) {
  std::vector<size_t> with;
  std::error_code ec;
  for (size_t i = 0; i < cameras.size(); ++i)
    if (!cameras[i].image_path.empty() && std::filesystem::is_regular_file(cameras[i].image_path, ec)) with.push_back(i);
  if (int(with.size()) <= count) return with;
  std::vector<size_t> spread;
  for (int k = 0; k < count; ++k) spread.push_back(with[size_t(k) * with.size() / size_t(count)]);
  return spread;
}

double median(std::vector<float> v) {
  if (v.empty()) return 0;
  auto mid = v.begin() + std::ptrdiff_t(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

TrainedBackground estimate_trained_background(const SceneBundle& b, const TrainedBackgroundOptions& o) {
  TrainedBackground out;
  std::vector<float> estimates[3];  // per uncovered pixel: (photo - render over black) / T
  size_t compared = 0;
  for (size_t i : cameras_with_photos(b.cameras, o.max_photos)) {
    const Camera& cam = b.cameras[i];
    // A photo with an alpha channel was composited over the background by the trainer
    // itself: it shows no background colour to recover.
    if (png_has_alpha(cam.image_path)) continue;
    Image photo;
    try {
      photo = read_image(cam.image_path, 3);
    } catch (const Error&) {
      continue;  // the estimate is optional: an unreadable photo only leaves it out
    }
    // A photo of another shape is not this camera's frame (cropped or rotated): no pixel
    // of it can be matched.
    if (std::abs(double(photo.width) / photo.height - double(cam.width) / cam.height) > 0.01) continue;
    const double s = std::min(1.0, double(o.render_side) / std::max(cam.width, cam.height));
    const Camera small = cam.resized(std::max(1, int(std::lround(cam.width * s))), std::max(1, int(std::lround(cam.height * s))));
    RenderSettings rs;  // over black: the colour the Gaussians themselves give
    rs.threads = o.threads;
    rs.depth = false;
    const RenderOutput r = render(b.gaussians, small, rs);
    const Image p = resize_image(photo, small.width, small.height);
    ++out.photos;
    compared += size_t(small.width) * small.height;
    for (int y = 0; y < small.height; ++y)
      for (int x = 0; x < small.width; ++x) {
        const double t = 1.0 - r.alpha.at(x, y);
        if (t < o.min_transmittance) continue;
        for (int c = 0; c < 3; ++c) estimates[c].push_back(float((p.at(x, y, c) - r.color.at(x, y, c)) / t));
      }
  }
  out.pixels = estimates[0].size();
  if (out.pixels == 0 || double(out.pixels) < o.min_share * double(compared)) return out;
  for (int c = 0; c < 3; ++c) out.rgb[c] = float(std::clamp(median(estimates[c]), 0.0, 1.0));
  size_t agreeing = 0;
  for (size_t k = 0; k < out.pixels; ++k) {
    bool near = true;
    for (int c = 0; c < 3; ++c) near = near && std::abs(estimates[c][k] - out.rgb[c]) <= o.tolerance;
    agreeing += near;
  }
  out.agreeing = double(agreeing) / double(out.pixels);
  out.found = out.agreeing >= o.min_agreeing;
  if (!out.found) out.rgb[0] = out.rgb[1] = out.rgb[2] = 0.f;
  return out;
}

void render_over(const TrainedBackground& background, ViewOptions& views, SessionOptions& session) {
  if (background.found && views.trained_background)
    for (int c = 0; c < 3; ++c) views.background[c] = background.rgb[c];
  for (int c = 0; c < 3; ++c) session.see_through_views.background[c] = views.background[c];
}

std::string use_trained_background(const SceneBundle& scene, ViewOptions& views, SessionOptions& session) {
  TrainedBackground background;  // not found: the views keep their colour
  if (views.trained_background) {
    TrainedBackgroundOptions o;
    o.threads = views.threads;
    background = estimate_trained_background(scene, o);
  }
  render_over(background, views, session);
  return views.trained_background ? background.summary() : std::string();
}

}  // namespace isegman::segment
