#include "app/args.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/error.h"
#include "core/parallel.h"

namespace isegman::app {

Args::Args(const std::vector<std::string>& argv, const std::set<std::string>& value_flags,
           const std::set<std::string>& switch_flags) {
  for (size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    if (a.size() > 2 && a.compare(0, 2, "--") == 0) {
      std::string name = a.substr(2), value;
      bool inline_value = false;
      if (auto eq = name.find('='); eq != std::string::npos) {
        value = name.substr(eq + 1);
        name = name.substr(0, eq);
        inline_value = true;
      }
      if (value_flags.count(name)) {
        if (!inline_value) {
          if (i + 1 >= argv.size()) throw Error("option --" + name + " needs a value");
          value = argv[++i];
        }
        values_[name].push_back(value);
      } else if (switch_flags.count(name)) {
        if (inline_value) throw Error("option --" + name + " takes no value");
        values_[name].push_back("1");
      } else {
        throw Error("unknown option --" + name);
      }
    } else {
      positionals_.push_back(a);
    }
  }
}

bool Args::has(const std::string& f) const { return values_.count(f) > 0; }

std::string Args::get(const std::string& f, const std::string& fallback) const {
  auto it = values_.find(f);
  return it == values_.end() ? fallback : it->second.back();
}

std::vector<std::string> Args::all(const std::string& f) const {
  auto it = values_.find(f);
  return it == values_.end() ? std::vector<std::string>{} : it->second;
}

double Args::get_double(const std::string& f, double fallback) const {
  if (!has(f)) return fallback;
  return parse_numbers(get(f), 1, "--" + f)[0];
}

int Args::get_int(const std::string& f, int fallback) const {
  if (!has(f)) return fallback;
  double v = get_double(f, fallback);
  if (v != std::floor(v) || std::fabs(v) > 1e9) throw Error("--" + f + " must be an integer, got '" + get(f) + "'");
  return int(v);
}

const std::string& Args::positional(size_t i, const std::string& what) const {
  if (i >= positionals_.size()) throw Error("missing argument: " + what);
  return positionals_[i];
}

int threads_arg(const Args& args) {
  const int n = args.get_int("threads", 0);
  if (n < 0 || n > kMaxThreads)
    throw Error("--threads must be between 0 (all cores) and " + std::to_string(kMaxThreads) + ", got " +
                args.get("threads"));
  return n;
}

std::vector<float> background_arg(const Args& args, std::vector<float> fallback) {
  if (!args.has("background")) return fallback;
  const std::vector<double> v = parse_numbers(args.get("background"), 3, "--background");
  for (double c : v)
    if (c < 0 || c > 1)
      throw Error("--background: each of r,g,b must be in [0, 1], got '" + args.get("background") + "'");
  return {float(v[0]), float(v[1]), float(v[2])};
}

std::vector<double> parse_numbers(const std::string& text, size_t count, const std::string& what) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    double v = std::strtod(item.c_str(), &end);
    if (item.empty() || !end || *end != '\0' || !std::isfinite(v))
      throw Error(what + ": '" + text + "' is not a list of finite numbers");
    out.push_back(v);
  }
  if (count > 0 && out.size() != count)
    throw Error(what + ": expected " + std::to_string(count) + " comma-separated numbers, got '" + text + "'");
  return out;
}

}  // namespace isegman::app
