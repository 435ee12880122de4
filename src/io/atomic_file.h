// Writes outputs atomically (temporary file in the same folder + rename), so a crash or
// a full disk never leaves a half-written scene, and never replaces an input by accident.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/atomic_write.h"

namespace isegman {

// write_file_atomic(path, bytes, size) itself lives in core/atomic_write.h.
inline void write_file_atomic(const std::string& path, const std::vector<uint8_t>& bytes) {
  write_file_atomic(path, bytes.data(), bytes.size());
}
inline void write_file_atomic(const std::string& path, const std::string& text) {
  write_file_atomic(path, text.data(), text.size());
}

// Reads a whole file; throws Error naming the path when it cannot be read.
std::vector<uint8_t> read_file_bytes(const std::string& path);

// True when both paths name the same existing file (hard links and symlinks included).
bool same_file(const std::string& a, const std::string& b);

// Throws when `output` is one of `inputs`: outputs never overwrite inputs.
void refuse_overwriting_inputs(const std::string& output, const std::vector<std::string>& inputs);

}  // namespace isegman
