#include "server/input_paths.h"

#include <filesystem>

#include "server/app_error.h"

namespace fs = std::filesystem;

namespace isegman::server {

std::string default_data_dir(const SceneBundle& bundle) {
  if (bundle.ply_path.empty()) return "";
  const fs::path p = fs::absolute(bundle.ply_path).lexically_normal();
  const fs::path iteration = p.parent_path(), point_cloud = iteration.parent_path();
  if (p.filename() == "point_cloud.ply" && point_cloud.filename() == "point_cloud")
    return point_cloud.parent_path().parent_path().string();
  return p.parent_path().string();
}

namespace {

bool inside(const fs::path& base, const fs::path& p) {
  auto b = base.begin(), r = p.begin();
  for (; b != base.end(); ++b, ++r)
    if (r == p.end() || *b != *r) return false;
  return true;
}

}  // namespace

std::string resolve_input_path(const std::string& data_dir, const std::string& path) {
  if (data_dir.empty()) invalid("path: the server was started without a data folder (--data-dir)");
  if (path.empty()) invalid("path: empty");
  if (path.size() > 4096) invalid("path: longer than 4096 characters");
  if (path.find('\0') != std::string::npos) invalid("path: contains a NUL character");
  std::error_code ec;
  const fs::path base = fs::weakly_canonical(fs::absolute(data_dir), ec);
  if (ec) invalid("path: the data folder cannot be read");
  const fs::path given(path);
  const fs::path joined = given.is_absolute() ? given : base / given;
  // Symlinks of the existing prefix are followed, ".." is resolved: what remains must
  // still lie under the data folder. The same answer for every outside path, existing
  // or not.
  const fs::path resolved = fs::weakly_canonical(joined, ec);
  const std::string outside = "path: must lie inside the data folder " + base.string() + " (--data-dir)";
  if (ec || !inside(base, resolved)) invalid(outside);
  if (!fs::exists(resolved, ec)) invalid("path: " + path.substr(0, 200) + ": no such file or folder in the data folder");
  return resolved.string();
}

}  // namespace isegman::server
