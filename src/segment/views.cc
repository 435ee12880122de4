#include "segment/views.h"

#include <algorithm>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>

#include "core/error.h"
#include "io/image_io.h"
#include "models/tensor_memory.h"
#include "render/visibility.h"
#include "segment/view_selection.h"

namespace isegman::segment {

std::vector<int> sample_views(const std::vector<Camera>& cameras, const std::string& spec, int must_include) {
  const int n = int(cameras.size());
  if (n == 0) throw Error("the scene has no cameras to segment in");
  std::set<int> chosen;
  int auto_k = 0;
  if (parse_auto_views(spec, auto_k)) {
    // No click point here: spread over all cameras (segment_from_prompts chooses by the
    // clicked surface point instead).
    if (n <= auto_k) {
      for (int i = 0; i < n; ++i) chosen.insert(i);
    } else {
      for (int i : spread_views(cameras, must_include, auto_k)) chosen.insert(i);
    }
  } else if (spec.empty() || spec == "all" || spec == "100%") {
    for (int i = 0; i < n; ++i) chosen.insert(i);
  } else if (spec.back() == '%') {
    char* end = nullptr;
    const double pct = std::strtod(spec.c_str(), &end);
    if (end != spec.c_str() + spec.size() - 1 || !(pct > 0 && pct <= 100))
      throw Error("--views: '" + spec + "' is not a percentage in (0, 100]");
    const int k = std::max(1, int(std::lround(n * pct / 100.0)));
    for (int i = 0; i < k; ++i) chosen.insert(int(std::floor((i + 0.5) * n / k)));
  } else {
    std::stringstream ss(spec);
    std::string item;
    while (std::getline(ss, item, ',')) {
      const Camera* c = find_camera(cameras, item);
      if (!c) throw Error("--views: no camera with id or name '" + item + "'");
      chosen.insert(int(c - cameras.data()));
    }
  }
  if (must_include >= 0 && must_include < n) chosen.insert(must_include);
  return std::vector<int>(chosen.begin(), chosen.end());
}

SegmentView build_view(const GaussianScene& scene, const Camera& camera, int camera_index,
                       const models::SamModel& sam, const ViewOptions& opt, models::SamTimings* timings) {
  SegmentView v;
  v.name = camera.name;
  v.camera_index = camera_index;
  v.camera = camera;
  const int longest = std::max(camera.width, camera.height);
  if (longest > opt.max_side) {
    const double s = double(opt.max_side) / longest;
    v.camera = camera.resized(std::max(1, int(std::lround(camera.width * s))),
                              std::max(1, int(std::lround(camera.height * s))));
  }
  RenderSettings rs;
  rs.threads = opt.threads;
  rs.near_plane = opt.near_plane;
  for (int c = 0; c < 3; ++c) rs.background[c] = opt.background[c];
  v.frame = prepare_frame(scene, v.camera, rs);
  // The frame is kept for votes and selection masks: compacted (what no pixel blends is
  // dropped; per-tile vote sums kept), without colours, in the same pass as the render.
  RenderOutput r = compact_frame(v.frame, rs, false);
  v.depth = std::move(r.depth);
  v.alpha = std::move(r.alpha);
  Image rgb;
  if (opt.use_photos) {
    if (camera.image_path.empty()) throw Error("camera '" + camera.name + "' has no source photo (use renders)");
    Image photo = read_image(camera.image_path, 3);
    rgb = (photo.width == v.camera.width && photo.height == v.camera.height)
              ? std::move(photo)
              : resize_image(photo, v.camera.width, v.camera.height);
  } else {
    rgb = std::move(r.color);
  }
  set_all_votes(v, scene, opt.threads);
  v.embedding = sam.encode_cached(rgb, opt.cache_dir, timings);
  // What SAM encoded, a quarter of the float image: at 1000x660, 6 MB less per view.
  v.rgb8 = models::quantise_rgb(rgb);
  return v;
}

void set_all_votes(SegmentView& v, const GaussianScene& scene, int threads) {
  const ViewVotes total = total_votes(v.frame, threads);
  v.surroundings = surroundings_index(scene, v.camera, total);
  v.all_votes = PackedVotes(total);
}

size_t view_bytes(const SegmentView& v) {
  return sizeof(SegmentView) + frame_bytes(v.frame) + v.rgb8.capacity() +
         (v.depth.data.capacity() + v.alpha.data.capacity()) * sizeof(float) +
         v.all_votes.bytes() + v.surroundings.bytes() +
         (v.embedding.features.bytes ? v.embedding.features.bytes->capacity() : 0) +
         models::SamModel::decoder_values_bytes(v.embedding);
}

Image SegmentView::rgb_image() const {
  Image out(camera.width, camera.height, 3);
  if (rgb8.size() != out.data.size()) return Image();
  for (size_t i = 0; i < rgb8.size(); ++i) out.data[i] = float(rgb8[i]) / 255.f;
  return out;
}

std::vector<SegmentView> build_views(const SceneBundle& b, const std::vector<int>& indices,
                                     const models::SamModel& sam, const ViewOptions& opt, const Progress& progress,
                                     double* ms_embedding) {
  std::vector<SegmentView> views;
  views.reserve(indices.size());
  for (size_t k = 0; k < indices.size(); ++k) {
    const Camera& cam = b.cameras.at(size_t(indices[k]));
    auto t0 = std::chrono::steady_clock::now();
    models::SamTimings t;
    views.push_back(build_view(b.gaussians, cam, indices[k], sam, opt, &t));
#ifdef __GLIBC__
    // The build's transient buffers (projection, sorting, compaction, SAM activations)
    // are freed, but glibc keeps much of such memory in its heaps; give it back, or it
    // adds up over the views.
    malloc_trim(0);
#endif
    if (ms_embedding) *ms_embedding += t.preprocess_ms + t.encoder_ms;
    if (progress) {
      char line[256];
      std::snprintf(line, sizeof line, "view %zu/%zu %s: %.0f ms (%s)", k + 1, indices.size(), cam.name.c_str(),
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count(),
                    t.from_cache ? "embedding from cache" : "embedding computed");
      progress(line);
    }
  }
  // Encoded: clicks only decode, so the encoder's activation blocks the tensor pool keeps
  // for reuse (~0.4 GB) go back to the system instead of staying resident (as the server does).
  models::trim_tensor_memory_pool();
  return views;
}

}  // namespace isegman::segment
