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
  // The root is the folder given at launch: create it; everything below it is checked
  // first (the deepest folder that exists must resolve inside the root) and only then
  // created, so a symlink leading out never gets a folder made at its far end.
  std::error_code ec;
  fs::create_directories(root, ec);
  const fs::path base = fs::weakly_canonical(fs::absolute(root), ec);
  if (ec) throw Error("output directory " + root, ec.message());
  auto inside = [&base](const fs::path& p) {
    auto b = base.begin(), r = p.begin();
    for (; b != base.end(); ++b, ++r)
      if (r == p.end() || *b != *r) return false;
    return true;
  };
  const fs::path target = base / rel;
  fs::path existing = target.parent_path();
  while (existing != base && !fs::exists(fs::symlink_status(existing, ec))) existing = existing.parent_path();
  const fs::path real_existing = fs::canonical(existing, ec);
  if (ec) invalid("path: " + existing.lexically_relative(base).string() + ": " + ec.message());
  if (!inside(real_existing)) invalid("path: leads outside the output directory");
  if (!fs::is_directory(real_existing)) invalid("path: " + existing.lexically_relative(base).string() + " is not a folder");
  fs::create_directories(target.parent_path(), ec);
  if (ec) invalid("path: cannot create " + target.parent_path().string() + ": " + ec.message());
  // Resolve symlinks in what exists now: the result must still lie under the root.
  const fs::path resolved = fs::weakly_canonical(target, ec);
  if (ec) invalid("path: " + ec.message());
  if (!inside(resolved)) invalid("path: leads outside the output directory");
  if (fs::is_directory(resolved)) invalid("path: names a directory");
  return resolved.string();
}

}  // namespace isegman::server
