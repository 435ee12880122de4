#include "core/process_settings.h"

#include <unistd.h>

#include <cstdlib>
#include <string>

namespace isegman {

void restart_with_process_settings(char** argv, const char* executable) {
  // Set in the restarted process: a C library that drops GLIBC_TUNABLES (a set-user-ID
  // start) cannot make it restart again.
  constexpr const char* kRestarted = "ISEGMAN_RESTARTED";
  if (std::getenv(kRestarted)) return;
  bool missing = false;
  if (!std::getenv("OMP_WAIT_POLICY")) {
    setenv("OMP_WAIT_POLICY", "PASSIVE", 1);
    missing = true;
  }
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  std::string t = tunables ? tunables : "";
  if (t.find("glibc.malloc.hugetlb") == std::string::npos) {
    t += t.empty() ? "glibc.malloc.hugetlb=1" : ":glibc.malloc.hugetlb=1";
    setenv("GLIBC_TUNABLES", t.c_str(), 1);
    missing = true;
  }
  if (!missing) return;
  setenv(kRestarted, "1", 1);
  execv(executable, argv);  // only returns on failure: then carry on as we are
  unsetenv(kRestarted);
}

}  // namespace isegman
