// Scene files for edit's callers: thin names over io/gaussian_file.h, the one loader and
// writer of every splat format (PLY, compressed PLY, .splat, .spz, .sog). Formats are
// detected by content on input and chosen by extension on output; outputs are written
// atomically, validated first, and never replace an input.
#pragma once

#include <string>
#include <vector>

#include "core/scene.h"
#include "io/gaussian_file.h"

namespace isegman::edit {

using SceneFormat = SplatFormat;

inline const char* format_name(SceneFormat f) { return splat_format_name(f); }

// Throws Error(source, ...) when the bytes are no splat format.
inline SceneFormat detect_scene_format(const uint8_t* data, size_t size, const std::string& source) {
  return detect_splat_format(data, size, source);
}

// Reads any splat file (or scene / SOG folder). `format` receives what was found,
// `notes` what the reader tolerated (and an extension/content mismatch).
GaussianScene read_scene_file(const std::string& path, SceneFormat* format = nullptr,
                              std::vector<std::string>* notes = nullptr);

inline SceneFormat output_format_for(const std::string& path) { return output_format_for_path(path); }

// Writes `scene` to `path` in the format of its extension, atomically, after checking
// that `path` is none of `inputs`. `notes` gets what the format could not keep; `order`
// the scene index of each written Gaussian (compressed PLY reorders).
inline void write_scene_file(const std::string& path, const GaussianScene& scene, const std::vector<std::string>& inputs,
                             std::vector<std::string>* notes = nullptr, std::vector<uint32_t>* order = nullptr) {
  write_gaussians(path, scene, inputs, notes, order);
}

}  // namespace isegman::edit
