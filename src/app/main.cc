// isegman: interactive segmentation and manipulation of 3D Gaussian Splatting scenes.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "app/command.h"
#include "core/process_settings.h"

namespace isegman::app {
std::map<std::string, CommandInfo>& command_registry() {
  static std::map<std::string, CommandInfo> registry;
  return registry;
}
}  // namespace isegman::app

static void print_help() {
  std::printf("isegman: interactive segmentation and manipulation of 3D Gaussian Splatting scenes\n\n"
              "usage: isegman <command> [options]   (isegman help <command> for details)\n\ncommands:\n");
  for (const auto& [name, info] : isegman::app::command_registry())
    std::printf("  %-10s %s\n", name.c_str(), info.summary.c_str());
}

int main(int argc, char** argv) {
  using namespace isegman::app;
  isegman::restart_with_process_settings(argv);
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "help" || args[0] == "--help" || args[0] == "-h") {
    if (args.size() >= 2 && command_registry().count(args[1])) {
      std::printf("%s\n", command_registry()[args[1]].usage.c_str());
      return 0;
    }
    print_help();
    return args.empty() ? 2 : 0;
  }
  auto it = command_registry().find(args[0]);
  if (it == command_registry().end()) {
    std::fprintf(stderr, "isegman: unknown command '%s'\n\n", args[0].c_str());
    print_help();
    return 2;
  }
  std::vector<std::string> rest(args.begin() + 1, args.end());
  for (const auto& a : rest)
    if (a == "--help" || a == "-h") {
      std::printf("%s\n", it->second.usage.c_str());
      return 0;
    }
  try {
    return it->second.run(rest);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "isegman %s: error: %s\n", args[0].c_str(), e.what());
    return 1;
  }
}
