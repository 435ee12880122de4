// A selection of Gaussians (per-Gaussian boolean, optional per-Gaussian score) tied to
// the scene it was made on, and its on-disk format (.isel).
//
// File format (little-endian, version 1):
//   offset  size  field
//   0       8     magic "ISEGSEL\0"
//   8       4     uint32 version = 1
//   12      4     uint32 flags: bit 0 = scores present
//   16      8     uint64 gaussian_count N
//   24      8     uint64 scene_fingerprint (GaussianScene::fingerprint() of the scene; files saved
//                  before 2026-11-26 carry its legacy_fingerprint(), also accepted)
//   32      8     uint64 selected count (number of true bits; checked on read)
//   40      ceil(N/8)  mask bits, Gaussian i in byte i/8, bit i%8 (LSB first);
//                      bits past N must be zero
//   ...     4N    float32 scores (only when flag bit 0 is set), finite
// Nothing may follow. Files are written atomically (temporary file + rename).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace isegman {

struct GaussianScene;

struct Selection {
  std::vector<bool> mask;    // gaussian_count flags: true = selected
  std::vector<float> score;  // empty, or gaussian_count values (e.g. vote ratios)
  uint64_t scene_fingerprint = 0;
  size_t gaussian_count = 0;

  // An empty selection (nothing selected) for `scene`.
  static Selection none_of(const GaussianScene& scene);
  // Everything selected.
  static Selection all_of(const GaussianScene& scene);
  // Wraps a mask made for `scene` (mask.size() must equal scene.size()).
  static Selection from_mask(const GaussianScene& scene, std::vector<bool> mask);
  // The same, for a caller that keeps the scene's fingerprint (scene.fingerprint(), which
  // reads every parameter: 94 ms at 6M Gaussians) current itself.
  static Selection from_mask(const GaussianScene& scene, std::vector<bool> mask, uint64_t scene_fingerprint);

  size_t count() const;  // number of selected Gaussians
  bool empty() const { return count() == 0; }

  // Throws Error(source, ...) when mask/score sizes disagree with gaussian_count or a
  // score is not finite.
  void validate(const std::string& source) const;
  // Throws Error(source, ...) when the selection was made for another scene (different
  // Gaussian count or fingerprint).
  void check_matches(const GaussianScene& scene, const std::string& source) const;
  // The same against a fingerprint the caller keeps current (scene.fingerprint()).
  void check_matches(const GaussianScene& scene, uint64_t current_fingerprint, const std::string& source) const;
};

// Reads a selection file; throws Error(path, problem) on a bad magic, version, size,
// count mismatch or truncated/oversized file.
Selection read_selection(const std::string& path);
// Writes a selection file atomically; throws Error(path, problem).
void write_selection(const std::string& path, const Selection& selection);

// In-memory forms of the same format (used by the file functions and tests).
std::vector<uint8_t> serialize_selection(const Selection& selection);
Selection parse_selection(const uint8_t* data, size_t size, const std::string& source);

}  // namespace isegman
