#include "core/MemoryLimit.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/Errors.hpp"

namespace rondel {

namespace {

std::string gigabytes(double bytes) {
  std::ostringstream s;
  s.precision(3);
  s << bytes / 1e9 << " GB";
  return s.str();
}

// The first number of a file (0 when it has none: "max", missing).
std::uint64_t number_in(const std::string& path) {
  std::ifstream in(path);
  std::uint64_t v = 0;
  return (in >> v) ? v : 0;
}

// The bytes this process has mapped (VmSize, /proc/self/statm's first field in pages).
std::uint64_t mapped_bytes() {
  const long page = sysconf(_SC_PAGE_SIZE);
  return number_in("/proc/self/statm") * static_cast<std::uint64_t>(page > 0 ? page : 4096);
}

// The cgroup memory limit less the cgroup's usage: cgroup v2 (memory.max, memory.current) or v1
// (memory.limit_in_bytes, memory.usage_in_bytes), at the process's cgroup path or at the mount's root (a
// container sees its own cgroup there). 0 when there is none.
MemoryBound cgroup_bound() {
  std::ifstream in("/proc/self/cgroup");
  std::string v2, v1;
  for (std::string line; std::getline(in, line);) {
    const std::size_t a = line.find(':'), b = line.find(':', a + 1);
    if (a == std::string::npos || b == std::string::npos) continue;
    const std::string controllers = line.substr(a + 1, b - a - 1), path = line.substr(b + 1);
    if (controllers.empty()) v2 = path;
    std::stringstream list(controllers);
    for (std::string c; std::getline(list, c, ',');)
      if (c == "memory") v1 = path;  // cgroup v1's memory controller, by its name in /proc/self/cgroup
  }
  const struct {
    std::string dir, limit, usage;
  } places[] = {{"/sys/fs/cgroup" + v2, "memory.max", "memory.current"},
                {"/sys/fs/cgroup", "memory.max", "memory.current"},
                {"/sys/fs/cgroup/memory" + v1, "memory.limit_in_bytes", "memory.usage_in_bytes"},
                {"/sys/fs/cgroup/memory", "memory.limit_in_bytes", "memory.usage_in_bytes"}};
  for (const auto& p : places) {
    const std::uint64_t limit = number_in(p.dir + "/" + p.limit);
    if (limit == 0) continue;
    if (limit >= (std::uint64_t{1} << 60)) return {};  // v1's "no limit" is a page-rounded 2^63
    const std::uint64_t used = number_in(p.dir + "/" + p.usage);
    return {limit > used ? limit - used : 1, "the cgroup memory limit of " + gigabytes(static_cast<double>(limit)) +
                                                 " (" + p.dir + "/" + p.limit + ", less " +
                                                 gigabytes(static_cast<double>(used)) + " in use)"};
  }
  return {};
}

}  // namespace

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

MemoryBound memory_bound() {
  MemoryBound best{physical_memory(), "this machine's physical memory"};
  const auto take = [&](const MemoryBound& b) {
    if (b.bytes > 0 && (best.bytes == 0 || b.bytes < best.bytes)) best = b;
  };
  rlimit r{};
  if (getrlimit(RLIMIT_AS, &r) == 0 && r.rlim_cur != RLIM_INFINITY) {
    const std::uint64_t limit = r.rlim_cur, mapped = mapped_bytes();
    take({limit > mapped ? limit - mapped : 1, "the process limit ulimit -v (RLIMIT_AS) of " +
                                                   gigabytes(static_cast<double>(limit)) + ", less " +
                                                   gigabytes(static_cast<double>(mapped)) + " mapped already"});
  }
  if (getrlimit(RLIMIT_DATA, &r) == 0 && r.rlim_cur != RLIM_INFINITY)
    take({r.rlim_cur, "the process limit ulimit -d (RLIMIT_DATA) of " + gigabytes(static_cast<double>(r.rlim_cur))});
  take(cgroup_bound());
  return best;
}

void check_memory(double discs, double cells, double bytes_per_cell, const std::string& what) {
  const double need = discs * kBytesPerDisc + cells * bytes_per_cell;
  const MemoryBound bound = memory_bound();
  const double have = static_cast<double>(bound.bytes);
  if (std::isfinite(need) && (have == 0.0 || need <= have)) return;
  std::ostringstream m;
  m.precision(3);
  m << what << ": ";
  if (discs > 0.0) m << discs << " discs" << (cells > 0.0 ? " and " : "");
  if (cells > 0.0) m << cells << " cells";
  m << " need about " << need / 1e9 << " GB (" << kBytesPerDisc << " B per disc";
  if (cells > 0.0) m << ", " << bytes_per_cell << " B per cell";
  m << ") but " << bound.source << " leaves " << gigabytes(have);
  throw ConfigError(m.str());
}

}  // namespace rondel
