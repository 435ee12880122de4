// The small interface the segmentation layer programs against: a promptable 2D segmenter
// that also yields a feature map for matching. SamPredictor (sam.h) implements it.
#pragma once

#include <vector>

#include "core/click.h"
#include "core/image.h"
#include "core/mask.h"
#include "models/feature_map.h"

namespace isegman::models {

// The one click type (core/click.h): continuous pixel coordinates, pixel (i, j) covers
// [i, i+1) x [j, j+1). SAM's point convention differs by half a pixel; sam.cc converts.
// Labels: 1 positive, 0 negative; 2 and 3 are a box's top-left and bottom-right corners
// (SAM's box prompt, at most one box).
using Click = isegman::Click;

struct SegmentResult {
  float score = 0;                 // the model's IoU prediction for its chosen mask
  int low_res_size = 0;            // 256 for SAM
  int mask_index = 0;              // which candidate the decoder chose
  // Every candidate the decoder returned (SAM's multimask output: whole, part, subpart) at
  // the image's size, with its predicted IoU and its low_res_size^2 logits over the padded
  // model frame, so a caller can choose by other evidence and refine in a later round.
  std::vector<Mask> candidates;
  std::vector<float> candidate_scores;
  std::vector<std::vector<float>> candidate_low_res;

  const Mask& mask() const { return candidates[size_t(mask_index)]; }
  const std::vector<float>& low_res_logits() const { return candidate_low_res[size_t(mask_index)]; }
};

class Segmenter2D {
 public:
  virtual ~Segmenter2D() = default;
  // Encodes an RGB image (values in [0, 1], any size) and keeps its embedding.
  virtual void set_image(const Image& rgb) = 0;
  // Segments the current image from clicks; `previous_low_res` (optional) is the
  // low_res_logits of an earlier result on the same image, for multi-round refinement.
  virtual SegmentResult predict(const std::vector<Click>& clicks,
                                const std::vector<float>* previous_low_res = nullptr) const = 0;
  // The current image's features as an L2-normalised grid.
  virtual FeatureMap feature_map() const = 0;
};

}  // namespace isegman::models
