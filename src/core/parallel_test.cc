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
