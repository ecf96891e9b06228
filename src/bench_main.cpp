// rondel_bench: the standard speed benchmark (bench/README.md). Loads the jammed periodic packing of 10,000
// discs, or nx x ny exact periodic copies of it (--discs 10000 times the copy count; nx and ny as close to
// square as the count allows, nx >= ny: 30,000 = 3 x 1, 160,000 = 4 x 4, 1,000,000 = 10 x 10,
// 10,000,000 = 40 x 25), runs the warm-up and the timed steps with linear contacts and friction, and prints
// disc-steps per second, contacts per disc and memory per disc; then the timed steps' wall time per phase,
// nanoseconds per contact and step, a STREAM-like triad's memory bandwidth (measured before the simulation is
// built; --no-stream skips it), the model of the bytes a step moves per disc (traffic_model,
// BenchSupport.hpp) and the bound on disc-steps per second that the two give.
//   rondel_bench [--discs 10000 x k] [--steps 5000] [--warmup 1000] [--rolling LAW] [--normal LAW] [--file PATH]
//                [--no-stream] [--skin S] [--against LAW [--chunk 100]] [--shear RATE] [--locked]
// Without --file it reads bench/jammed10k.csv of the working directory (a clone's root) and, when that is
// missing, the one of the source tree it was built from (RONDEL_SOURCE_DIR, set by CMakeLists.txt), so it runs
// from a build directory as well; the packing is described in bench/README.md. With --file, --discs counts
// copies of that file's discs.
// Rolling parameters follow the benchmark README (wang k_r = 2/7 k_n, mu_r = 0.1, which alonso_marroquin reads
// from the same [wang] block; jiang_* delta = 0.5); the other laws get the equivalent cap for the mean radius
// (iwashita_oda K_r = k_r R*^2, eta = mu_r R*; force_proportional mu_r = 0.1; constant_torque and
// displacement_damping mu_r = 0.05). --skin S sets neighbour.skin (default: a quarter of the mean radius); a
// small skin makes the neighbour list rebuild within a few steps, to measure the memory peak of a rebuild.
// --against LAW builds a second simulation of the same discs with that rolling law and runs the timed steps of
// the two in alternating chunks of --chunk steps (A B B A ...), printing the second law's rate and the ratio
// of the rates per chunk pair (median and range) and of the totals: a comparison of two laws that the
// neighbours of a shared machine disturb far less than separate runs. --shear RATE shears the first
// simulation's cell at cell.rate_xy = RATE (Lees-Edwards, docs/physics.md section 10; the discs start with the
// mean flow) and leaves the second's standing: `--rolling none --against none --shear 0.0067` is the cost of the
// sheared cell at I = 1e-3 against today's periodic box (docs/benchmarks.md). --locked makes every contact of
// both simulations stick: coulomb.mu and the rolling laws' caps (wang, force_proportional, constant_torque and
// displacement_damping mu_r, iwashita_oda eta) raised to 1e6, so that a sheared packing's contacts neither slide
// nor yield in rolling, as a jammed one's: what a cell costs apart from the physics of a flow. --normal walton_braun
// runs both simulations with the hysteretic normal law instead of the linear one (K1 = the linear k_n, and the
// restitution the linear law's zeta = 0.3 gives, 0.37: K2 = 7.3 K1).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "BenchSupport.hpp"
#include "app/Simulation.hpp"
#include "core/Errors.hpp"
#include "core/Format.hpp"
#include "parallel/Communicator.hpp"
#include "physics/LawRegistry.hpp"
#include "physics/Restitution.hpp"

