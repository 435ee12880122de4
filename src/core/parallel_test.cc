// Issue 11 item 11: a pool that cannot start all its threads joins what it started and
// reports, instead of std::terminate ("terminate called without an active exception").
#include "core/parallel.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <thread>

#include "core/error.h"

namespace isegman {
namespace {

size_t virtual_memory_bytes() {
  std::ifstream in("/proc/self/statm");
  size_t pages = 0;
  in >> pages;
  return pages * size_t(::sysconf(_SC_PAGESIZE));
}

TEST(ParallelFor, ThreadStartFailureIsReportedNotFatal) {
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    // About 40 thread stacks fit; 1000 threads do not.
    const rlim_t limit = virtual_memory_bytes() + (rlim_t(320) << 20);
    rlimit r{limit, limit};
    ::setrlimit(RLIMIT_AS, &r);
    try {
      std::atomic<size_t> ran{0};
      parallel_for(1000, 1000, [&](int, size_t) { ++ran; });
      std::_Exit(0);  // every thread started (no limit here): nothing to show
    } catch (const Error& e) {
      std::_Exit(std::string(e.what()).find("--threads") != std::string::npos ? 3 : 4);
    } catch (...) {
      std::_Exit(5);
    }
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << "the child died of signal " << WTERMSIG(status);
  if (WEXITSTATUS(status) == 0) GTEST_SKIP() << "1000 threads started under the limit";
  EXPECT_EQ(WEXITSTATUS(status), 3);
}

TEST(ParallelFor, RunsEveryTaskOnce) {
  std::vector<std::atomic<int>> hits(500);
  parallel_for(hits.size(), 8, [&](int, size_t t) { ++hits[t]; });
  for (auto& h : hits) EXPECT_EQ(h.load(), 1);
}

// parallel_for serves calls from threads that stay up (core/worker_pool.h); what a pool can
// get wrong: a late thread joining the wrong call, a lost wake-up, a call inside a task or
// on two threads at once, an exception, a forked child (no pool threads in it).
TEST(ParallelFor, ManyShortCallsRunEveryTaskOnceEachTime) {
  std::vector<std::atomic<int>> hits(7);
  for (int call = 0; call < 3000; ++call) {
    const size_t tasks = 1 + size_t(call) % hits.size();  // changing worker counts
    parallel_for(tasks, 2 + call % 3, [&](int w, size_t t) {
      EXPECT_LT(w, 4);
      ++hits[t];
    });
  }
  int total = 0;
  for (auto& h : hits) total += h.load();
  int expected = 0;
  for (int call = 0; call < 3000; ++call) expected += 1 + call % int(hits.size());
  EXPECT_EQ(total, expected);
}

TEST(ParallelFor, CallsInsideTasksAndOnTwoThreadsAtOnceComplete) {
  std::atomic<int> inner{0};
  parallel_for(4, 2, [&](int, size_t) { parallel_for(50, 2, [&](int, size_t) { ++inner; }); });
  EXPECT_EQ(inner.load(), 200);
  std::atomic<int> ran{0};
  auto caller = [&] {
    for (int i = 0; i < 300; ++i) parallel_for(10, 2, [&](int, size_t) { ++ran; });
  };
  std::thread a(caller), b(caller);
  a.join();
  b.join();
  EXPECT_EQ(ran.load(), 6000);
}

TEST(ParallelFor, ATaskThrowingReachesTheCallerAndTheNextCallRuns) {
  for (int round = 0; round < 20; ++round) {
    EXPECT_THROW(parallel_for(16, 2, [&](int, size_t t) {
                   if (t == size_t(round % 16)) throw Error("task failed");
                 }),
                 Error);
    std::atomic<int> ran{0};
    parallel_for(16, 2, [&](int, size_t) { ++ran; });
    EXPECT_EQ(ran.load(), 16);
  }
}

TEST(ParallelFor, AForkedChildRunsCallsWithoutThePoolsThreads) {
  std::atomic<int> ran{0};
  parallel_for(8, 2, [&](int, size_t) { ++ran; });  // the pool's threads are up
  ASSERT_EQ(ran.load(), 8);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    ::alarm(20);  // a call waiting for threads that do not exist here would hang
    std::atomic<int> in_child{0};
    parallel_for(8, 2, [&](int, size_t) { ++in_child; });
    std::_Exit(in_child.load() == 8 ? 0 : 1);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << "the child died of signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 0);
}

TEST(ParallelChunks, EachChunkGetsItsIndexAndTheRangesCoverTheListOnce) {
  const size_t n = 100001, grain = 8192;
  ASSERT_EQ(chunk_count(n, grain), size_t(13));
  EXPECT_EQ(chunk_count(0, grain), size_t(0));
  std::vector<std::pair<size_t, size_t>> ranges(chunk_count(n, grain));
  std::vector<std::atomic<int>> covered(n);
  parallel_chunks(n, grain, 2, [&](size_t chunk, size_t begin, size_t end) {
    ranges[chunk] = {begin, end};
    for (size_t i = begin; i < end; ++i) ++covered[i];
  });
  for (size_t c = 0; c < ranges.size(); ++c) {
    EXPECT_EQ(ranges[c].first, c * grain);
    EXPECT_EQ(ranges[c].second, std::min(n, (c + 1) * grain));
  }
  for (size_t i = 0; i < n; ++i) ASSERT_EQ(covered[i].load(), 1) << i;
}

TEST(ListGrain, LongListsGiveTwoWorkersSeveralChunksEachAndShortOnesStayWhole) {
  // A short list is one chunk: starting a worker would cost more than the pass.
  EXPECT_EQ(list_grain(1), list_grain(8192));
  EXPECT_GE(list_grain(5000), size_t(5000));
  // 100k entries: eight chunks or more (in chunks of kListGrain it was two, one of 35k).
  for (size_t n : {size_t(50000), size_t(100000), size_t(300000)}) {
    const size_t g = list_grain(n), chunks = (n + g - 1) / g;
    EXPECT_GE(chunks, size_t(6)) << n;
    EXPECT_LE(chunks, size_t(8)) << n;
  }
  // A very long list keeps kListGrain chunks (the per-chunk buffers stay small).
  EXPECT_EQ(list_grain(size_t(1) << 24), kListGrain);
}

}  // namespace
}  // namespace isegman
