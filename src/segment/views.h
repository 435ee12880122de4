// The views a segmentation works in: the scene's cameras (rendered from the Gaussians,
// or their source photos), a sampled subset of them, and free cameras added on the fly.
// Each view keeps what every interaction reuses: its image, expected depth and alpha, its
// prepared frame (for votes and selection masks), all-pixel votes and its SAM embedding.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/scene.h"
#include "models/sam.h"
#include "render/rasterizer.h"
#include "segment/background_gate.h"
#include "segment/packed_votes.h"
#include "segment/votes.h"

namespace isegman::segment {

struct SegmentView {
  std::string name;
  int camera_index = -1;  // index in the scene's camera list; -1 for a free camera
  Camera camera;          // at the working resolution
  std::vector<uint8_t> rgb8;  // what SAM segmented, 8 bits per channel (kept for the overlays)
  Image rgb_image() const;    // rgb8 as a float image
  Image depth, alpha;     // rendered expected depth and accumulated alpha
  PreparedFrame frame;
  PackedVotes all_votes;  // A-votes of every pixel (mask independent), packed: kept all session
  SurroundingsIndex surroundings;  // of all_votes, for the background gate (background_gate.h)
  models::SamEmbedding embedding;
};

// Sets the view's all-pixel votes (all_votes) from its frame, and the surroundings index
// over them; `scene` is the frame's.
void set_all_votes(SegmentView& view, const GaussianScene& scene, int threads);

// Bytes a view holds (its frame, images, all-pixel votes and embedding): what a cache of
// views is bounded by.
size_t view_bytes(const SegmentView& view);

struct ViewOptions {
  bool use_photos = false;   // SAM sees the source photos instead of renders
  int max_side = 1024;       // working resolution cap (SAM works at 1024 anyway)
  std::string cache_dir;     // embedding cache ("" = none)
  int threads = 0;
  float background[3] = {0.f, 0.f, 0.f};
  // Render over the colour the scene was trained on where its photos show it, instead of
  // `background` (trained_background.h: use_trained_background).
  bool trained_background = true;
  float near_plane = RenderSettings{}.near_plane;  // Gaussians nearer are not rendered (see_through.h)
};

// Parses a view sampling spec against `count` cameras: "all", "25%" (spread uniformly
// along the list), "auto" / "auto:K" (every camera when there are at most K, default 20;
// otherwise K cameras spread over the scene: segment_from_prompts chooses them by the
// clicked surface point, see view_selection.h), or a comma list of ids or names.
// `must_include` is always in.
std::vector<int> sample_views(const std::vector<Camera>& cameras, const std::string& spec, int must_include = -1);

using Progress = std::function<void(const std::string& line)>;

// Renders and encodes one view (the embedding comes from the cache when present).
SegmentView build_view(const GaussianScene& scene, const Camera& camera, int camera_index,
                       const models::SamModel& sam, const ViewOptions& options, models::SamTimings* timings = nullptr);

// Builds the listed cameras' views, reporting progress per view; adds the SAM
// preprocessing + encoder time (0 for cached embeddings) to *ms_embedding.
std::vector<SegmentView> build_views(const SceneBundle& bundle, const std::vector<int>& camera_indices,
                                     const models::SamModel& sam, const ViewOptions& options,
                                     const Progress& progress = nullptr, double* ms_embedding = nullptr);

}  // namespace isegman::segment
