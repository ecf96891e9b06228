#pragma once
// Shared by the benchmark commands (rondel_bench, rondel_bench_io).
#include <fstream>
#include <initializer_list>
#include <string>
#include <variant>

#include "core/Errors.hpp"

namespace rondel {

// One command-line option of a benchmark command: "--name VALUE" into a number or a text, or a switch
// "--name" without a value.
struct BenchOption {
  const char* name;
  std::variant<long*, std::string*, bool*> target;
};

// Parses argv against the options; an unknown option, a missing value or a number that is not one is a
// ConfigError naming the command, the option and the options there are.
inline void parse_bench_options(const std::string& command, int argc, char** argv,
                                std::initializer_list<BenchOption> options) {
  std::string names;
  for (const BenchOption& o : options) names += (names.empty() ? "" : ", ") + std::string(o.name);
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    const BenchOption* found = nullptr;
    for (const BenchOption& o : options)
      if (k == o.name) found = &o;
    if (!found) throw ConfigError(command + ": unknown option '" + k + "' (" + names + ")");
    if (bool* const* flag = std::get_if<bool*>(&found->target)) {
      **flag = true;
      continue;
    }
    if (i + 1 >= argc) throw ConfigError(command + ": option '" + k + "' needs a value");
    const std::string v = argv[++i];
    if (std::string* const* text = std::get_if<std::string*>(&found->target)) {
      **text = v;
      continue;
    }
    std::size_t used = 0;
    try {
      *std::get<long*>(found->target) = std::stol(v, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != v.size())
      throw ConfigError(command + ": option '" + k + "' needs a whole number, not '" + v + "'");
  }
}

// Peak resident set size of this process [KiB] (VmHWM of /proc/self/status; 0 when unavailable).
inline long peak_rss_kib() {
  std::ifstream in("/proc/self/status");
  std::string key;
  long value = 0;
  while (in >> key) {
    if (key == "VmHWM:") {
      in >> value;
      return value;
    }
    std::getline(in, key);
  }
  return 0;
}

}  // namespace rondel
