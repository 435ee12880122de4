// The one loader and the one writer for Gaussian splat files. Every command and the
// server open and save scenes through these.
//   load_gaussians(path): a trainer scene directory (its point_cloud.ply), a SOG folder
//   (meta.json), or a file recognised by its content, whatever its extension: INRIA PLY,
//   SuperSplat compressed PLY, .spz (gzip v1-3 or zstd v4), zipped .sog, or .splat.
//   write_gaussians(path, ...): format from the extension: .ply, .compressed.ply, .splat,
//   .spz, .sog.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/scene.h"

namespace isegman {

enum class SplatFormat { kPly, kSplat, kCompressedPly, kSpz, kSog };

const char* splat_format_name(SplatFormat f);
// Whether the format stores the SH bands above degree 0 (.splat does not).
bool format_keeps_sh(SplatFormat f);

// Recognises file bytes; throws Error(source, ...) when they are no splat format.
SplatFormat detect_splat_format(const uint8_t* data, size_t size, const std::string& source);

// Decodes file bytes in the given format (`notes` gets what the reader tolerated;
// `parsed`, for PLY: byte ranges that will not be read again, see parse_ply).
GaussianScene parse_gaussians(const uint8_t* data, size_t size, SplatFormat format, const std::string& source,
                              std::vector<std::string>* notes = nullptr,
                              const std::function<void(size_t offset, size_t length)>& parsed = {});

struct LoadedGaussians {
  GaussianScene scene;
  SplatFormat format = SplatFormat::kPly;
  std::string file;                // the file (or SOG folder) the Gaussians came from
  std::vector<std::string> notes;  // tolerated oddities, extension/content mismatch
};
LoadedGaussians load_gaussians(const std::string& path);

// Output format of a path by its extension; throws naming the supported ones.
SplatFormat output_format_for_path(const std::string& path);

struct GaussianWriteOptions {
  int spz_version = 0;  // 0: SpzWriteOptions' default; 2, 3 (gzip) or 4 (zstd)
};

// Encodes; `notes` gets what the format could not keep; `order` (when given) receives,
// per written Gaussian, its index in `scene` (formats that reorder: compressed PLY).
std::vector<uint8_t> serialize_gaussians(const GaussianScene& scene, SplatFormat format,
                                         std::vector<std::string>* notes = nullptr,
                                         std::vector<uint32_t>* order = nullptr,
                                         const GaussianWriteOptions& options = {});

// Refuses to replace any of `inputs` or to write an empty scene, then writes atomically
// in the format of the extension.
void write_gaussians(const std::string& path, const GaussianScene& scene, const std::vector<std::string>& inputs,
                     std::vector<std::string>* notes = nullptr, std::vector<uint32_t>* order = nullptr,
                     const GaussianWriteOptions& options = {});

}  // namespace isegman
