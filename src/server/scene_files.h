// The scenes the page can combine with the one being edited: files and scene folders
// inside the data folder (`--data-dir`, listed, never anything outside it), and scenes
// uploaded from the browser (bounded in size, checked by parsing, kept in a temporary
// folder of this server that is removed when it stops).
#pragma once

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

namespace isegman::server {

struct SceneFileEntry {
  std::string name;    // data folder: the path relative to it; uploads: the stored name
  std::string kind;    // "file" or "folder" (a trainer scene folder or a SOG folder)
  uint64_t bytes = 0;  // files only
  size_t gaussians = 0;  // uploads: what the upload parsed to
};

class SceneFiles {
 public:
  // `data_dir` "": no listing. Uploads go to a fresh folder under the system's temp dir.
  SceneFiles(std::string data_dir, uint64_t max_upload_bytes);
  ~SceneFiles();
  SceneFiles(const SceneFiles&) = delete;
  SceneFiles& operator=(const SceneFiles&) = delete;

  // Splat files (by extension: .ply, .splat, .spz, .sog) and scene folders inside the
  // data folder, at most 3 levels deep and `limit` entries, hidden names and symlinks
  // skipped, sorted by path.
  std::vector<SceneFileEntry> list_data(size_t limit = 500) const;
  std::vector<SceneFileEntry> list_uploads() const;

  // Parses `bytes` (any io format but a SOG folder), then stores them under a name made
  // from `name` (its base name; letters, digits, '.', '-', '_' kept; a suffix -2, -3, ...
  // when taken). AppError(kInvalid) for a bad name, an oversized or unparsable body.
  SceneFileEntry upload(const std::string& name, const std::string& bytes);
  // The stored file of an upload; AppError(kNotFound) when there is none of that name.
  std::string upload_path(const std::string& name) const;
  uint64_t max_upload_bytes() const { return max_upload_bytes_; }

 private:
  const std::string data_dir_;
  const uint64_t max_upload_bytes_;
  std::string upload_dir_;  // created on the first upload
  mutable std::mutex mu_;
  std::vector<SceneFileEntry> uploads_;
};

}  // namespace isegman::server
