// Atomic file output (temporary file in the same folder + fsync + rename), so a crash or
// a full disk never leaves a half-written file. In core so every layer can use it.
//
// The temporary is created exclusively (O_CREAT|O_EXCL|O_NOFOLLOW) under a name nobody
// can predict, so a file or symlink planted beside the target is never followed or
// truncated, and concurrent writers to one path never share a temporary: the last rename
// wins and the target always holds one complete file. Temporaries still open when
// SIGINT/SIGTERM arrive are removed before the process dies.
#pragma once

#include <cstddef>
#include <string>

namespace isegman {

// Writes `bytes` to `path` via ".<name>.tmp-<pid>-<random>" beside it + fsync + rename.
// Throws Error naming the path on failure; the temporary file is removed.
void write_file_atomic(const std::string& path, const void* bytes, size_t size);

// Number of temporaries currently being written (tests and diagnostics).
int atomic_writes_in_flight();

}  // namespace isegman
