#include "server/jobs.h"

#include <chrono>
#include <exception>

#include "server/app_error.h"

namespace isegman::server {

namespace {
using Clock = std::chrono::steady_clock;
constexpr size_t kFinishedKept = 32;
}  // namespace

JobRunner::JobRunner(size_t max_queued) : max_queued_(max_queued) { worker_ = std::thread([this] { loop(); }); }

JobRunner::~JobRunner() { stop(); }

void JobRunner::stop() {
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (stopping_ && !worker_.joinable()) return;
    stopping_ = true;
    queue_.clear();
  }
  cv_.notify_all();
  if (worker_.joinable() && worker_.get_id() != std::this_thread::get_id()) worker_.join();
  idle_cv_.notify_all();
}

uint64_t JobRunner::submit(const std::string& name, Work work) {
  std::lock_guard<std::mutex> lock(mu_);
  if (stopping_) throw AppError(ErrorKind::kBusy, "the server is shutting down");
  if (queue_.size() >= max_queued_)
    throw AppError(ErrorKind::kBusy, "too many queued jobs (" + std::to_string(queue_.size()) + "); wait for the current work");
  Entry e;
  e.status.id = next_id_++;
  e.status.name = name;
  e.status.state = "queued";
  e.work = std::move(work);
  queue_.push_back(std::move(e));
  cv_.notify_all();
  return queue_.back().status.id;
}

void JobRunner::loop() {
  for (;;) {
    Entry e;
    {
      std::unique_lock<std::mutex> lock(mu_);
      cv_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (stopping_) return;
      e = std::move(queue_.front());
      queue_.pop_front();
      e.status.state = "running";
      running_ = e.status;
      has_running_ = true;
    }
    const auto t0 = Clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - t0).count(); };
    Report report = [this, elapsed](int done, int total, const std::string& message) {
      std::lock_guard<std::mutex> lock(mu_);
      running_.done = done;
      running_.total = total;
      running_.message = message;
      running_.seconds = elapsed();
    };
    std::string error;
    try {
      e.work(report);
    } catch (const std::exception& ex) {
      error = ex.what();
    } catch (...) {
      error = "unknown error";
    }
    {
      std::lock_guard<std::mutex> lock(mu_);
      JobStatus s = running_;
      s.seconds = elapsed();
      s.state = error.empty() ? "done" : "failed";
      s.error = error;
      has_running_ = false;
      finished_.push_front(s);
      if (finished_.size() > kFinishedKept) finished_.pop_back();
    }
    idle_cv_.notify_all();
  }
}

JobStatus JobRunner::current() const {
  std::lock_guard<std::mutex> lock(mu_);
  if (has_running_) {
    return running_;
  }
  if (!queue_.empty()) return queue_.front().status;
  if (!finished_.empty()) return finished_.front();
  return {};
}

JobStatus JobRunner::find(uint64_t id) const {
  std::lock_guard<std::mutex> lock(mu_);
  if (has_running_ && running_.id == id) return running_;
  for (const Entry& e : queue_)
    if (e.status.id == id) return e.status;
  for (const JobStatus& s : finished_)
    if (s.id == id) return s;
  return {};
}

size_t JobRunner::queued() const {
  std::lock_guard<std::mutex> lock(mu_);
  return queue_.size();
}

bool JobRunner::busy() const {
  std::lock_guard<std::mutex> lock(mu_);
  return has_running_ || !queue_.empty();
}

bool JobRunner::wait_idle(double timeout_seconds) const {
  std::unique_lock<std::mutex> lock(mu_);
  return idle_cv_.wait_for(lock, std::chrono::duration<double>(timeout_seconds),
                           [this] { return stopping_ || (!has_running_ && queue_.empty()); });
}

}  // namespace isegman::server
