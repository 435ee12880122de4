#include "core/atomic_write.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <random>

#include "core/error.h"

namespace isegman {
namespace {

// Temporaries being written, for the signal handler. Fixed slots of fixed buffers:
// the handler may only call async-signal-safe functions (unlink, signal, raise).
constexpr int kSlots = 64;
constexpr size_t kPathMax = 4096;
char g_paths[kSlots][kPathMax];
std::atomic<bool> g_claimed[kSlots];  // slot owned by a writer
std::atomic<bool> g_used[kSlots];     // path complete: the handler may remove it
std::atomic<int> g_in_flight{0};

extern "C" void remove_temporaries_and_die(int sig) {
  for (int i = 0; i < kSlots; ++i)
    if (g_used[i].load()) ::unlink(g_paths[i]);
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

// Installs the cleanup handler for SIGINT/SIGTERM where nobody else handles them
// (commands with their own handler, e.g. `semantic`'s Ctrl-C, keep theirs).
void install_handlers_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int sig : {SIGINT, SIGTERM}) {
      struct sigaction old {};
      if (::sigaction(sig, nullptr, &old) != 0) continue;
      if (!(old.sa_flags & SA_SIGINFO) && old.sa_handler == SIG_DFL) {
        struct sigaction sa {};
        sa.sa_handler = remove_temporaries_and_die;
        sigemptyset(&sa.sa_mask);
        ::sigaction(sig, &sa, nullptr);
      }
    }
  });
}

// Registers a temporary for removal on a signal; returns its slot (-1: none free, the
// file is then only removed on ordinary failure).
int track(const std::string& tmp) {
  if (tmp.size() >= kPathMax) return -1;
  for (int i = 0; i < kSlots; ++i) {
    bool expected = false;
    if (!g_claimed[i].compare_exchange_strong(expected, true)) continue;
    std::memcpy(g_paths[i], tmp.c_str(), tmp.size() + 1);
    g_used[i] = true;
    return i;
  }
  return -1;
}

void untrack(int slot) {
  if (slot < 0) return;
  g_used[slot] = false;
  g_claimed[slot] = false;
}

std::string random_suffix() {
  static std::mutex mu;
  static std::mt19937_64 rng(std::random_device{}() ^ (uint64_t(::getpid()) << 32));
  std::lock_guard<std::mutex> lock(mu);
  char buf[24];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(rng()));
  return buf;
}

// ".<name>.tmp-<pid>-<random>" in the target's own folder, so the rename stays on one
// file system and the hidden name keeps it out of listings.
std::string temporary_name(const std::string& path) {
  const size_t slash = path.rfind('/');
  const std::string dir = slash == std::string::npos ? "" : path.substr(0, slash + 1);
  const std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  return dir + "." + base + ".tmp-" + std::to_string(::getpid()) + "-" + random_suffix();
}

}  // namespace

int atomic_writes_in_flight() { return g_in_flight.load(); }

void write_file_atomic(const std::string& path, const void* bytes, size_t size) {
  if (path.empty()) throw Error("cannot write a file with an empty name");
  if (path.find('\0') != std::string::npos) throw Error(path, "the file name contains a NUL character");
  if (path.back() == '/') throw Error(path, "names a folder, not a file");
  install_handlers_once();
  std::string tmp;
  int fd = -1, slot = -1;
  for (int attempt = 0; attempt < 16 && fd < 0; ++attempt) {
    tmp = temporary_name(path);
    // Tracked before it exists, so a signal arriving right after the open still removes it.
    slot = track(tmp);
    fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd >= 0) break;
    const int err = errno;
    untrack(slot);  // not ours (EEXIST) or not created: never remove it
    slot = -1;
    errno = err;
    if (err != EEXIST) break;
  }
  if (fd < 0) throw Error(path, std::string("cannot create output: ") + std::strerror(errno));
  ++g_in_flight;
  auto fail = [&](const std::string& what, int err) {
    if (fd >= 0) ::close(fd);
    ::unlink(tmp.c_str());
    untrack(slot);
    --g_in_flight;
    throw Error(path, what + std::strerror(err));
  };
  const auto* p = static_cast<const uint8_t*>(bytes);
  size_t left = size;
  while (left > 0) {
    ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail("write failed: ", n < 0 ? errno : ENOSPC);
    p += n;
    left -= size_t(n);
  }
  if (::fsync(fd) != 0) fail("write failed: ", errno);
  const int closed = ::close(fd);
  fd = -1;
  if (closed != 0) fail("write failed: ", errno);
  if (::rename(tmp.c_str(), path.c_str()) != 0) fail("cannot move the finished file into place: ", errno);
  untrack(slot);
  --g_in_flight;
}

}  // namespace isegman
