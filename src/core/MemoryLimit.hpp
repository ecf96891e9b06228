#pragma once
// Counts checked against the memory this process may use before any work (docs/design.md section 8): a scene
// of 1e9 discs, or a cell grid of 1e10 cells from a tiny radius, is refused with an estimate instead of ending
// in std::bad_alloc (or the kernel's out-of-memory kill) after the run began. The bound is the tightest of the
// machine's physical memory, the process limits (ulimit -v: RLIMIT_AS, less what the process has mapped
// already; ulimit -d: RLIMIT_DATA) and the cgroup's memory limit (a container's or a batch job's, less what
// the cgroup uses already).
#include <cstdint>
#include <string>

namespace rondel {

// Bytes per disc at the peak of a run on one rank (docs/benchmarks.md measures up to 550 B, the stores, the
// contact rows and a rebuild's lists), and per cell of the grid (the rank's cell list and owner box: sfc and
// grid; metis holds the whole cell graph as well).
inline constexpr double kBytesPerDisc = 600.0;
inline constexpr double kBytesPerCell = 16.0;
inline constexpr double kBytesPerMetisCell = 128.0;

// The machine's physical memory in bytes (sysconf, else /proc/meminfo's MemTotal); 0 when unknown.
std::uint64_t physical_memory();

// The memory this process may still take: `bytes` (0 when no bound is known) and what sets it, in words
// ("this machine's physical memory", "the process limit ulimit -v (RLIMIT_AS) of 600 MB, less 250 MB mapped",
// "the cgroup memory limit (/sys/fs/cgroup/...)").
struct MemoryBound {
  std::uint64_t bytes = 0;
  std::string source;
};
MemoryBound memory_bound();

// Throws ConfigError "WHAT: N discs and C cells need about X GB (...) but <the bound> leaves Y GB" when the
// estimate exceeds memory_bound() (or is not finite). `what` names the keys that gave the counts.
void check_memory(double discs, double cells, double bytes_per_cell, const std::string& what);

}  // namespace rondel
