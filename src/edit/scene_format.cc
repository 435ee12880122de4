#include "edit/scene_format.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "core/error.h"
#include "edit/splat_format.h"
#include "io/atomic_file.h"
#include "io/ply.h"

namespace isegman::edit {
namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

}  // namespace

const char* format_name(SceneFormat f) { return f == SceneFormat::kPly ? "PLY" : ".splat"; }

SceneFormat detect_scene_format(const uint8_t* data, size_t size, const std::string& source) {
  if (size >= 4 && std::memcmp(data, "ply", 3) == 0 && (data[3] == '\n' || data[3] == '\r')) return SceneFormat::kPly;
  if (size == 0) throw Error(source, "empty file: not a scene");
  if (size % kSplatRecordBytes != 0)
    throw Error(source, "not a scene file: no PLY header ('ply' line) and " + std::to_string(size) +
                            " bytes is not a multiple of the 32-byte .splat record");
  // Check a spread of records: finite positions, positive finite scales, and a
  // non-zero quaternion. Random bytes or text almost never pass for all of them.
  const size_t n = size / kSplatRecordBytes;
  const size_t step = std::max<size_t>(1, n / 64);
  for (size_t i = 0; i < n; i += step) {
    const uint8_t* r = data + i * kSplatRecordBytes;
    for (int a = 0; a < 3; ++a) {
      const float p = splat_f32(r + 4 * a), s = splat_f32(r + 12 + 4 * a);
      if (!std::isfinite(p) || std::fabs(p) > 1e8f || !std::isfinite(s) || !(s > 0) || s > 1e8f)
        throw Error(source, "not a scene file: no PLY header, and record " + std::to_string(i) +
                                " is not a valid .splat record (position/scale out of range)");
    }
    if (r[28] == 128 && r[29] == 128 && r[30] == 128 && r[31] == 128)
      throw Error(source, "not a scene file: no PLY header, and record " + std::to_string(i) +
                              " has a zero .splat rotation");
  }
  return SceneFormat::kSplat;
}

GaussianScene read_scene_file(const std::string& path, SceneFormat* format, std::vector<std::string>* notes) {
  std::vector<uint8_t> bytes = read_file_bytes(path);
  const SceneFormat f = detect_scene_format(bytes.data(), bytes.size(), path);
  if (format) *format = f;
  const std::string ext = lower_extension(path);
  if (notes && ((ext == ".ply" && f != SceneFormat::kPly) || (ext == ".splat" && f != SceneFormat::kSplat)))
    notes->push_back(path + ": named " + ext + " but its content is " + format_name(f) + "; read as " + format_name(f));
  if (f == SceneFormat::kPly) {
    PlyReadReport report;
    GaussianScene s = parse_ply(bytes.data(), bytes.size(), path, &report);
    if (notes)
      for (const auto& n : report.notes) notes->push_back(path + ": " + n);
    return s;
  }
  return parse_splat(bytes.data(), bytes.size(), path);
}

SceneFormat output_format_for(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".ply") return SceneFormat::kPly;
  if (ext == ".splat") return SceneFormat::kSplat;
  throw Error(path, "unknown output format '" + ext + "': name the output *.ply (INRIA PLY) or *.splat");
}

void write_scene_file(const std::string& path, const GaussianScene& scene, const std::vector<std::string>& inputs,
                      std::vector<std::string>* notes) {
  const SceneFormat f = output_format_for(path);
  refuse_overwriting_inputs(path, inputs);
  if (scene.size() == 0) throw Error(path, "refusing to write a scene with no Gaussians");
  if (f == SceneFormat::kPly) write_ply(path, scene);
  else write_splat(path, scene, notes);
}

}  // namespace isegman::edit
