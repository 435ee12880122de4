// One check of everything a command reads and writes, before any work: no output may
// replace an input or another output of the same command, whatever the spelling
// (relative, "..", symlinks, hard links). Paths are resolved against the file system
// (realpath of the deepest existing folder, st_dev + st_ino of existing files); folders
// are created only after every check passed, then tested for writability.
#pragma once

#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace isegman {

class OutputPlan {
 public:
  // A file the command reads (missing files are fine: they cannot be replaced).
  void input(const std::string& path, const std::string& what);
  // A file the command will write. Throws Error at once when it collides with an input or
  // an output registered earlier, names an existing folder, or contains a NUL byte.
  void output(const std::string& path, const std::string& what);
  // Creates the outputs' folders and checks they are writable; throws Error naming the folder.
  void prepare() const;

 private:
  struct Entry {
    std::string path, what;
    std::string resolved;  // absolute, symlinks resolved (an output's last component kept)
    std::string target;    // for an existing symlink: where it leads; else = resolved
    bool exists = false;
    unsigned long long dev = 0, ino = 0;
  };
  struct Index {
    std::map<std::string, Entry> by_path;  // resolved and target paths
    std::map<std::pair<unsigned long long, unsigned long long>, Entry> by_inode;
  };
  static Entry resolve(const std::string& path, const std::string& what, bool is_output);
  static const Entry* find(const Index& index, const Entry& e);
  static void add(Index& index, const Entry& e);
  Index inputs_, outputs_;
  std::set<std::string> dirs_;  // folders of the outputs, created by prepare()
};

// A camera name as a file name in an output folder: path separators become '_' (COLMAP
// names may carry sub-folders); names that would still be unsafe (empty, ".", "..",
// control characters, longer than 200 bytes) are refused with an Error naming the camera.
std::string camera_file_stem(const std::string& camera_name);

}  // namespace isegman
