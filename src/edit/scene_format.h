// Scene files by content: an INRIA PLY starts with "ply"; a .splat has no header and is
// recognised by its 32-byte records (size, finite positions, positive finite scales).
// Outputs pick the format by extension (.ply default, .splat), are written atomically,
// are validated first, and never replace an input.
#pragma once

#include <string>
#include <vector>

#include "core/scene.h"

namespace isegman::edit {

enum class SceneFormat { kPly, kSplat };

const char* format_name(SceneFormat f);

// Throws Error(source, ...) when the bytes are neither.
SceneFormat detect_scene_format(const uint8_t* data, size_t size, const std::string& source);

// Reads a PLY or .splat file, whatever its extension. `format` receives what was found,
// `notes` what the reader tolerated (and an extension/content mismatch).
GaussianScene read_scene_file(const std::string& path, SceneFormat* format = nullptr,
                              std::vector<std::string>* notes = nullptr);

// ".ply" (or no recognised extension: error) -> PLY; ".splat" -> .splat.
SceneFormat output_format_for(const std::string& path);

// Writes `scene` to `path` in the format of its extension, atomically, after checking
// that `path` is none of `inputs`. `notes` gets what the format could not keep.
void write_scene_file(const std::string& path, const GaussianScene& scene, const std::vector<std::string>& inputs,
                      std::vector<std::string>* notes = nullptr);

}  // namespace isegman::edit
