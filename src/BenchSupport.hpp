#pragma once
// Shared by the benchmark commands (rondel_bench, rondel_bench_io).
#include <fstream>
#include <string>

namespace rondel {

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
