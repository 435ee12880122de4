// The small interface the segmentation layer programs against: a promptable 2D segmenter
// that also yields a feature map for matching. SamPredictor (sam.h) implements it.
#pragma once

#include <vector>

#include "core/click.h"
#include "core/image.h"
#include "models/feature_map.h"

namespace isegman::models {

// The one click type (core/click.h): continuous pixel coordinates, pixel (i, j) covers
// [i, i+1) x [j, j+1). SAM's point convention differs by half a pixel; sam.cc converts.
// Labels: 1 positive, 0 negative; 2 and 3 are a box's top-left and bottom-right corners
// (SAM's box prompt, at most one box).
using Click = isegman::Click;

struct SegmentResult {
  Image mask;                      // width x height of the image, 1 channel, values 0 or 1
  float score = 0;                 // the model's IoU prediction for the mask
  std::vector<float> low_res_logits;  // low_res_size^2 logits over the padded model frame
  int low_res_size = 0;               // 256 for SAM
  int mask_index = 0;                 // which of the decoder's candidate masks was chosen
  // Every candidate the decoder returned (SAM's multimask output: whole, part, subpart),
  // with its predicted IoU, so a caller can choose by other evidence.
  std::vector<Image> candidates;
  std::vector<float> candidate_scores;
  std::vector<std::vector<float>> candidate_low_res;
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
