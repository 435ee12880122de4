// Test helpers for file-system tests: a fresh folder per test and process, and a path
// with a NUL byte in it (which no file can have).
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>

namespace isegman::testing {

// <temp>/<prefix><name>-<pid>, emptied and created.
inline std::string fresh_temp_dir(const std::string& prefix, const std::string& name) {
  const std::filesystem::path p =
      std::filesystem::temp_directory_path() / (prefix + name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(p);
  std::filesystem::create_directories(p);
  return p.string();
}

inline std::string path_with_nul(const std::string& dir) {
  std::string p = dir + "/a";
  p.push_back('\0');
  return p + "b";
}

}  // namespace isegman::testing
