// The one exception type of isegman: every message names the file (or input) and the problem.
#pragma once

#include <stdexcept>
#include <string>

namespace isegman {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
  // "<file>: <problem>" — the form every input error takes.
  Error(const std::string& file, const std::string& problem)
      : std::runtime_error(file + ": " + problem) {}
};

}  // namespace isegman
