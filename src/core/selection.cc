#include "core/selection.h"

#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>

#include "core/atomic_write.h"
#include "core/error.h"
#include "core/scene.h"

namespace isegman {
namespace {

constexpr char kMagic[8] = {'I', 'S', 'E', 'G', 'S', 'E', 'L', '\0'};
constexpr uint32_t kVersion = 1;
constexpr size_t kHeaderSize = 40;

void put_u32(std::vector<uint8_t>& out, uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
}
void put_u64(std::vector<uint8_t>& out, uint64_t v) {
  for (int i = 0; i < 8; ++i) out.push_back(uint8_t(v >> (8 * i)));
}
uint32_t get_u32(const uint8_t* p) {
  uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= uint32_t(p[i]) << (8 * i);
  return v;
}
uint64_t get_u64(const uint8_t* p) {
  uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v |= uint64_t(p[i]) << (8 * i);
  return v;
}

}  // namespace

Selection Selection::none_of(const GaussianScene& scene) {
  Selection s;
  s.gaussian_count = scene.size();
  s.mask.assign(scene.size(), false);
  s.scene_fingerprint = scene.fingerprint();
  return s;
}

Selection Selection::all_of(const GaussianScene& scene) {
  Selection s = none_of(scene);
  s.mask.assign(scene.size(), true);
  return s;
}

Selection Selection::from_mask(const GaussianScene& scene, std::vector<bool> mask) {
  return from_mask(scene, std::move(mask), scene.fingerprint());
}

Selection Selection::from_mask(const GaussianScene& scene, std::vector<bool> mask, uint64_t scene_fingerprint) {
  if (mask.size() != scene.size())
    throw Error("selection", "mask has " + std::to_string(mask.size()) + " flags but the scene has " +
                                 std::to_string(scene.size()) + " Gaussians");
  Selection s;
  s.gaussian_count = scene.size();
  s.mask = std::move(mask);
  s.scene_fingerprint = scene_fingerprint;
  return s;
}

size_t Selection::count() const {
  size_t n = 0;
  for (bool b : mask) n += b ? 1 : 0;
  return n;
}

void Selection::validate(const std::string& source) const {
  if (mask.size() != gaussian_count)
    throw Error(source, "selection mask has " + std::to_string(mask.size()) + " flags for " +
                            std::to_string(gaussian_count) + " Gaussians");
  if (!score.empty() && score.size() != gaussian_count)
    throw Error(source, "selection has " + std::to_string(score.size()) + " scores for " +
                            std::to_string(gaussian_count) + " Gaussians");
  for (size_t i = 0; i < score.size(); ++i)
    if (!std::isfinite(score[i]))
      throw Error(source, "selection score of Gaussian " + std::to_string(i) + " is not finite");
}

void Selection::check_matches(const GaussianScene& scene, const std::string& source) const {
  check_matches(scene, scene.fingerprint(), source);
}

void Selection::check_matches(const GaussianScene& scene, uint64_t current_fingerprint, const std::string& source) const {
  validate(source);
  if (gaussian_count != scene.size())
    throw Error(source, "selection was made for a scene of " + std::to_string(gaussian_count) +
                            " Gaussians, this scene has " + std::to_string(scene.size()));
  // Selection files saved before 2026-11-26 carry the scene's legacy fingerprint.
  if (scene_fingerprint != current_fingerprint && scene_fingerprint != scene.legacy_fingerprint())
    throw Error(source, "selection was made for a different scene (fingerprint mismatch: the scene's "
                        "Gaussians changed since the selection was made)");
}

std::vector<uint8_t> serialize_selection(const Selection& sel) {
  sel.validate("selection");
  std::vector<uint8_t> out;
  const size_t n = sel.gaussian_count;
  out.reserve(kHeaderSize + (n + 7) / 8 + (sel.score.empty() ? 0 : 4 * n));
  for (char c : kMagic) out.push_back(uint8_t(c));
  put_u32(out, kVersion);
  put_u32(out, sel.score.empty() ? 0u : 1u);
  put_u64(out, n);
  put_u64(out, sel.scene_fingerprint);
  put_u64(out, sel.count());
  const size_t bits_at = out.size();
  out.resize(bits_at + (n + 7) / 8, 0);
  for (size_t i = 0; i < n; ++i)
    if (sel.mask[i]) out[bits_at + i / 8] |= uint8_t(1u << (i % 8));
  for (float f : sel.score) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    put_u32(out, u);
  }
  return out;
}

Selection parse_selection(const uint8_t* data, size_t size, const std::string& source) {
  if (size < kHeaderSize)
    throw Error(source, "not an isegman selection file (" + std::to_string(size) + " bytes, header needs 40)");
  if (std::memcmp(data, kMagic, 8) != 0)
    throw Error(source, "not an isegman selection file (magic \"ISEGSEL\" missing)");
  const uint32_t version = get_u32(data + 8);
  if (version != kVersion)
    throw Error(source, "selection file version " + std::to_string(version) + " is not supported (expected 1)");
  const uint32_t flags = get_u32(data + 12);
  if (flags & ~1u) throw Error(source, "selection file has unknown flags " + std::to_string(flags));
  const uint64_t n = get_u64(data + 16);
  const bool has_score = flags & 1u;
  // Guard the size arithmetic before trusting n.
  if (n > (uint64_t(1) << 40)) throw Error(source, "selection file claims " + std::to_string(n) + " Gaussians");
  const uint64_t expected = kHeaderSize + (n + 7) / 8 + (has_score ? 4 * n : 0);
  if (size != expected)
    throw Error(source, "selection file is " + std::to_string(size) + " bytes, expected " +
                            std::to_string(expected) + " for " + std::to_string(n) + " Gaussians" +
                            (size < expected ? " (truncated)" : " (trailing data)"));
  Selection sel;
  sel.gaussian_count = size_t(n);
  sel.scene_fingerprint = get_u64(data + 24);
  const uint64_t declared = get_u64(data + 32);
  const uint8_t* bits = data + kHeaderSize;
  sel.mask.resize(size_t(n));
  for (size_t i = 0; i < n; ++i) sel.mask[i] = (bits[i / 8] >> (i % 8)) & 1u;
  if (n % 8 != 0 && (bits[n / 8] >> (n % 8)) != 0)
    throw Error(source, "selection file has mask bits set past the last Gaussian");
  if (sel.count() != declared)
    throw Error(source, "selection file declares " + std::to_string(declared) + " selected Gaussians but its mask has " +
                            std::to_string(sel.count()));
  if (has_score) {
    const uint8_t* p = bits + (n + 7) / 8;
    sel.score.resize(size_t(n));
    for (size_t i = 0; i < n; ++i) {
      uint32_t u = get_u32(p + 4 * i);
      std::memcpy(&sel.score[i], &u, 4);
    }
  }
  sel.validate(source);
  return sel;
}

Selection read_selection(const std::string& path) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) throw Error(path, std::string("cannot open selection: ") + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) throw Error(path, "is a directory, expected a selection file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, "cannot open selection for reading");
  std::vector<uint8_t> data(size_t(st.st_size));
  if (!data.empty() && !in.read(reinterpret_cast<char*>(data.data()), std::streamsize(data.size())))
    throw Error(path, "read failed");
  return parse_selection(data.data(), data.size(), path);
}

void write_selection(const std::string& path, const Selection& selection) {
  std::vector<uint8_t> bytes;
  try {
    bytes = serialize_selection(selection);
  } catch (const Error& e) {
    throw Error(path, e.what());
  }
  write_file_atomic(path, bytes.data(), bytes.size());
}

}  // namespace isegman
