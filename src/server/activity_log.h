// The app's activity log (what the page lists: segmentation ready, edits, exports) and
// the status version the page polls to notice changes. Thread-safe.
#pragma once

#include <atomic>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

namespace isegman::server {

struct LogEntry {
  uint64_t seq = 0;
  double time = 0;           // seconds since the epoch
  std::string level;         // info, warn, error
  std::string text;
};

class ActivityLog {
 public:
  void note(const std::string& text, const std::string& level = "info");
  // Newest first, at most `kKept`.
  std::vector<LogEntry> entries() const;
  // Anything the page shows changed.
  void bump() { ++version_; }
  uint64_t version() const { return version_.load(); }

  static constexpr size_t kKept = 60;

 private:
  mutable std::mutex mu_;
  std::deque<LogEntry> log_;
  uint64_t seq_ = 0;
  std::atomic<uint64_t> version_{1};
};

}  // namespace isegman::server
