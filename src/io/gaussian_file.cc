#include "io/gaussian_file.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <numeric>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/compressed_ply.h"
#include "io/mapped_file.h"
#include "io/ply.h"
#include "io/scene_loader.h"
#include "io/sog.h"
#include "io/splat.h"
#include "io/spz.h"

namespace fs = std::filesystem;

namespace isegman {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}
bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The format a file name suggests, if any.
bool format_from_name(const std::string& path, SplatFormat& f) {
  const std::string name = lower(fs::path(path).filename().string());
  if (ends_with(name, ".compressed.ply")) f = SplatFormat::kCompressedPly;
  else if (ends_with(name, ".ply")) f = SplatFormat::kPly;
  else if (ends_with(name, ".splat")) f = SplatFormat::kSplat;
  else if (ends_with(name, ".spz")) f = SplatFormat::kSpz;
  else if (ends_with(name, ".sog")) f = SplatFormat::kSog;
  else return false;
  return true;
}

// A .splat has no header: check a spread of records (finite positions, positive finite
// scales, a non-zero quaternion). Random bytes or text almost never pass for all.
void check_splat_records(const uint8_t* data, size_t size, const std::string& source) {
  if (size % kSplatRecordBytes != 0)
    throw Error(source, "not a scene file: no PLY, .spz or .sog header, and " + std::to_string(size) +
                            " bytes is not a multiple of the 32-byte .splat record");
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
}

}  // namespace

const char* splat_format_name(SplatFormat f) {
  switch (f) {
    case SplatFormat::kPly: return "PLY";
    case SplatFormat::kSplat: return ".splat";
    case SplatFormat::kCompressedPly: return "compressed PLY";
    case SplatFormat::kSpz: return ".spz";
    case SplatFormat::kSog: return ".sog";
  }
  return "?";
}

bool format_keeps_sh(SplatFormat f) { return f != SplatFormat::kSplat; }

SplatFormat detect_splat_format(const uint8_t* data, size_t size, const std::string& source) {
  if (size == 0) throw Error(source, "empty file: not a scene");
  if (size >= 4 && std::memcmp(data, "ply", 3) == 0 && (data[3] == '\n' || data[3] == '\r'))
    return is_compressed_ply(data, size) ? SplatFormat::kCompressedPly : SplatFormat::kPly;
  if (looks_like_spz(data, size)) return SplatFormat::kSpz;
  if (looks_like_zip(data, size)) return SplatFormat::kSog;
  check_splat_records(data, size, source);
  return SplatFormat::kSplat;
}

GaussianScene parse_gaussians(const uint8_t* data, size_t size, SplatFormat format, const std::string& source,
                              std::vector<std::string>* notes, const std::function<void(size_t, size_t)>& parsed) {
  switch (format) {
    case SplatFormat::kPly: {
      PlyReadReport report;
      GaussianScene s = parse_ply(data, size, source, &report, parsed);
      if (notes)
        for (const auto& n : report.notes) notes->push_back(source + ": " + n);
      return s;
    }
    case SplatFormat::kSplat: return parse_splat(data, size, source);
    case SplatFormat::kCompressedPly: return parse_compressed_ply(data, size, source);
    case SplatFormat::kSpz: return parse_spz(data, size, source, notes);
    case SplatFormat::kSog: return parse_sog_zip(data, size, source);
  }
  throw Error(source, "unknown format");
}

LoadedGaussians load_gaussians(const std::string& path) {
  LoadedGaussians l;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error(path, "no such file or directory");
  if (fs::is_directory(path, ec)) {
    if (is_sog_dir(path)) {
      l.file = path;
      l.format = SplatFormat::kSog;
      l.scene = read_sog_dir(path);
      return l;
    }
    l.file = find_scene_ply(path);
  } else {
    l.file = path;
  }
  // Mapped, not read: a PLY parse drops the pages it has stored, so the file and the
  // scene are never both in memory.
  const MappedFile file(l.file);
  l.format = detect_splat_format(file.data(), file.size(), l.file);
  SplatFormat named;
  if (format_from_name(l.file, named) && named != l.format &&
      !(named == SplatFormat::kCompressedPly && l.format == SplatFormat::kPly) &&
      !(named == SplatFormat::kPly && l.format == SplatFormat::kCompressedPly))
    l.notes.push_back(l.file + ": named " + fs::path(l.file).extension().string() + " but its content is " +
                      splat_format_name(l.format) + "; read as " + splat_format_name(l.format));
  l.scene = parse_gaussians(file.data(), file.size(), l.format, l.file, &l.notes,
                            [&](size_t offset, size_t length) { file.release(offset, length); });
  return l;
}

SplatFormat output_format_for_path(const std::string& path) {
  SplatFormat f;
  if (!format_from_name(path, f))
    throw Error(path, "unknown output format '" + fs::path(path).extension().string() +
                          "': name the output *.ply (INRIA PLY), *.compressed.ply (SuperSplat), *.splat, *.spz or *.sog");
  return f;
}

std::vector<uint8_t> serialize_gaussians(const GaussianScene& scene, SplatFormat format, std::vector<std::string>* notes,
                                         std::vector<uint32_t>* order, const GaussianWriteOptions& options) {
  if (order) {
    order->resize(scene.size());
    std::iota(order->begin(), order->end(), 0u);
  }
  switch (format) {
    case SplatFormat::kPly: return serialize_ply(scene);
    case SplatFormat::kSplat: return serialize_splat(scene, notes);
    case SplatFormat::kCompressedPly: return serialize_compressed_ply(scene, true, order, notes);
    case SplatFormat::kSpz: {
      SpzWriteOptions o;
      if (options.spz_version) o.version = options.spz_version;
      return serialize_spz(scene, o, notes);
    }
    case SplatFormat::kSog: return serialize_sog(scene, notes);
  }
  throw Error("output", "unknown format");
}

void write_gaussians(const std::string& path, const GaussianScene& scene, const std::vector<std::string>& inputs,
                     std::vector<std::string>* notes, std::vector<uint32_t>* order, const GaussianWriteOptions& options) {
  const SplatFormat f = output_format_for_path(path);
  refuse_overwriting_inputs(path, inputs);
  if (scene.size() == 0) throw Error(path, "refusing to write a scene with no Gaussians");
  if (f == SplatFormat::kPly) {
    if (order) {
      order->resize(scene.size());
      std::iota(order->begin(), order->end(), 0u);
    }
    write_ply(path, scene);  // validates and writes atomically
    return;
  }
  std::vector<uint8_t> bytes;
  try {
    bytes = serialize_gaussians(scene, f, notes, order, options);
  } catch (const Error& e) {
    throw Error(path, e.what());
  }
  write_file_atomic(path, bytes);
}

}  // namespace isegman
