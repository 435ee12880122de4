#include "server/activity_log.h"

#include <ctime>

namespace isegman::server {

void ActivityLog::note(const std::string& text, const std::string& level) {
  std::lock_guard<std::mutex> lock(mu_);
  log_.push_front({++seq_, double(std::time(nullptr)), level, text});
  if (log_.size() > kKept) log_.pop_back();
  ++version_;
}

std::vector<LogEntry> ActivityLog::entries() const {
  std::lock_guard<std::mutex> lock(mu_);
  return {log_.begin(), log_.end()};
}

}  // namespace isegman::server
