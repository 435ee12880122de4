// Atomic file output (temporary file in the same folder + fsync + rename), so a crash or
// a full disk never leaves a half-written file. In core so every layer can use it.
#pragma once

#include <cstddef>
#include <string>

namespace isegman {

// Writes `bytes` to `path` via "<path>.tmp-<pid>" + fsync + rename. Throws Error naming
// the path on failure; the temporary file is removed.
void write_file_atomic(const std::string& path, const void* bytes, size_t size);

}  // namespace isegman
