#include "segment/pipeline.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "core/centre_index.h"
#include "core/error.h"
#include "models/tensor_memory.h"
#include "segment/trained_background.h"
#include "segment/view_selection.h"
#include "segment/voting_views.h"

namespace isegman::segment {

int view_of_camera(const Session& s, int camera_index) {
  for (size_t k = 0; k < s.views().size(); ++k)
    if (s.views()[k].camera_index == camera_index) return int(k);
  return -1;
}

std::unique_ptr<Session> segment_from_prompts(const SceneBundle& b, int camera_index,
                                              const std::vector<Click>& clicks,
                                              std::shared_ptr<const models::SamModel> sam,
                                              const SessionOptions& session_options,
                                              const ViewOptions& view_options, const std::string& views_spec,
                                              PipelineTimings* timings, const Progress& progress) {
  if (camera_index < 0 || camera_index >= int(b.cameras.size())) throw Error("no camera " + std::to_string(camera_index));
  if (clicks.empty()) throw Error("segmentation needs at least one click");
  if (clicks.front().label != 1) throw Error("the first click must be positive");
  const Camera& cam = b.cameras[size_t(camera_index)];
  for (const Click& c : clicks)
    if (!(c.x >= 0 && c.y >= 0 && c.x < cam.width && c.y < cam.height))
      throw Error("click (" + std::to_string(c.x) + ", " + std::to_string(c.y) + ") lies outside camera '" +
                  cam.name + "' (" + std::to_string(cam.width) + "x" + std::to_string(cam.height) + ")");
  auto t0 = std::chrono::steady_clock::now();
  // Every view, the ones a click adds later included, over the colour the scene was
  // trained on: thin and half-transparent parts look to SAM as they did in the photos.
  ViewOptions vo = view_options;
  SessionOptions so = session_options;
  const std::string background_line = use_trained_background(b, vo, so);
  if (progress && !background_line.empty()) progress(background_line);
  PipelineTimings t;
  std::vector<SegmentView> views;
  std::shared_ptr<const CentreIndex> neighbours;  // built for view selection, then the session's
  int auto_k = 0;
  if (parse_auto_views(views_spec, auto_k) && int(b.cameras.size()) > auto_k) {
    // Voting-view selection: build the clicked view first, then choose the views that see
    // the clicked object (voting_views.h).
    views = build_views(b, {camera_index}, *sam, vo, progress, &t.ms_embedding);
    auto ts = std::chrono::steady_clock::now();
    const SegmentView& cv = views.front();
    const Click first = rescaled(clicks.front(), cam.width, cam.height, cv.camera.width, cv.camera.height);
    // What may hide the object from a camera: the Gaussians near each line of sight.
    neighbours = std::make_shared<const CentreIndex>(b.gaussians);
    bool surface = false;
    std::vector<int> chosen = choose_voting_views(b.gaussians, *neighbours, b.cameras, camera_index, cv, first, *sam,
                                                  so.propagation.min_alpha, auto_k, &surface);
    t.ms_selection = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - ts).count();
    if (progress) {
      char line[256];
      std::snprintf(line, sizeof line, "auto views: %zu of %zu cameras %s", chosen.size(), b.cameras.size(),
                    surface ? "see the clicked object, spread around it" : "spread over the scene (no surface under the click)");
      progress(line);
    }
    chosen.erase(std::remove(chosen.begin(), chosen.end(), camera_index), chosen.end());
    std::vector<SegmentView> rest = build_views(b, chosen, *sam, vo, progress, &t.ms_embedding);
    for (SegmentView& v : rest) views.push_back(std::move(v));
    std::sort(views.begin(), views.end(),
              [](const SegmentView& a, const SegmentView& c) { return a.camera_index < c.camera_index; });
  } else {
    std::vector<int> chosen = sample_views(b.cameras, views_spec, camera_index);
    views = build_views(b, chosen, *sam, vo, progress, &t.ms_embedding);
  }
  // The views are encoded and clicks only decode: the blocks the SAM engine keeps for the
  // encoder's activations (~0.4 GB) would stay resident for the whole session. (Not after
  // every view: encoding with a cold pool was about twice as slow.)
  models::trim_tensor_memory_pool();
  t.views = int(views.size());
  t.ms_views = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  auto session = std::make_unique<Session>(b.gaussians, std::move(views), std::move(sam), so);
  if (neighbours) session->share_neighbours(neighbours);
  const int v = view_of_camera(*session, camera_index);
  // By value: a click may add a view (see_through.h), which moves the session's views.
  const int work_width = session->views()[size_t(v)].camera.width, work_height = session->views()[size_t(v)].camera.height;
  for (const Click& c : clicks) {
    RoundReport r = session->click(v, rescaled(c, cam.width, cam.height, work_width, work_height));
    t.ms_propagation += r.ms_propagation;
    t.ms_sam += r.ms_sam;
    t.ms_voting += r.ms_voting;
    t.voting += r.voting;
    ++t.rounds;
  }
  if (timings) *timings = t;
  return session;
}

}  // namespace isegman::segment
