// Subcommand registry of the `isegman` executable: each cmd_*.cc registers itself.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace isegman::app {

using CommandFn = std::function<int(const std::vector<std::string>& args)>;

struct CommandInfo {
  std::string summary;  // one line for `isegman help`
  std::string usage;    // full usage text
  CommandFn run;
};

std::map<std::string, CommandInfo>& command_registry();

struct RegisterCommand {
  RegisterCommand(const std::string& name, const std::string& summary, const std::string& usage, CommandFn fn) {
    command_registry()[name] = CommandInfo{summary, usage, std::move(fn)};
  }
};

}  // namespace isegman::app
