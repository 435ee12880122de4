// Background work with progress: one worker thread runs submitted jobs in order, so long
// computations (view embeddings, segmentation rounds) never block the HTTP handlers and
// the page can poll what is happening. The queue is bounded; a full queue is a 503.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace isegman::server {

struct JobStatus {
  uint64_t id = 0;
  std::string name;
  std::string state;  // "queued", "running", "done", "failed" ("" when no job ever ran)
  int done = 0, total = 0;
  std::string message;  // last progress line
  std::string error;    // when failed
  double seconds = 0;   // run time so far / in all
};

class JobRunner {
 public:
  // Reports progress from inside a job: `done` of `total` steps and a line of text.
  using Report = std::function<void(int done, int total, const std::string& message)>;
  using Work = std::function<void(const Report& report)>;

  explicit JobRunner(size_t max_queued = 16);
  ~JobRunner();  // stop()
  JobRunner(const JobRunner&) = delete;
  JobRunner& operator=(const JobRunner&) = delete;

  // Queues a job and returns its id. Throws AppError(kBusy) when the queue is full or
  // the runner has stopped. A job that throws is recorded as failed with the message.
  uint64_t submit(const std::string& name, Work work);

  // The running job, else the most recent one (state "" when none ran yet).
  JobStatus current() const;
  JobStatus find(uint64_t id) const;  // state "" when unknown (pruned or never existed)
  size_t queued() const;
  bool busy() const;  // running or queued
  // Blocks until nothing is running or queued (tests); false on timeout.
  bool wait_idle(double timeout_seconds) const;
  // Drops queued jobs, waits for the running one, joins the worker. Idempotent.
  void stop();

 private:
  struct Entry {
    JobStatus status;
    Work work;
  };
  void loop();

  mutable std::mutex mu_;
  mutable std::condition_variable cv_, idle_cv_;
  std::deque<Entry> queue_;
  JobStatus running_;
  bool has_running_ = false;
  std::deque<JobStatus> finished_;  // recent first, bounded
  size_t max_queued_;
  uint64_t next_id_ = 1;
  bool stopping_ = false;
  std::thread worker_;
};

}  // namespace isegman::server
