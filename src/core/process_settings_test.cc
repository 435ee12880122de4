#include "core/process_settings.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/test_dirs.h"

namespace isegman {
namespace {

// Runs restart_with_process_settings in a child whose environment is `env` (name, value;
// a null value unsets), with /bin/sh standing in for the program: the restarted "program"
// writes the three variables to a file. Returns that file's text, or "returned" when the
// call came back without a restart.
std::string restart_in_child(const std::vector<std::pair<const char*, const char*>>& env) {
  static const std::string dir = testing::fresh_temp_dir("isegman-", "process-settings");
  const std::string out = dir + "/env.txt";
  std::filesystem::remove(out);
  const pid_t child = ::fork();
  if (child == 0) {
    for (const auto& [name, value] : env) value ? setenv(name, value, 1) : unsetenv(name);
    const std::string script =
        "printf '%s|%s|%s' \"$GLIBC_TUNABLES\" \"$OMP_WAIT_POLICY\" \"$ISEGMAN_RESTARTED\" > '" + out + "'";
    char* argv[] = {const_cast<char*>("sh"), const_cast<char*>("-c"), const_cast<char*>(script.c_str()), nullptr};
    restart_with_process_settings(argv, "/bin/sh");
    std::ofstream(out) << "returned";
    std::_Exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  std::stringstream text;
  text << std::ifstream(out).rdbuf();
  return text.str();
}

TEST(ProcessSettings, AFreshStartRestartsOnceWithHugePagesAndPassiveOpenMP) {
  EXPECT_EQ(restart_in_child({{"GLIBC_TUNABLES", nullptr}, {"OMP_WAIT_POLICY", nullptr}, {"ISEGMAN_RESTARTED", nullptr}}),
            "glibc.malloc.hugetlb=1|PASSIVE|1");
}

TEST(ProcessSettings, TheUsersOwnSettingsAreKept) {
  // Other tunables stay, the huge-page one is added after them.
  EXPECT_EQ(restart_in_child({{"GLIBC_TUNABLES", "glibc.malloc.arena_max=2"},
                              {"OMP_WAIT_POLICY", "ACTIVE"},
                              {"ISEGMAN_RESTARTED", nullptr}}),
            "glibc.malloc.arena_max=2:glibc.malloc.hugetlb=1|ACTIVE|1");
  // hugetlb=0 switches it off; with OpenMP's policy set too nothing is missing: no restart.
  EXPECT_EQ(restart_in_child({{"GLIBC_TUNABLES", "glibc.malloc.hugetlb=0"},
                              {"OMP_WAIT_POLICY", "PASSIVE"},
                              {"ISEGMAN_RESTARTED", nullptr}}),
            "returned");
}

TEST(ProcessSettings, ARestartedProcessNeverRestartsAgain) {
  EXPECT_EQ(restart_in_child({{"GLIBC_TUNABLES", nullptr}, {"OMP_WAIT_POLICY", nullptr}, {"ISEGMAN_RESTARTED", "1"}}),
            "returned");
}

}  // namespace
}  // namespace isegman
