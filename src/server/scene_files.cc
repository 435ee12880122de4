#include "server/scene_files.h"

#include <stdlib.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "core/atomic_write.h"
#include "core/error.h"
#include "io/gaussian_file.h"
#include "server/app_error.h"

namespace fs = std::filesystem;

namespace isegman::server {

namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

bool splat_extension(const std::string& name) {
  for (const char* e : {".ply", ".splat", ".spz", ".sog"})
    if (ends_with(name, e)) return true;
  return false;
}

// A trainer output folder (point_cloud/) or a SOG folder (meta.json).
bool scene_folder(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p / "point_cloud", ec) || fs::is_regular_file(p / "meta.json", ec);
}

std::string clean_name(const std::string& name) {
  std::string base = fs::path(name).filename().string();
  std::string out;
  for (char c : base)
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_') out += c;
  while (!out.empty() && out[0] == '.') out.erase(0, 1);
  if (out.size() > 100) out = out.substr(out.size() - 100);
  return out;
}

}  // namespace

SceneFiles::SceneFiles(std::string data_dir, uint64_t max_upload_bytes)
    : data_dir_(std::move(data_dir)), max_upload_bytes_(max_upload_bytes) {}

SceneFiles::~SceneFiles() {
  if (upload_dir_.empty()) return;
  std::error_code ec;
  fs::remove_all(upload_dir_, ec);
}

std::vector<SceneFileEntry> SceneFiles::list_data(size_t limit) const {
  std::vector<SceneFileEntry> out;
  if (data_dir_.empty()) return out;
  std::error_code ec;
  const fs::path base = fs::weakly_canonical(fs::absolute(data_dir_), ec);
  if (ec || !fs::is_directory(base, ec)) return out;
  // Symlinks are neither followed nor listed: what is listed lies inside the folder.
  fs::recursive_directory_iterator it(base, fs::directory_options::skip_permission_denied, ec), end;
  for (; !ec && it != end && out.size() < limit; it.increment(ec)) {
    const fs::path& p = it->path();
    const std::string name = p.filename().string();
    std::error_code e2;
    if (name.empty() || name[0] == '.' || it->is_symlink(e2)) {
      if (it->is_directory(e2)) it.disable_recursion_pending();
      continue;
    }
    const std::string rel = p.lexically_relative(base).generic_string();
    if (it->is_directory(e2)) {
      if (scene_folder(p)) {
        out.push_back({rel, "folder", 0, 0});
        it.disable_recursion_pending();  // its insides are the scene
      } else if (it.depth() >= 2) {
        it.disable_recursion_pending();
      }
    } else if (it->is_regular_file(e2) && splat_extension(name)) {
      out.push_back({rel, "file", uint64_t(it->file_size(e2)), 0});
    }
  }
  std::sort(out.begin(), out.end(), [](const SceneFileEntry& a, const SceneFileEntry& b) { return a.name < b.name; });
  return out;
}

std::vector<SceneFileEntry> SceneFiles::list_uploads() const {
  std::lock_guard<std::mutex> lock(mu_);
  return uploads_;
}

SceneFileEntry SceneFiles::upload(const std::string& name, const std::string& bytes) {
  if (bytes.empty()) invalid("upload: the body is empty (send the file's bytes)");
  if (bytes.size() > max_upload_bytes_)
    invalid("upload: " + std::to_string(bytes.size()) + " bytes is more than the limit of " +
            std::to_string(max_upload_bytes_) + " bytes");
  std::string base = clean_name(name);
  if (base.empty()) invalid("name: give a file name such as scene.spz (letters, digits, '.', '-', '_')");
  SceneFileEntry entry;
  try {
    const auto* data = reinterpret_cast<const uint8_t*>(bytes.data());
    const SplatFormat format = detect_splat_format(data, bytes.size(), base);
    const GaussianScene scene = parse_gaussians(data, bytes.size(), format, base);
    entry.gaussians = scene.size();
  } catch (const Error& e) {
    invalid(std::string("upload: ") + e.what());
  }
  if (entry.gaussians == 0) invalid("upload: " + base + " has no Gaussians");
  std::lock_guard<std::mutex> lock(mu_);
  if (upload_dir_.empty()) {
    std::string tmpl = (fs::temp_directory_path() / "isegman-uploads-XXXXXX").string();
    if (!mkdtemp(tmpl.data())) throw AppError(ErrorKind::kUnavailable, "upload: cannot create a temporary folder");
    upload_dir_ = tmpl;
  }
  std::string stored = base;
  const size_t dot = base.find('.');
  for (int k = 2; std::any_of(uploads_.begin(), uploads_.end(), [&](const SceneFileEntry& u) { return u.name == stored; });
       ++k)
    stored = (dot == std::string::npos ? base : base.substr(0, dot)) + "-" + std::to_string(k) +
             (dot == std::string::npos ? "" : base.substr(dot));
  write_file_atomic((fs::path(upload_dir_) / stored).string(), bytes.data(), bytes.size());
  entry.name = stored;
  entry.kind = "file";
  entry.bytes = bytes.size();
  uploads_.push_back(entry);
  return entry;
}

std::string SceneFiles::upload_path(const std::string& name) const {
  std::lock_guard<std::mutex> lock(mu_);
  for (const SceneFileEntry& u : uploads_)
    if (u.name == name) return (fs::path(upload_dir_) / u.name).string();
  throw AppError(ErrorKind::kNotFound, "upload: no uploaded scene named '" + name.substr(0, 100) + "'");
}

}  // namespace isegman::server
