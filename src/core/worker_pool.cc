#include "core/worker_pool.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>

namespace isegman {

namespace {

// How long a pool thread spins for the next call before it sleeps: a click's passes follow
// each other within microseconds to a few milliseconds.
constexpr auto kSpin = std::chrono::microseconds(100);

inline void cpu_relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

// One word per call: the call's number (upper 48 bits) and its worker count (lower 16), so a
// pool thread that wakes late reads both together and never joins a call with the count of
// another. A call cannot finish without every thread its count names, so `body_` stays the
// one of the number such a thread read.
constexpr int kCountBits = 16;
constexpr uint64_t kCountMask = (uint64_t(1) << kCountBits) - 1;

class WorkerPool {
 public:
  WorkerPool() : owner_(::getpid()), capacity_(std::max(2, int(std::thread::hardware_concurrency()))) {}

  bool run(int workers, const std::function<void(int)>& body) {
    if (workers < 2 || workers > capacity_ || ::getpid() != owner_) return false;
    std::unique_lock<std::mutex> lock(busy_, std::try_to_lock);
    if (!lock.owns_lock()) return false;
    while (started_ < workers - 1) {
      try {
        std::thread(&WorkerPool::serve, this, started_ + 1, call_.load(std::memory_order_acquire)).detach();
      } catch (...) {
        return false;
      }
      ++started_;
    }
    body_ = &body;
    pending_.store(workers - 1, std::memory_order_relaxed);
    const uint64_t number = (call_.load(std::memory_order_relaxed) >> kCountBits) + 1;
    call_.store(number << kCountBits | uint64_t(workers));
    if (sleeping_.load() > 0) {  // sequentially consistent with serve's count and check
      { std::lock_guard<std::mutex> l(sleep_); }
      wake_.notify_all();
    }
    body(0);
    const auto until = std::chrono::steady_clock::now() + kSpin;
    while (pending_.load(std::memory_order_acquire) != 0 && std::chrono::steady_clock::now() < until) cpu_relax();
    if (pending_.load(std::memory_order_acquire) != 0) {
      std::unique_lock<std::mutex> l(sleep_);
      caller_waits_ = true;
      done_.wait(l, [&] { return pending_.load(std::memory_order_acquire) == 0; });
      caller_waits_ = false;
    }
    body_ = nullptr;
    return true;
  }

 private:
  // Pool thread `index` (1...), started while `seen` was the latest call.
  void serve(int index, uint64_t seen) {
    for (;;) {
      uint64_t call = call_.load(std::memory_order_acquire);
      const auto until = std::chrono::steady_clock::now() + kSpin;
      while (call == seen && std::chrono::steady_clock::now() < until) {
        cpu_relax();
        call = call_.load(std::memory_order_acquire);
      }
      if (call == seen) {
        std::unique_lock<std::mutex> l(sleep_);
        sleeping_.fetch_add(1);
        wake_.wait(l, [&] { return (call = call_.load()) != seen; });
        sleeping_.fetch_sub(1);
      }
      seen = call;
      if (index >= int(call & kCountMask)) continue;
      (*body_)(index);
      if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
        std::lock_guard<std::mutex> l(sleep_);
        if (caller_waits_) done_.notify_one();
      }
    }
  }

  const pid_t owner_;
  const int capacity_;
  std::mutex busy_;  // held by the call being served
  int started_ = 0;  // pool threads started (under busy_)
  std::atomic<uint64_t> call_{0};
  std::atomic<int> pending_{0};   // pool threads still in the call
  std::mutex sleep_;               // guards the sleeps below and caller_waits_
  std::condition_variable wake_;   // pool threads sleeping for the next call
  std::condition_variable done_;   // the caller sleeping for the last pool thread
  std::atomic<int> sleeping_{0};   // pool threads in (or about to enter) wake_'s wait
  bool caller_waits_ = false;
  const std::function<void(int)>* body_ = nullptr;
};

}  // namespace

bool run_on_pool(int workers, const std::function<void(int)>& body) {
  // Never destroyed: its threads sleep until the process ends, and no exit path waits on them.
  static WorkerPool* const pool = new WorkerPool;
  return pool->run(workers, body);
}

}  // namespace isegman
