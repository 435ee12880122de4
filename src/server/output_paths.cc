#include "server/output_paths.h"

#include <algorithm>
#include <filesystem>

#include "core/error.h"
#include "server/app_error.h"

namespace fs = std::filesystem;

namespace isegman::server {

std::string resolve_output_path(const std::string& root, const std::string& relative,
                                const std::vector<std::string>& extensions) {
  if (relative.empty()) invalid("path: empty");
  if (relative.size() > 200) invalid("path: longer than 200 characters");
  for (char c : relative) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
                    c == '-' || c == '.' || c == '/';
    if (!ok) invalid("path: only letters, digits, '_', '-', '.' and '/' are allowed");
  }
  const fs::path rel(relative);
  if (rel.is_absolute()) invalid("path: must be relative to the output directory");
  for (const fs::path& part : rel) {
    const std::string p = part.string();
    if (p.empty() || p == "." || p == "..") invalid("path: '.' and '..' components are not allowed");
    if (p[0] == '.') invalid("path: hidden names (starting with '.') are not allowed");
  }
  const std::string ext = rel.extension().string();
  if (std::find(extensions.begin(), extensions.end(), ext) == extensions.end()) {
    std::string list;
    for (const auto& e : extensions) list += (list.empty() ? "" : ", ") + e;
    invalid("path: the extension must be one of " + list);
  }
  std::error_code ec;
  fs::create_directories(root, ec);
  const fs::path base = fs::weakly_canonical(fs::absolute(root), ec);
  if (ec) throw Error("output directory " + root, ec.message());
  const fs::path target = base / rel;
  fs::create_directories(target.parent_path(), ec);
  if (ec) invalid("path: cannot create " + target.parent_path().string() + ": " + ec.message());
  // Resolve symlinks in what exists now: the result must still lie under the root.
  const fs::path resolved = fs::weakly_canonical(target, ec);
  if (ec) invalid("path: " + ec.message());
  auto b = base.begin(), r = resolved.begin();
  for (; b != base.end(); ++b, ++r)
    if (r == resolved.end() || *b != *r) invalid("path: leads outside the output directory");
  if (fs::is_directory(resolved)) invalid("path: names a directory");
  return resolved.string();
}

}  // namespace isegman::server
