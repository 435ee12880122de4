// Segmentation from prompts in one call: build the sampled views (embeddings cached),
// open a session and play the clicks as rounds. Used by `segment`, `eval`, the ablation
// and the demo.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "segment/session.h"

namespace isegman::segment {

struct PipelineTimings {
  double ms_views = 0, ms_propagation = 0, ms_sam = 0, ms_voting = 0;
  double ms_embedding = 0;  // part of ms_views: SAM encoding (0 when cached)
  double ms_selection = 0;  // part of ms_views: choosing the "auto" views
  int views = 0, rounds = 0;
  VotingParts voting;  // where ms_voting went, summed over the rounds
  double ms_interaction() const { return ms_propagation + ms_sam + ms_voting; }
};

// The clicked camera is always among the views. With views_spec "auto" / "auto:K" and more
// than K cameras, the views are chosen for the first click (voting_views.h): the clicked
// view is built first, and the K views that best see the clicked object (inside their
// frame, with open lines of sight) are taken, spread around it (all cameras spread when no
// surface is under the click).
// Returns the session after the last click.
std::unique_ptr<Session> segment_from_prompts(const SceneBundle& bundle, int camera_index,
                                              const std::vector<Click>& clicks,
                                              std::shared_ptr<const models::SamModel> sam,
                                              const SessionOptions& session_options, const ViewOptions& view_options,
                                              const std::string& views_spec, PipelineTimings* timings = nullptr,
                                              const Progress& progress = nullptr);

// Index of a camera's view inside a session built by segment_from_prompts.
int view_of_camera(const Session& session, int camera_index);

}  // namespace isegman::segment
