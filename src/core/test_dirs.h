// Test helpers for file-system tests: a fresh folder per test and process (removed at
// exit), and a path with a NUL byte in it (which no file can have).
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

namespace isegman::testing {

// Paths a test process made in the temp folder, removed when it exits (by the process that
// made them, not a forked child), so repeated runs do not pile folders up there. Set
// ISEGMAN_KEEP_TEST_DIRS to keep them for a look after a failure.
class RemovedAtExit {
 public:
  static void add(const std::filesystem::path& p) {
    RemovedAtExit& r = instance();
    std::lock_guard<std::mutex> lock(r.mutex_);
    r.paths_.push_back(p);
  }
  ~RemovedAtExit() {
    if (::getpid() != owner_ || std::getenv("ISEGMAN_KEEP_TEST_DIRS")) return;
    for (const std::filesystem::path& p : paths_) {
      std::error_code ec;
      std::filesystem::remove_all(p, ec);
    }
  }

 private:
  static RemovedAtExit& instance() {
    static RemovedAtExit r;
    return r;
  }
  const pid_t owner_ = ::getpid();
  std::mutex mutex_;
  std::vector<std::filesystem::path> paths_;
};

// <temp>/<prefix><name>-<pid>, emptied and created; removed when the process exits.
inline std::string fresh_temp_dir(const std::string& prefix, const std::string& name) {
  const std::filesystem::path p =
      std::filesystem::temp_directory_path() / (prefix + name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(p);
  std::filesystem::create_directories(p);
  RemovedAtExit::add(p);
  return p.string();
}

inline std::string path_with_nul(const std::string& dir) {
  std::string p = dir + "/a";
  p.push_back('\0');
  return p + "b";
}

}  // namespace isegman::testing
