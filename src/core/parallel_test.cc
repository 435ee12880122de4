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

}  // namespace
}  // namespace isegman
