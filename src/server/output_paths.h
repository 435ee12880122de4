// Where the server may write: every output path a request names is relative to the
// configured output directory and must stay inside it (no absolute paths, no "..", no
// hidden names, no symlink leading out), with one of the allowed extensions.
#pragma once

#include <string>
#include <vector>

namespace isegman::server {

// Returns the absolute path of `relative` under `root` (creating `root` and the parent
// folders). Throws AppError(kInvalid) naming the problem.
std::string resolve_output_path(const std::string& root, const std::string& relative,
                                const std::vector<std::string>& extensions);

}  // namespace isegman::server
