#include "core/MemoryLimit.hpp"

#include <unistd.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/Errors.hpp"

namespace rondel {

std::uint64_t physical_memory() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if (pages > 0 && page > 0) return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page);
  std::ifstream in("/proc/meminfo");
  for (std::string name; in >> name;) {
    std::uint64_t kb = 0;
    if (name == "MemTotal:" && in >> kb) return kb * 1024;  // the field of /proc/meminfo
    in.ignore(1 << 12, '\n');
  }
  return 0;
}

void check_memory(double discs, double cells, double bytes_per_cell, const std::string& what) {
  const double need = discs * kBytesPerDisc + cells * bytes_per_cell;
  const double have = static_cast<double>(physical_memory());
  if (std::isfinite(need) && (have == 0.0 || need <= have)) return;
  std::ostringstream m;
  m.precision(3);
  m << what << ": ";
  if (discs > 0.0) m << discs << " discs" << (cells > 0.0 ? " and " : "");
  if (cells > 0.0) m << cells << " cells";
  m << " need about " << need / 1e9 << " GB (" << kBytesPerDisc << " B per disc";
  if (cells > 0.0) m << ", " << bytes_per_cell << " B per cell";
  m << ") but this machine has " << have / 1e9 << " GB of memory";
  throw ConfigError(m.str());
}

}  // namespace rondel
