#include "segment/pipeline.h"

#include <chrono>

#include "core/error.h"

namespace isegman::segment {

int view_of_camera(const Session& s, int camera_index) {
  for (size_t k = 0; k < s.views().size(); ++k)
    if (s.views()[k].camera_index == camera_index) return int(k);
  return -1;
}

std::unique_ptr<Session> segment_from_prompts(const SceneBundle& b, int camera_index,
                                              const std::vector<Click>& clicks,
                                              std::shared_ptr<const models::SamModel> sam,
                                              const SessionOptions& so, const ViewOptions& vo,
                                              const std::string& views_spec, PipelineTimings* timings,
                                              const Progress& progress) {
  if (camera_index < 0 || camera_index >= int(b.cameras.size())) throw Error("no camera " + std::to_string(camera_index));
  if (clicks.empty()) throw Error("segmentation needs at least one click");
  if (clicks.front().label != 1) throw Error("the first click must be positive");
  const Camera& cam = b.cameras[size_t(camera_index)];
  for (const Click& c : clicks)
    if (!(c.x >= 0 && c.y >= 0 && c.x < cam.width && c.y < cam.height))
      throw Error("click (" + std::to_string(c.x) + ", " + std::to_string(c.y) + ") lies outside camera '" +
                  cam.name + "' (" + std::to_string(cam.width) + "x" + std::to_string(cam.height) + ")");
  auto t0 = std::chrono::steady_clock::now();
  std::vector<int> chosen = sample_views(b.cameras, views_spec, camera_index);
  std::vector<SegmentView> views = build_views(b, chosen, *sam, vo, progress);
  PipelineTimings t;
  t.views = int(views.size());
  t.ms_views = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  auto session = std::make_unique<Session>(b.gaussians, std::move(views), std::move(sam), so);
  const int v = view_of_camera(*session, camera_index);
  const Camera& work = session->views()[size_t(v)].camera;
  for (const Click& c : clicks) {
    RoundReport r = session->click(v, rescaled(c, cam.width, cam.height, work.width, work.height));
    t.ms_propagation += r.ms_propagation;
    t.ms_sam += r.ms_sam;
    t.ms_voting += r.ms_voting;
    ++t.rounds;
  }
  if (timings) *timings = t;
  return session;
}

}  // namespace isegman::segment
