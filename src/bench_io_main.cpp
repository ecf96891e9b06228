// rondel_bench_io: the cost of checkpoints (docs/design.md section 7, FORMAT.md). Builds a square lattice of N
// discs in a periodic box, slightly compressed (spacing 2 R (1 - 0.0025), so every disc has four loaded
// contacts) and spinning (so the tangential springs load), with Coulomb friction and the Wang rolling law;
// runs a few warm-up steps, times the steps, then times write_checkpoint() and the restart read: the
// file readers alone (header, discs, contact rows) and a whole restart (a Simulation constructed from the
// checkpoint: read, distribute, neighbour build). Prints times, bandwidths (file bytes / time, MB = 1e6 B),
// the file size per disc and the checkpoint overhead at an interval of --every steps. The write is also
// split into its phases (ordering, copying into blocks, HDF5) by a StateWriter of its own.
//   mpirun -n P rondel_bench_io [--discs 100000] [--steps 20] [--warmup 5] [--repeat 3] [--every 10000]
//                               [--output DIR] [--keep] [--no-verify]
// Writes go to the page cache; "write + sync" adds a sync(2) of the file system after the write, the time
// to get the bytes to the disk.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "BenchSupport.hpp"
#include "app/Restart.hpp"
#include "app/Simulation.hpp"
#include "core/Errors.hpp"
#include "parallel/Communicator.hpp"
#include "parallel/Hdf5File.hpp"
#include "parallel/StateFile.hpp"

