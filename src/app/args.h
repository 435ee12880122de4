// A small, strict command-line parser: --flag value, --flag=value, repeated flags,
// positionals. Unknown flags are errors, so typos never pass silently.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

namespace isegman::app {

class Args {
 public:
  // `value_flags` take a value; `switch_flags` do not. Throws Error on unknown flags.
  Args(const std::vector<std::string>& argv, const std::set<std::string>& value_flags,
       const std::set<std::string>& switch_flags);

  bool has(const std::string& flag) const;
  std::string get(const std::string& flag, const std::string& fallback = "") const;
  std::vector<std::string> all(const std::string& flag) const;
  double get_double(const std::string& flag, double fallback) const;
  int get_int(const std::string& flag, int fallback) const;
  const std::vector<std::string>& positionals() const { return positionals_; }
  // The i-th positional or an error naming what was expected.
  const std::string& positional(size_t i, const std::string& what) const;

 private:
  std::map<std::string, std::vector<std::string>> values_;
  std::vector<std::string> positionals_;
};

// --threads N: 0 (all cores) to kMaxThreads; more would only fail to start or waste memory.
int threads_arg(const Args& args);
// --background r,g,b with each component in [0, 1].
std::vector<float> background_arg(const Args& args, std::vector<float> fallback);

// Parses "a,b,c" into doubles, requiring exactly `count` values when count > 0.
std::vector<double> parse_numbers(const std::string& text, size_t count, const std::string& what);

}  // namespace isegman::app
