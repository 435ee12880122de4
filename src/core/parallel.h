// parallel_for over task indices with a fixed worker count and dynamic scheduling.
// Results stay deterministic when each task writes only its own outputs.
#pragma once

#include <algorithm>
#include <atomic>
#include <exception>
#include <stdexcept>
#include <functional>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "core/error.h"
#include "core/worker_pool.h"

namespace isegman {

// The most worker threads a command accepts (--threads); more only costs memory.
constexpr int kMaxThreads = 256;

inline int resolve_threads(int requested) {
  if (requested > 0) return requested;
  unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : int(hw);
}

// Calls fn(worker, task) for task in [0, tasks) on `threads` workers (0 = all cores).
inline void parallel_for(size_t tasks, int threads, const std::function<void(int, size_t)>& fn) {
  const int workers = int(std::min<size_t>(size_t(resolve_threads(threads)), std::max<size_t>(tasks, 1)));
  if (workers <= 1) {
    for (size_t t = 0; t < tasks; ++t) fn(0, t);
    return;
  }
  std::atomic<size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  const std::function<void(int)> body = [&](int w) {
    try {
      for (size_t t; (t = next.fetch_add(1)) < tasks;) fn(w, t);
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      next = tasks;
    }
  };
  if (run_on_pool(workers, body)) {
    if (error) std::rethrow_exception(error);
    return;
  }
  // The pool is busy (a parallel_for inside a task, or on another thread) or cannot serve
  // this many: threads of this call's own.
  std::vector<std::thread> pool;
  pool.reserve(size_t(workers));
  std::string start_failure;
  for (int w = 1; w < workers; ++w) {
    try {
      pool.emplace_back(body, w);
    } catch (const std::exception& e) {
      // Out of threads or memory: stop the tasks, join what started, then report.
      start_failure = "cannot start worker thread " + std::to_string(w + 1) + " of " + std::to_string(workers) +
                      " (" + e.what() + "); use fewer threads (--threads)";
      next = tasks;
      break;
    }
  }
  if (start_failure.empty()) body(0);
  for (auto& t : pool) t.join();
  if (!start_failure.empty()) throw Error(start_failure);
  if (error) std::rethrow_exception(error);
}

// The largest chunk of a per-element pass over a long list (a view's votes, a mask's
// Gaussians; list_grain below sizes the chunks).
constexpr size_t kListGrain = size_t(1) << 16;

// The chunk size for a per-element pass over a list of n entries: kListGrain at most, and
// small enough that a list of a few times kListGrain still gives two workers several chunks
// each (in chunks of kListGrain a list of 100k entries leaves one worker idle for a third of
// the pass), and a list of up to 8,192 entries one chunk, run on the calling thread, where
// starting a worker would cost more than the pass. A function of n alone, so what chunks
// sum or sort is the same on any machine.
inline size_t list_grain(size_t n) {
  constexpr size_t kMinGrain = size_t(1) << 13, kChunks = 8;
  const size_t even = (n + kChunks - 1) / kChunks;
  return std::clamp((even + kMinGrain - 1) / kMinGrain * kMinGrain, kMinGrain, kListGrain);
}

// The number of chunks of `grain` entries that [0, n) splits into.
inline size_t chunk_count(size_t n, size_t grain) { return (n + grain - 1) / grain; }

// Splits [0, n) into chunks of `grain` and runs fn(chunk, begin, end) on each, chunk in
// [0, chunk_count(n, grain)): a pass that keeps a result per chunk stores it at `chunk` and
// merges them in chunk order (one chunk: on the calling thread).
inline void parallel_chunks(size_t n, size_t grain, int threads,
                            const std::function<void(size_t, size_t, size_t)>& fn) {
  parallel_for(chunk_count(n, grain), threads,
               [&](int, size_t c) { fn(c, c * grain, std::min(n, (c + 1) * grain)); });
}

// Number of workers parallel_for will actually use for `tasks` tasks.
inline int worker_count(size_t tasks, int threads) {
  return int(std::min<size_t>(size_t(resolve_threads(threads)), std::max<size_t>(tasks, 1)));
}

}  // namespace isegman
