#pragma once
// Shared by the benchmark commands (rondel_bench, rondel_bench_io).
#include <chrono>
#include <cstddef>
#include <cstdlib>
#include <fstream>
#include <initializer_list>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>

#ifdef __linux__
#include <sys/mman.h>
#endif

#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
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

// A size of this process [KiB] from /proc/self/status: `field` is the kernel's name ("VmHWM:" the peak resident
// set, "VmRSS:" the resident set now); 0 when unavailable.
inline long status_kib(const std::string& field) {
  std::ifstream in("/proc/self/status");
  std::string key;
  long value = 0;
  while (in >> key) {
    if (key == field) {
      in >> value;
      return value;
    }
    std::getline(in, key);
  }
  return 0;
}
inline long peak_rss_kib() { return status_kib("VmHWM:"); }
inline long resident_kib() { return status_kib("VmRSS:"); }

// Resets the peak resident set size (VmHWM) to the present one (Linux 4.0 and later: "5" into
// /proc/self/clear_refs), so that peak_rss_kib() measures what comes after; false when that is not possible.
inline bool reset_peak_rss() {
  std::ofstream out("/proc/self/clear_refs");
  out << "5";
  out.flush();
  return static_cast<bool>(out);
}

// A STREAM-like triad a[i] = b[i] + s c[i] over three arrays of `bytes_each` bytes each (choose them far
// larger than the last-level cache): the bytes per second of the fastest of `repeats` passes, counting 24
// bytes per element as STREAM does (the write-allocate read of a is not counted). `slowest(seconds)` turns
// this process's time of a pass into the time the figure is made of: the identity for one process, the
// maximum over the ranks (after a barrier) when every rank runs the triad at once; the figure is then this
// process's share, so the ranks' figures add up to the machine's.
template <class Slowest>
double stream_triad_bandwidth(std::size_t bytes_each, int repeats, Slowest&& slowest) {
  // 2 MiB aligned, and huge pages asked for where the kernel offers them on request: the first touch of
  // three large arrays is otherwise most of the triad's time (one page fault per 4 KiB).
  constexpr std::size_t kAlign = std::size_t{2} << 20;
  bytes_each = (bytes_each + kAlign - 1) / kAlign * kAlign;
  const std::size_t n = bytes_each / sizeof(double);
  auto array = [bytes_each] {
    std::unique_ptr<double, decltype(&std::free)> p(static_cast<double*>(std::aligned_alloc(kAlign, bytes_each)),
                                                    &std::free);
    if (!p) throw ConfigError("stream triad: cannot allocate " + std::to_string(bytes_each >> 20) + " MiB");
#ifdef __linux__
    madvise(p.get(), bytes_each, MADV_HUGEPAGE);  // a hint: without it the triad is the same, set up slower
#endif
    return p;
  };
  const auto a = array(), b = array(), c = array();
  double* __restrict pa = a.get();
  double* __restrict pb = b.get();
  double* __restrict pc = c.get();
  for (std::size_t i = 0; i < n; ++i) pa[i] = 0.0, pb[i] = 1.0, pc[i] = 2.0;  // every page touched first
  const double s = 3.0;
  double best = 0.0;
  for (int k = 0; k < repeats; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < n; ++i) pa[i] = pb[i] + s * pc[i];
    const double t = slowest(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    if (k == 0 || t < best) best = t;
  }
  // Read the result, so that the passes cannot be dropped (every element is 1 + 3 * 2 = 7).
  if (pa[n / 2] != 7.0) throw ConfigError("stream triad: wrong result");
  return best > 0.0 ? 24.0 * static_cast<double>(n) / best : 0.0;
}

// The bytes-per-disc-step model of rondel_bench: a lower bound on the memory traffic of one step, as if
// every byte the step needs crossed the memory bus once per step and the caches were perfect (each column
// streamed once; a disc's fields read once although up to seven rows read them). It follows the columns
// of ContactTable::visit_columns and the fields of DiscStore::for_each_field, so a column added or removed
// changes the model without an edit here.
//   Contact-table column: its element size once (read), and once more (written back) when the force
//   evaluation rewrites it: the history slots, last forces and couples (the columns kept or inherited; a
//   wall row's force). The local indices and the parameter index are read only. The key is left out: the
//   step reads it only when rows are rebuilt or an error is reported.
//   Disc field, per owned disc: its element size once (read), and once more when the step changes it:
//   the fields refreshed on ghosts every step (position, velocity, omega) and those ghosts do not carry at
//   all (theta, force, torque: owned-only results). gid and material are left out: only the rebuilds and
//   the checkpoints read them (a row carries its parameter index).
//   Disc field, per ghost (several ranks): the fields a ghost carries, read once, and those refreshed every
//   step written once more by the ghost update.
// Left out, so that the model stays a lower bound: the displacement check's reference positions (16 B per
// disc, read by the drift), the ghost messages and any neighbour build.
struct TrafficModel {
  double row_read = 0.0, row_written = 0.0;      // bytes per contact-table row
  double disc_read = 0.0, disc_written = 0.0;    // bytes per owned disc
  double ghost_read = 0.0, ghost_written = 0.0;  // bytes per ghost
  double row_bytes() const { return row_read + row_written; }
  double disc_bytes() const { return disc_read + disc_written; }
  double ghost_bytes() const { return ghost_read + ghost_written; }
  // Bytes per disc-step with the given rows and ghosts per owned disc.
  double per_disc_step(double rows_per_disc, double ghosts_per_disc) const {
    return rows_per_disc * row_bytes() + disc_bytes() + ghosts_per_disc * ghost_bytes();
  }
};

// The model for a contact table of this layout (its slots and rolling columns are those of the laws
// selected) and the disc store's fields.
inline TrafficModel traffic_model(const ContactTable& table) {
  TrafficModel m;
  constexpr unsigned kWritten = kColumnInherit | kColumnState;
  table.for_each_column([&m](std::string_view name, unsigned uses, const auto& column) {
    if (name == "key") return;  // rebuilds and error reports only
    const double bytes = sizeof(typename std::decay_t<decltype(column)>::value_type);
    m.row_read += bytes;
    if (uses & kWritten) m.row_written += bytes;
  });
  DiscStore probe;  // the fields and their element types, not their contents
  probe.for_each_field([&m](std::string_view name, unsigned uses, const auto& field) {
    if (name == "gid" || name == "material") return;  // rebuilds and checkpoints only
    const double bytes = sizeof(typename std::decay_t<decltype(field)>::value_type);
    const bool changes = (uses & kGhostStep) || !(uses & kGhostCreate);
    m.disc_read += bytes;
    if (changes) m.disc_written += bytes;
    if (uses & kGhostCreate) m.ghost_read += bytes;
    if (uses & kGhostStep) m.ghost_written += bytes;
  });
  return m;
}

}  // namespace rondel