namespace {

namespace fs = std::filesystem;

struct Options {
  long discs = 100000, steps = 20, warmup = 5, repeat = 3, every = 10000;
  std::string output = "rondel-bench-io";
  bool keep = false;
  bool no_verify = false;  // output.verify_checkpoints = false: no read-back of each checkpoint
};

Options parse(int argc, char** argv) {
  Options o;
  rondel::parse_bench_options("rondel_bench_io", argc, argv,
                              {{"--discs", &o.discs},
                               {"--steps", &o.steps},
                               {"--warmup", &o.warmup},
                               {"--repeat", &o.repeat},
                               {"--every", &o.every},
                               {"--output", &o.output},
                               {"--keep", &o.keep},
                               {"--no-verify", &o.no_verify}});
  if (o.discs < 16) throw rondel::ConfigError("rondel_bench_io: --discs must be at least 16");
  if (o.steps < 1 || o.repeat < 1 || o.every < 1 || o.warmup < 0)
    throw rondel::ConfigError("rondel_bench_io: --steps, --repeat and --every must be >= 1, --warmup >= 0");
  return o;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Median of the repeats (and the fastest), the slowest rank deciding each repeat.
struct Timing {
  std::vector<double> runs;
  double median() const {
    std::vector<double> s = runs;
    std::sort(s.begin(), s.end());
    return s.empty() ? 0.0 : s[s.size() / 2];
  }
  double best() const { return runs.empty() ? 0.0 : *std::min_element(runs.begin(), runs.end()); }
};

// The lattice scene: N discs in a periodic box, slightly compressed and spinning, wang rolling resistance.
rondel::Config lattice_config(const Options& o, long& nx, long& ny) {
  nx = std::lround(std::sqrt(static_cast<double>(o.discs)));
  ny = (o.discs + nx - 1) / nx;
  const double R = 0.001, spacing = 2.0 * R * (1.0 - 0.0025);
  char ini[4096];
  std::snprintf(ini, sizeof ini,
                "[run]\nsteps = 0\nprogress = false\noutput = %s\noverwrite = true\n[diagnostics]\nevery = 1000000\n"
                "[output]\nverify_checkpoints = %s\n"
                "[domain]\nxlo = 0\nxhi = %.17g\nylo = 0\nyhi = %.17g\nperiodic_x = true\nperiodic_y = true\n"
                "[linear]\nk_n = 1e7\ne = 0.5\n[coulomb]\nk_s = 7.5e6\nmu = 0.5\n"
                "[contact]\nrolling = wang\n[wang]\nk_r = 2e6\nmu_r = 0.1\n"
                "[scene]\ntype = lattice_square\nnx = %ld\nny = %ld\nradius = %.17g\nspacing = %.17g\n"
                "x0 = %.17g\ny0 = %.17g\nomega = 20\nmax_initial_overlap = 0.01\n",
                o.output.c_str(), o.no_verify ? "false" : "true", nx * spacing, ny * spacing, nx, ny, R, spacing,
                0.5 * spacing, 0.5 * spacing);
  return rondel::parse_config_text(ini);
}

// Seconds per step (slowest rank) after the warm-up.
double time_steps(rondel::Simulation& sim, const Options& o, const rondel::Communicator& comm) {
  for (long s = 0; s < o.warmup; ++s) sim.step();
  comm.barrier();
  const auto t0 = std::chrono::steady_clock::now();
  for (long s = 0; s < o.steps; ++s) sim.step();
  return comm.max(seconds_since(t0)) / static_cast<double>(o.steps);
}

// Checkpoint writes (the same step each time: the file is replaced), without and with a sync(2).
std::string time_writes(rondel::Simulation& sim, const Options& o, const rondel::Communicator& comm, Timing& write,
                        Timing& write_sync) {
  std::string path;
  std::streambuf* out = std::cout.rdbuf(nullptr);  // the simulation logs each checkpoint
  for (long r = 0; r < o.repeat; ++r) {
    comm.barrier();
    const auto t0 = std::chrono::steady_clock::now();
    path = sim.write_checkpoint();
    comm.barrier();
    write.runs.push_back(comm.max(seconds_since(t0)));
    if (comm.root()) ::sync();
    comm.barrier();
    write_sync.runs.push_back(comm.max(seconds_since(t0)));
  }
  std::cout.rdbuf(out);
  return path;
}

// Where a checkpoint write goes: the same file written by a StateWriter of its own (kept across the repeats,
// as Checkpointing keeps its writer), its phases timed (slowest rank per phase, median of the repeats).
struct WriterPhases {
  Timing order, columns, hdf5;
  double structure_bytes = 0.0;  // the largest rank's
};
WriterPhases time_writer_phases(rondel::Simulation& sim, const Options& o, const rondel::Communicator& comm) {
  WriterPhases p;
  rondel::StateWriter writer;
  const std::string path = (fs::path(o.output) / "phases.h5").string();
  const rondel::StateHeader header = rondel::Restart::header(sim.state(), "checkpoint");
  for (long r = 0; r < o.repeat; ++r) {
    comm.barrier();
    writer.write(path, header, sim.discs(), sim.pairs(), sim.wall_rows(), sim.walls(), comm, {}, 0.0);
    p.order.runs.push_back(comm.max(writer.last_times().order));
    p.columns.runs.push_back(comm.max(writer.last_times().columns));
    p.hdf5.runs.push_back(comm.max(writer.last_times().hdf5));
  }
  p.structure_bytes = comm.max(static_cast<double>(writer.checkpoint_structure_bytes()));
  comm.barrier();
  if (comm.root()) fs::remove(path);
  return p;
}

// Baseline: the same number of bytes as one dataset of doubles, each rank writing its block collectively (no
// reordering): what parallel HDF5 and MPI-IO alone cost here.
Timing time_raw_write(double file_bytes, const Options& o, const rondel::Communicator& comm) {
  Timing raw;
  const auto total = static_cast<std::uint64_t>(file_bytes / 8.0);
  const std::uint64_t begin = total * comm.rank() / comm.size(), end = total * (comm.rank() + 1) / comm.size();
  const std::vector<double> block(end - begin, 1.0);
  const std::string raw_path = (fs::path(o.output) / "raw.h5").string();
  for (long r = 0; r < o.repeat; ++r) {
    comm.barrier();
    const auto t0 = std::chrono::steady_clock::now();
    {
      rondel::Hdf5File f(raw_path, rondel::Hdf5File::Mode::create, comm);
      f.write("/raw", block, total, begin);
    }
    comm.barrier();
    raw.runs.push_back(comm.max(seconds_since(t0)));
  }
  if (comm.root()) fs::remove(raw_path);
  return raw;
}

// What the file holds, counted while reading it back.
struct FileRows {
  std::int64_t pairs = 0, walls = 0, with_history = 0;
};

// Reads: the file layer alone (header, discs, rows), then a whole restart (a Simulation from the checkpoint).
FileRows time_reads(const std::string& path, std::int64_t step, const rondel::Config& config, const Options& o,
                    const rondel::Communicator& comm, Timing& read, Timing& restart) {
  FileRows rows;
  for (long r = 0; r < o.repeat; ++r) {
    comm.barrier();
    auto t0 = std::chrono::steady_clock::now();
    {
      const rondel::StateHeader h = rondel::read_state_header(path, comm);
      rondel::DiscStore discs;
      rondel::read_state_discs(path, discs, comm);
      const rondel::LawSelection laws{"linear", "coulomb", "wang"};
      rondel::ContactTable pairs = rondel::make_contact_table(laws, false),
                           walls = rondel::make_contact_table(laws, true);
      rondel::read_state_rows(path, pairs, walls, comm);
      comm.barrier();
      read.runs.push_back(comm.max(seconds_since(t0)));
      std::int64_t loaded = 0;
      for (std::size_t k = 0; k < pairs.size(); ++k) loaded += pairs.has_state(k);
      rows = {comm.sum(static_cast<std::int64_t>(pairs.size())), comm.sum(static_cast<std::int64_t>(walls.size())),
              comm.sum(loaded)};
      if (h.step != step) throw rondel::InputError("rondel_bench_io: the checkpoint read back has another step");
    }
    comm.barrier();
    t0 = std::chrono::steady_clock::now();
    {
      rondel::Simulation again(config, comm, false, path);
      comm.barrier();
      restart.runs.push_back(comm.max(seconds_since(t0)));
      if (again.step_count() != step) throw rondel::InputError("rondel_bench_io: the restart is at another step");
    }
  }
  return rows;
}

int bench(int argc, char** argv, const rondel::Communicator& comm) {
  const Options o = parse(argc, argv);
  long nx = 0, ny = 0;
  const rondel::Config config = lattice_config(o, nx, ny);
  // The directory is removed at the end (unless --keep): never one that holds something already.
  if (comm.any(fs::exists(o.output) && !(fs::is_directory(o.output) && fs::is_empty(o.output))))
    throw rondel::ConfigError("--output " + o.output + " exists and is not empty; name a new directory");

  auto sim = std::make_unique<rondel::Simulation>(config, comm, true);
  const auto n = comm.sum(static_cast<std::int64_t>(sim->discs().n_owned()));
  const double step_time = time_steps(*sim, o, comm);
  Timing write, write_sync, read, restart;
  const std::string path = time_writes(*sim, o, comm, write, write_sync);
  const double file_bytes = comm.sum(comm.root() ? static_cast<double>(fs::file_size(path)) : 0.0);
  const std::int64_t step = sim->step_count();
  const WriterPhases phases = time_writer_phases(*sim, o, comm);
  sim.reset();  // the restart below holds the only copy of the state
  const Timing raw = time_raw_write(file_bytes, o, comm);
  const FileRows rows = time_reads(path, step, config, o, comm, read, restart);
  const double rss = comm.sum(static_cast<double>(rondel::peak_rss_kib()) * 1024.0);
  if (comm.root()) {
    const double mb = file_bytes / 1e6;
    const double interval = static_cast<double>(o.every) * step_time;
    std::printf(
        "rondel_bench_io: %lld discs (%ld x %ld square lattice, periodic, wang rolling), %d rank(s), step %lld\n"
        "  contact rows in the file   %lld disc pairs (%lld carry state), %lld wall rows\n"
        "  file size                  %.1f MB, %.1f B per disc\n"
        "  step time                  %.4g s (%ld timed steps after %ld warm-up)\n"
        "  write_checkpoint           %.3f s median, %.3f s best of %ld: %.0f MB/s\n"
        "    of which                 order %.3f s, copy into blocks %.3f s, HDF5 %.3f s (medians, slowest rank)\n"
        "    checkpoint structures    %.1f MB on the largest rank (%.0f B per disc and rank)\n"
        "  write + sync               %.3f s median: %.0f MB/s\n"
        "  raw HDF5 write, same bytes %.3f s median: %.0f MB/s (one dataset, no reordering)\n"
        "  read (file layer)          %.3f s median, %.3f s best: %.0f MB/s\n"
        "  restart (read + set-up)    %.3f s median, %.3f s best\n"
        "  checkpoint every %ld steps: %.4g s of steps; write %.3f %%, write + sync %.3f %% overhead\n"
        "  peak RSS                   %.0f MB over all ranks (%.0f B per disc)\n",
        static_cast<long long>(n), nx, ny, comm.size(), static_cast<long long>(step),
        static_cast<long long>(rows.pairs), static_cast<long long>(rows.with_history),
        static_cast<long long>(rows.walls), mb, file_bytes / static_cast<double>(n), step_time, o.steps, o.warmup,
        write.median(), write.best(), o.repeat, mb / write.median(), phases.order.median(), phases.columns.median(),
        phases.hdf5.median(), phases.structure_bytes / 1e6,
        phases.structure_bytes * comm.size() / static_cast<double>(n), write_sync.median(), mb / write_sync.median(),
        raw.median(), mb / raw.median(), read.median(), read.best(), mb / read.median(), restart.median(),
        restart.best(), o.every, interval, 100.0 * write.median() / interval, 100.0 * write_sync.median() / interval,
        rss / 1e6, rss / static_cast<double>(n));
  }
  comm.barrier();
  if (!o.keep && comm.root()) {
    std::error_code ec;
    fs::remove_all(o.output, ec);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  rondel::MpiEnvironment mpi(&argc, &argv);
  rondel::Communicator comm;
  try {
    return bench(argc, argv, comm);
  } catch (const std::exception& e) {
    const std::string message = e.what();  // errors of this command name it already, others get its name
    if (comm.root())
      std::cerr << (message.rfind("rondel_bench_io:", 0) == 0 ? "" : "rondel_bench_io: ") << message << '\n';
    return 1;
  }
}
