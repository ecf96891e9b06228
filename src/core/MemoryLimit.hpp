#pragma once
// Counts checked against the machine's memory before any work (docs/design.md section 8): a scene of 1e9
// discs, or a cell grid of 1e10 cells from a tiny radius, is refused with an estimate instead of ending in
// std::bad_alloc (or the kernel's out-of-memory kill) after the run began.
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

// Throws ConfigError "WHAT: N discs and C cells need about X GB (...) but this machine has Y GB of memory"
// when the estimate exceeds the physical memory (or is not finite). `what` names the keys that gave the counts.
void check_memory(double discs, double cells, double bytes_per_cell, const std::string& what);

}  // namespace rondel
