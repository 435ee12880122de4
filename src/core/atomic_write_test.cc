// Issue 11 items 4-5: temporaries are exclusive and unpredictable, concurrent writers to
// one path always leave a complete file, and an interrupted write leaves no temporary.
#include "core/atomic_write.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

#include "core/error.h"
#include "core/test_dirs.h"

namespace fs = std::filesystem;

namespace isegman {
namespace {

std::string temp_dir(const std::string& name) { return testing::fresh_temp_dir("isegman-atomic-", name); }

std::string nul_path(const std::string& d) { return testing::path_with_nul(d); }

int temporaries_in(const std::string& dir) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.path().filename().string().find(".tmp-") != std::string::npos;
  return n;
}

std::string slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(AtomicWrite, NeverFollowsAPlantedSymlink) {
  const std::string d = temp_dir("symlink");
  const std::string victim = d + "/victim";
  { std::ofstream(victim) << "precious"; }
  // The old, predictable temporary name, planted as a symlink to the victim.
  fs::create_symlink(victim, d + "/out.ply.tmp-" + std::to_string(::getpid()));
  write_file_atomic(d + "/out.ply", "data", 4);
  EXPECT_EQ(slurp(victim), "precious");
  EXPECT_EQ(slurp(d + "/out.ply"), "data");
  EXPECT_EQ(atomic_writes_in_flight(), 0);
  EXPECT_THROW(write_file_atomic(nul_path(d), "x", 1), Error);
}

TEST(AtomicWrite, ConcurrentWritersLeaveOneCompleteFile) {
  const std::string d = temp_dir("concurrent");
  const std::string target = d + "/same.bin";
  constexpr size_t kSize = 1 << 16;
  std::atomic<bool> done{false};
  std::atomic<int> bad{0}, failures{0};
  std::thread reader([&] {
    while (!done) {
      std::ifstream in(target, std::ios::binary);
      if (!in) continue;  // not written yet
      const std::string s(std::istreambuf_iterator<char>(in), {});
      if (s.size() != kSize || s.find_first_not_of(s[0]) != std::string::npos) ++bad;
    }
  });
  std::vector<std::thread> writers;
  for (int t = 0; t < 100; ++t)
    writers.emplace_back([&, t] {
      const std::vector<char> bytes(kSize, char('A' + t % 26));
      try {
        write_file_atomic(target, bytes.data(), bytes.size());
      } catch (const Error&) {
        ++failures;
      }
    });
  for (auto& w : writers) w.join();
  done = true;
  reader.join();
  EXPECT_EQ(failures.load(), 0);
  EXPECT_EQ(bad.load(), 0);
  EXPECT_EQ(fs::file_size(target), kSize);
  EXPECT_EQ(temporaries_in(d), 0);
}

TEST(AtomicWrite, InterruptedWriteLeavesNoTemporary) {
  const std::string d = temp_dir("signal");
  // A child writes a large file; it is killed by SIGTERM while the temporary exists.
  for (int attempt = 0; attempt < 5; ++attempt) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      std::vector<char> big(size_t(256) << 20, 'x');
      for (;;) write_file_atomic(d + "/big.bin", big.data(), big.size());
    }
    bool seen = false;
    for (int i = 0; i < 20000 && !seen; ++i) {
      seen = temporaries_in(d) > 0;
      if (!seen) ::usleep(500);
    }
    ::kill(child, SIGTERM);
    int status = 0;
    ::waitpid(child, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status));
    EXPECT_EQ(WTERMSIG(status), SIGTERM);
    if (!seen) continue;
    EXPECT_EQ(temporaries_in(d), 0);
    return;
  }
  GTEST_SKIP() << "never caught the child mid-write";
}

}  // namespace
}  // namespace isegman
