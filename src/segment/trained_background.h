// The colour a scene was trained over, recovered from its photos. Trainers composite every
// render over a fixed background (black, white, or any colour), and where the Gaussians leave
// a pixel partly uncovered the photo shows that colour through them: photo = C + T * bg,
// with C the render over black and T its transmittance. Rendering the segmentation's views
// over another colour changes what SAM sees wherever the scene is thin (a half-transparent
// box on a white-trained object turned into one mask with the roof behind it).
#pragma once

#include <string>

#include "core/scene.h"
#include "segment/session.h"
#include "segment/views.h"

namespace isegman::segment {

struct TrainedBackgroundOptions {
  int max_photos = 4;            // photos compared, spread over the cameras that have one
  int render_side = 200;         // they are compared at this longest side
  double min_transmittance = 0.5;  // pixels at least this uncovered speak for the background
  double min_share = 0.01;       // ... and must make up this share of the compared pixels
  // The estimate holds only when the uncovered pixels agree: this share of their per-pixel
  // estimates lies within `tolerance` (every channel) of the median. Photos whose uncovered
  // parts show a real surrounding (sky, a room the training left out) give no estimate.
  double min_agreeing = 0.6;
  double tolerance = 0.08;
  int threads = 0;
};

struct TrainedBackground {
  bool found = false;
  float rgb[3] = {0.f, 0.f, 0.f};  // in [0, 1]
  int photos = 0;                   // photos compared
  size_t pixels = 0;                // uncovered pixels among them
  double agreeing = 0;              // share of those within the tolerance of the estimate
  std::string summary() const;      // one line: the colour and what it rests on, or why none
};

// Compares the scene's renders with its cameras' photos (Camera::image_path). No photos,
// photos that cannot be read, have another aspect ratio or an alpha channel (the trainer
// composited those itself), too few uncovered pixels or estimates that disagree: not found
// (the caller keeps its colour).
TrainedBackground estimate_trained_background(const SceneBundle& scene, const TrainedBackgroundOptions& options = {});

// Renders `views` over `background` when it was found and `views.trained_background` is on,
// and the views a session's clicks add (session.see_through_views) over the same colour as
// `views`, found or not.
void render_over(const TrainedBackground& background, ViewOptions& views, SessionOptions& session);

// The estimate for `scene` (only when `views.trained_background` is on), applied as
// render_over does; returns its summary line ("" when none was made).
std::string use_trained_background(const SceneBundle& scene, ViewOptions& views, SessionOptions& session);

}  // namespace isegman::segment