namespace {

struct Options {
  long discs = 10000, steps = 5000, warmup = 1000;
  std::string file;  // empty: the default packing (default_packing)
  std::string rolling = "none";
  std::string normal = "linear";  // linear or walton_braun (normal_block)
  std::string skin;               // empty: neighbour.skin's default
  std::string against;            // a second rolling law run beside the first, in alternating chunks (empty: none run)
  std::string shear;              // cell.rate_xy of the first simulation (empty: its cell stands still)
  long chunk = -1;                // steps per chunk with --against (-1: 100, or --steps when fewer)
  bool no_stream = false;
  bool locked = false;  // contacts that neither slide nor yield in rolling (the caps raised to kLockedCap)
};

// The normal law's block: linear k_n = 1e5 with zeta = 0.3, or walton_braun with K1 = that k_n and the restitution
// that zeta gives.
std::string normal_block(const std::string& law) {
  const std::string e = rondel::fmt(rondel::restitution_from_zeta(0.3), 17);
  const std::pair<const char*, std::string> blocks[] = {{"linear", "[linear]\nk_n = 1e5\nzeta = 0.3\n"},
                                                        {"walton_braun", "[walton_braun]\nK1 = 1e5\ne = " + e + "\n"}};
  for (const auto& [name, block] : blocks)
    if (law == name) return block;
  throw rondel::ConfigError("rondel_bench: --normal '" + law +
                            "' is not a normal law the benchmark sets up (linear | walton_braun)");
}

Options parse(int argc, char** argv) {
  Options o;
  rondel::parse_bench_options("rondel_bench", argc, argv,
                              {{"--discs", &o.discs},
                               {"--steps", &o.steps},
                               {"--warmup", &o.warmup},
                               {"--rolling", &o.rolling},
                               {"--normal", &o.normal},
                               {"--file", &o.file},
                               {"--no-stream", &o.no_stream},
                               {"--skin", &o.skin},
                               {"--against", &o.against},
                               {"--shear", &o.shear},
                               {"--chunk", &o.chunk},
                               {"--locked", &o.locked}});
  if (o.steps <= 0)
    throw rondel::ConfigError("rondel_bench: --steps must be at least 1, not " + std::to_string(o.steps));
  if (o.warmup < 0)
    throw rondel::ConfigError("rondel_bench: --warmup must be 0 or more, not " + std::to_string(o.warmup));
  normal_block(o.normal);  // refuses a law the benchmark does not set up
  if (o.chunk == -1) o.chunk = std::min(100L, o.steps);
  if (!o.against.empty() && (o.chunk <= 0 || o.chunk > o.steps))
    throw rondel::ConfigError("rondel_bench: --chunk must be between 1 and --steps (" + std::to_string(o.steps) +
                              "), not " + std::to_string(o.chunk));
  return o;
}

// The discs of a packing file: its rows that start with a number (not the comments, not the header).
long count_discs(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw rondel::InputError("rondel_bench: cannot read '" + file + "' (use --file PATH)");
  long n = 0;
  for (std::string line; std::getline(in, line);) {
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos) continue;
    const char c = line[first];
    if ((c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.') ++n;
  }
  if (n == 0) throw rondel::InputError("rondel_bench: '" + file + "' holds no disc");
  return n;
}

// The periodic copies nx x ny of a packing of `base` discs that make `discs`: nx ny = discs / base, ny the
// largest divisor of the count not above its square root (as square as the count allows, nx >= ny).
std::pair<long, long> copies_of(long discs, long base) {
  if (discs <= 0 || discs % base != 0) {
    const std::string b = std::to_string(base);
    throw rondel::ConfigError("rondel_bench: --discs must be " + b +
                              " (the discs of the packing) times a whole number of periodic copies nx x ny, e.g. " + b +
                              ", " + std::to_string(3 * base) + " (3 x 1), " + std::to_string(16 * base) +
                              " (4 x 4), " + std::to_string(100 * base) + " (10 x 10); not " + std::to_string(discs));
  }
  const long k = discs / base;
  long ny = 1;
  for (long d = 1; d * d <= k; ++d)
    if (k % d == 0) ny = d;
  return {k / ny, ny};
}

// The benchmark's value of each rolling parameter it sets, by key, scaled to the packing; a required parameter
// without one takes its law's example value (ParamSpec::example), the others keep their defaults.
struct BenchValue {
  const char* key;
  const char* value;
};
constexpr BenchValue kRollingValues[] = {
    {"jiang.delta", "0.5"},
    {"wang.k_r", "28571.43"},
    {"wang.mu_r", "0.1"},
    {"iwashita_oda.K_r", "4018"},
    {"iwashita_oda.C_r", "0"},
    {"iwashita_oda.eta", "0.0375"},
    {"force_proportional.mu_r", "0.1"},
    {"constant_torque.mu_r", "0.05"},
    {"displacement_damping.mu_r", "0.05"},
};
// --locked: the value of coulomb.mu and of these caps.
constexpr const char* kLockedCap = "1e6";
constexpr const char* kCapKeys[] = {"wang.mu_r", "iwashita_oda.eta", "force_proportional.mu_r", "constant_torque.mu_r",
                                    "displacement_damping.mu_r"};

// The [contact] normal and rolling lines and the rolling law's parameter block, from the law's parameter list.
std::string rolling_block(const std::string& law, const char* option, bool locked, const std::string& normal) {
  const rondel::LawInfo* info = rondel::law_catalog().rolling.find(law);
  if (!info)
    throw rondel::ConfigError("rondel_bench: " + std::string(option) + " '" + law + "' is not a rolling law (" +
                              rondel::law_catalog().rolling.keywords() + ")");
  std::string text = "[contact]\nnormal = " + normal + "\nrolling = " + law + "\n";
  if (!info->block) return text;
  text += "[" + std::string(info->block->section) + "]\n";
  for (const rondel::ParamSpec& p : info->block->params) {
    const std::string key = std::string(info->block->section) + "." + p.key;
    const auto v = std::find_if(std::begin(kRollingValues), std::end(kRollingValues),
                                [&key](const BenchValue& b) { return key == b.key; });
    const bool cap = std::find(std::begin(kCapKeys), std::end(kCapKeys), key) != std::end(kCapKeys);
    if (locked && cap)
      text += std::string(p.key) + " = " + kLockedCap + "\n";
    else if (v != std::end(kRollingValues))
      text += std::string(p.key) + " = " + v->value + "\n";
    else if (p.presence == rondel::Presence::required && std::isfinite(p.example))
      text += std::string(p.key) + " = " + rondel::fmt(p.example) + "\n";
  }
  return text;
}

// The packing shipped in the repository: relative to the working directory first, then in the source tree of
// this build, so that neither a clone's root nor its build directory needs a path outside the repository.
std::string default_packing() {
  const std::string relative = "bench/jammed10k.csv";
  const std::string in_source = std::string(RONDEL_SOURCE_DIR) + "/" + relative;
  for (const std::string& file : {relative, in_source})
    if (std::ifstream(file)) return file;
  throw rondel::InputError("rondel_bench: cannot read the benchmark packing: neither '" + relative +
                           "' (relative to the working directory) nor '" + in_source +
                           "' (the source tree of this build) exists; use --file PATH");
}

// The periodic box from the file's comment line "Periodic box x, y in [lo, hi]".
void box_of(const std::string& file, double& lo, double& hi) {
  std::ifstream in(file);
  if (!in) throw rondel::InputError("rondel_bench: cannot read '" + file + "' (use --file PATH)");
  std::string line;
  while (std::getline(in, line) && line.rfind('#', 0) == 0) {
    const auto box = line.find("Periodic box");
    const auto p = box == std::string::npos ? box : line.find("in [", box);
    if (p != std::string::npos && std::sscanf(line.c_str() + p, "in [%lf, %lf]", &lo, &hi) == 2) return;
  }
  throw rondel::InputError("rondel_bench: '" + file + "' has no 'Periodic box x, y in [lo, hi]' comment");
}

// Memory bandwidth first, while no simulation holds memory: every rank at once, each pass timed by the slowest
// rank, the ranks' shares summed. `peak_reset`: the peak RSS printed later is the simulation's.
constexpr std::size_t kTriadBytes = std::size_t{128} << 20;  // each of the three arrays
constexpr int kTriadRepeats = 5;
double measure_bandwidth(const Options& o, const rondel::Communicator& comm, bool& peak_reset) {
  peak_reset = true;
  if (o.no_stream) return 0.0;
  const double bandwidth = comm.sum(rondel::stream_triad_bandwidth(kTriadBytes, kTriadRepeats, [&comm](double seconds) {
    comm.barrier();
    return comm.max(seconds);
  }));
  peak_reset = rondel::reset_peak_rss();
  return bandwidth;
}

// The benchmark's INI text for nx x ny copies of the packing `file` of period [lo, hi].
std::string bench_ini(const Options& o, long nx, long ny, double lo, double hi) {
  const double L = hi - lo;
  char ini[4096];
  std::snprintf(ini, sizeof ini,
                "[run]\ndt = 3e-4\nsteps = 0\n[domain]\nxlo = %.17g\nxhi = %.17g\nylo = %.17g\nyhi = %.17g\n"
                "periodic_x = true\nperiodic_y = true\n[material]\ndensity = 1\n"
                "[coulomb]\nk_s = 28571.43\nmu = %s\n[scene]\ntype = csv\nfile = %s\nreplicate_x = %ld\n"
                "replicate_y = %ld\nmax_initial_overlap = 0.2\n",
                lo, lo + static_cast<double>(nx) * L, lo, lo + static_cast<double>(ny) * L,
                o.locked ? kLockedCap : "0.5", o.file.c_str(), nx, ny);
  return std::string(ini) + normal_block(o.normal) + (o.skin.empty() ? "" : "[neighbour]\nskin = " + o.skin + "\n");
}

// The timed steps: of `sim` alone, or with --against alternating with `other` in chunks, A B B A A B ..., so that a
// slow spell of a shared machine falls on both (each pair's ratio is kept). Each chunk timed by the slowest rank.
struct Timed {
  double secs = 0.0, other_secs = 0.0;
  std::vector<double> pair_ratios;  // this law's rate over the other's, per chunk pair
};
Timed run_timed(const Options& o, rondel::Simulation& sim, rondel::Simulation* other,
                const rondel::Communicator& comm) {
  const auto timed = [&comm](rondel::Simulation& s, long steps) {
    comm.barrier();
    const auto t = std::chrono::steady_clock::now();
    s.advance(steps, [] { return std::int64_t{0}; });
    return comm.max(std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count());
  };
  Timed out;
  if (!other) {
    out.secs = timed(sim, o.steps);
    return out;
  }
  bool first = true;
  for (long done = 0; done < o.steps; done += o.chunk, first = !first) {
    const long c = std::min(o.chunk, o.steps - done);
    double a = 0.0, b = 0.0;
    if (first) {
      a = timed(sim, c), b = timed(*other, c);
    } else {
      b = timed(*other, c), a = timed(sim, c);
    }
    out.secs += a, out.other_secs += b;
    out.pair_ratios.push_back(b / a);
  }
  return out;
}

// What the report prints, summed over the ranks.
struct Measured {
  double n = 0, contacts = 0, rows = 0, wall_rows = 0, twice = 0, ghosts = 0, comm_time = 0, store = 0, rss = 0;
  bool peak_reset = true;
  std::array<double, rondel::PhaseTimes::count> phase{};  // the timed steps' rank-seconds per phase
  double rank_seconds = 0, bytes = 0, bandwidth = 0;
  std::size_t builds = 0;
  rondel::TrafficModel model{};
};
Measured measure(const rondel::Simulation& sim, const rondel::Communicator& comm, const Timed& t, double comm_before,
                 const rondel::PhaseTimes& phases0, std::size_t builds0) {
  long contacts = 0, border = 0;
  for (std::size_t r = 0; r < sim.pairs().size(); ++r) {
    const bool booked = static_cast<std::size_t>(sim.pairs().i1[r]) < sim.discs().n_owned();
    if (booked && sim.pairs().F_n[r] > 0.0) ++contacts;
    if (!booked) ++border;  // computed here for a disc we own, booked by the other rank too
  }
  Measured m;
  m.n = static_cast<double>(comm.sum(static_cast<std::int64_t>(sim.discs().n_owned())));
  m.contacts = static_cast<double>(comm.sum(static_cast<std::int64_t>(contacts)));
  m.rows = comm.sum(static_cast<double>(sim.pairs().size()));
  m.wall_rows = comm.sum(static_cast<double>(sim.wall_rows().size()));
  m.twice = comm.sum(static_cast<double>(border));
  m.ghosts = comm.sum(static_cast<double>(sim.state().ghosts));
  m.comm_time = comm.max(sim.comm_seconds() - comm_before);
  m.store = comm.sum(
      static_cast<double>(sim.discs().memory_bytes() + sim.pairs().memory_bytes() + sim.wall_rows().memory_bytes()));
  m.rss = comm.sum(static_cast<double>(rondel::peak_rss_kib()) * 1024.0);
  for (int p = 0; p < rondel::PhaseTimes::count; ++p) {
    const auto ph = static_cast<rondel::PhaseTimes::Phase>(p);
    m.phase[p] = comm.sum(sim.phases().seconds(ph) - phases0.seconds(ph));
  }
  m.rank_seconds = comm.sum(t.secs);
  m.model = rondel::traffic_model(sim.pairs());
  const rondel::TrafficModel wall_model = rondel::traffic_model(sim.wall_rows());
  m.bytes = m.model.per_disc_step(m.rows / m.n, m.ghosts / m.n) + m.wall_rows / m.n * wall_model.row_bytes();
  m.builds = sim.counts().neighbour_builds - builds0;
  return m;
}

void print_report(const Options& o, long nx, long ny, const rondel::Simulation& sim, const Timed& t, const Measured& m,
                  bool against) {
  const int ranks = sim.state().comm.size();
  const double n = m.n, rate = n * static_cast<double>(o.steps) / t.secs;
  if (o.normal != rondel::law_catalog().normal.laws.front().keyword)  // the default law goes unsaid, as before
    std::printf("rondel_bench: normal law %s\n", o.normal.c_str());
  std::printf(
      "rondel_bench: %ld discs (%ld x %ld copies), rolling %s, %ld timed steps (after %ld warm-up), dt %.3g s "
      "(critical %.3g s, %s mode), %d rank(s)\n"
      "  wall time             %.3f s\n  disc-steps per second %.4g\n"
      "  contacts per disc     %.3f (coordination %.3f)\n  candidate rows/disc   %.3f\n"
      "  neighbour builds      %zu\n  memory per disc       %.0f B in discs and contact rows, %.0f B peak RSS%s\n"
      "  communication         %.3f s (%.1f %% of the wall time, slowest rank)\n"
      "  ghosts per disc       %.4f\n  rows computed twice   %.2f %% of all rows (border pairs)\n",
      o.discs, nx, ny, o.rolling.c_str(), o.steps, o.warmup, sim.state().dt, sim.critical().dt,
      sim.critical().mode.c_str(), ranks, t.secs, rate, m.contacts / n, 2.0 * m.contacts / n, m.rows / n, m.builds,
      m.store / n, m.rss / n,
      against        ? " (of both simulations: --against)"
      : m.peak_reset ? ""
                     : " (with the triad's arrays: use --no-stream)",
      m.comm_time, 100.0 * m.comm_time / t.secs, m.ghosts / n, 100.0 * m.twice / m.rows);
  // Per phase: the mean over the ranks, and its share of the mean wall time.
  if (ranks > 1) std::printf("  the phases below: mean over the %d ranks\n", ranks);
  for (int p = 0; p < rondel::PhaseTimes::count; ++p)
    std::printf("  phase %-15s %.3f s (%.1f %%)\n", rondel::PhaseTimes::name(static_cast<rondel::PhaseTimes::Phase>(p)),
                m.phase[p] / ranks, m.rank_seconds > 0.0 ? 100.0 * m.phase[p] / m.rank_seconds : 0.0);
  const double contact_steps = m.contacts * static_cast<double>(o.steps);
  if (contact_steps > 0.0)
    std::printf("  ns per contact-step   %.2f in the force phase, %.2f in all (rank-seconds / contacts x steps)\n",
                1e9 * m.phase[rondel::PhaseTimes::force] / contact_steps, 1e9 * m.rank_seconds / contact_steps);
}

// --against: the second law's rate, and the ratio per chunk pair (median, range) and of the totals. Not "disc-steps
// per second": tools/bench_pairs.sh reads the one line that says so.
void print_against(const Options& o, const Timed& t, double n) {
  std::vector<double> sorted = t.pair_ratios;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t m = sorted.size();
  const double median = m % 2 ? sorted[m / 2] : 0.5 * (sorted[m / 2 - 1] + sorted[m / 2]);
  std::printf("  against %-13s %.4g disc-steps/s, the same steps in %zu chunk pairs of %ld (A B B A ...)\n",
              o.against.c_str(), n * static_cast<double>(o.steps) / t.other_secs, m, o.chunk);
  std::printf("  rate %s / %s: %.3f median of the pairs (%.3f to %.3f), %.3f of the totals\n", o.rolling.c_str(),
              o.against.c_str(), median, sorted.front(), sorted.back(), t.other_secs / t.secs);
}

// The memory bandwidth, the model of the bytes a step moves per disc and the bound the two give.
void print_bandwidth(const Options& o, const Measured& m, double rate, int ranks) {
  if (o.no_stream)
    std::printf("  stream triad          not measured (--no-stream)\n");
  else
    std::printf("  stream triad          %.2f GB/s (3 arrays of %zu MiB per rank, best of %d; %s)\n",
                1e-9 * m.bandwidth, kTriadBytes >> 20, kTriadRepeats,
                ranks > 1 ? "every rank at once, summed" : "1 rank");
  std::printf("  bytes per disc-step (model) %.0f B (%.3f rows x %.0f B, discs %.0f B, %.4f ghosts x %.0f B)\n",
              m.bytes, m.rows / m.n, m.model.row_bytes(), m.model.disc_bytes(), m.ghosts / m.n, m.model.ghost_bytes());
  if (o.no_stream) return;
  const double bound = m.bandwidth / m.bytes;
  std::printf("  bandwidth bound       %.4g disc-steps/s (triad bandwidth / bytes per disc-step)\n", bound);
  std::printf("  measured / bound      %.3f\n", rate / bound);
}

int bench(int argc, char** argv, const rondel::Communicator& comm) {
  Options o = parse(argc, argv);
  if (o.file.empty()) o.file = default_packing();
  const auto [nx, ny] = copies_of(o.discs, count_discs(o.file));
  double lo = 0, hi = 0;
  box_of(o.file, lo, hi);
  bool peak_reset = true;
  const double bandwidth = measure_bandwidth(o, comm, peak_reset);
  const std::string ini = bench_ini(o, nx, ny, lo, hi);
  const auto config_of = [&](const std::string& law, const char* option, bool sheared) {
    return rondel::parse_config_text(ini + rolling_block(law, option, o.locked, o.normal) +
                                     (sheared && !o.shear.empty() ? "[cell]\nrate_xy = " + o.shear + "\n" : ""));
  };
  rondel::Simulation sim(config_of(o.rolling, "--rolling", true), comm, false);
  // --against: the second law's simulation of the same discs, held beside the first.
  std::unique_ptr<rondel::Simulation> other;
  if (!o.against.empty())
    other = std::make_unique<rondel::Simulation>(config_of(o.against, "--against", false), comm, false);
  // The steps as a run takes them between outputs (Simulation::advance; no stop requests here).
  const auto no_stop = [] { return std::int64_t{0}; };
  sim.advance(o.warmup, no_stop);
  if (other) other->advance(o.warmup, no_stop);
  const std::size_t builds0 = sim.counts().neighbour_builds;
  const double comm_before = sim.comm_seconds();
  const rondel::PhaseTimes phases0 = sim.phases();
  const Timed t = run_timed(o, sim, other.get(), comm);
  Measured m = measure(sim, comm, t, comm_before, phases0, builds0);
  m.peak_reset = !comm.any(!peak_reset), m.bandwidth = bandwidth;
  if (!comm.root()) return 0;
  print_report(o, nx, ny, sim, t, m, other != nullptr);
  if (other) print_against(o, t, m.n);
  print_bandwidth(o, m, m.n * static_cast<double>(o.steps) / t.secs, comm.size());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  rondel::MpiEnvironment mpi(&argc, &argv);
  rondel::Communicator comm;
  try {
    return bench(argc, argv, comm);
  } catch (const std::exception& e) {
    if (comm.root()) std::cerr << e.what() << '\n';
    return 1;
  }
}
