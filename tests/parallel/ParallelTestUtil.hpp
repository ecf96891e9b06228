// Helpers of the MPI tests (tests/parallel): collectives on MPI_COMM_WORLD for verdicts and gathers, a
// bit-exact digest of the contact rows, and the lock-step comparison of an N-rank run with a 1-rank run.
#pragma once
#include <gtest/gtest.h>
#include <mpi.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "../support/ContactRows.hpp"
#include "app/Simulation.hpp"
#include "core/Errors.hpp"
#include "core/Partitioners.hpp"
#include "core/SceneBuilder.hpp"
#include "support/Assertions.hpp"
#include "support/Format.hpp"
#include "support/Scenes.hpp"

namespace rondel::partest {

inline int world_rank() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}
inline int world_size() {
  int n = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &n);
  return n;
}

// True on every rank iff `ok` on every rank.
inline void world_barrier() { MPI_Barrier(MPI_COMM_WORLD); }

inline bool all_ranks(bool ok) {
  int v = ok ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_INT, MPI_LAND, MPI_COMM_WORLD);
  return v != 0;
}

// Root's string on every rank.
inline std::string broadcast(std::string s, int root = 0) {
  long n = static_cast<long>(s.size());
  MPI_Bcast(&n, 1, MPI_LONG, root, MPI_COMM_WORLD);
  s.resize(static_cast<std::size_t>(n));
  if (n > 0) MPI_Bcast(s.data(), static_cast<int>(n), MPI_CHAR, root, MPI_COMM_WORLD);
  return s;
}

// Rank 0 gets every rank's string (in rank order); others get an empty vector.
inline std::vector<std::string> gather(const std::string& mine) {
  const int n = world_size();
  int len = static_cast<int>(mine.size());
  std::vector<int> lens(static_cast<std::size_t>(n)), displs(static_cast<std::size_t>(n));
  MPI_Gather(&len, 1, MPI_INT, lens.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  int total = 0;
  for (int r = 0; r < n; ++r) displs[r] = total, total += lens[r];
  std::string all(static_cast<std::size_t>(world_rank() == 0 ? total : 0), '\0');
  MPI_Gatherv(mine.data(), len, MPI_CHAR, all.data(), lens.data(), displs.data(), MPI_CHAR, 0, MPI_COMM_WORLD);
  std::vector<std::string> out;
  if (world_rank() != 0) return out;
  for (int r = 0; r < n; ++r)
    out.push_back(all.substr(static_cast<std::size_t>(displs[r]), static_cast<std::size_t>(lens[r])));
  return out;
}

// Every rank gets every rank's string (in rank order).
inline std::vector<std::string> all_gather(const std::string& mine) {
  auto parts = gather(mine);
  std::string joined;
  if (world_rank() == 0)
    for (const auto& p : parts) joined += std::to_string(p.size()) + ":" + p;
  joined = broadcast(joined);
  std::vector<std::string> out;
  std::size_t pos = 0;
  while (pos < joined.size()) {
    const std::size_t colon = joined.find(':', pos);
    const std::size_t len = std::stoul(joined.substr(pos, colon - pos));
    out.push_back(joined.substr(colon + 1, len));
    pos = colon + 1 + len;
  }
  return out;
}

using test::hex;
using test::lines_of;
using test::num;

// "line k: 1 rank '...', N ranks '...'" for the first line where two texts differ ("" when equal).
inline std::string first_difference(const std::string& expected, const std::string& actual) {
  return test::first_difference(expected, actual, "1 rank", "N ranks");
}

// One line per contact row that carries state (history or last forces): "P lo hi |", then every column but
// the local indices as name=value, in the column table's order, doubles in hex (W for wall rows).
inline std::string rows_text(const Simulation& sim) {
  std::string out;
  auto put = [&](const ContactTable& t, const char* tag) {
    for (std::size_t r = 0; r < t.size(); ++r) {
      if (!t.has_state(r)) continue;
      out += std::string(tag) + ' ' + std::to_string(t.key[r].lo) + ' ' + std::to_string(t.key[r].hi) + " | " +
             test::row_text(t, r, ~kColumnLocalIndex) + '\n';
    }
  };
  put(sim.pairs(), "P");
  put(sim.wall_rows(), "W");
  put(sim.bonds(), "B");  // the parallel bonds (none without [bonds])
  return out;
}

// The rows of every rank merged (rank 0): each contact once, sorted; `error` names a contact whose copies
// on two ranks differ; `max_copies` is the largest number of ranks holding one active (F_n > 0) pair row.
struct MergedRows {
  std::string text, error;
  int max_copies = 0;
};

inline MergedRows merge_rows(const std::vector<std::string>& per_rank) {
  MergedRows m;
  std::map<std::string, std::map<std::string, std::vector<int>>> by_key;  // key -> line -> ranks
  for (std::size_t r = 0; r < per_rank.size(); ++r)
    for (const std::string& l : lines_of(per_rank[r]))
      by_key[l.substr(0, l.find(" |"))][l].push_back(static_cast<int>(r));
  for (const auto& [key, variants] : by_key) {
    if (variants.size() > 1 && m.error.empty()) {
      m.error = "contact " + key + " differs between ranks:";
      for (const auto& [line, ranks] : variants)
        m.error += " [rank " + std::to_string(ranks.front()) + ": " + line + "]";
    }
    const auto& [line, ranks] = *variants.begin();
    m.text += line + "\n";
    // F_n is the first column after the key: active when it is not zero.
    const bool active = key[0] == 'P' && line.compare(key.size() + 3, 6, "0x0p+0") != 0;
    if (active) m.max_copies = std::max(m.max_copies, static_cast<int>(ranks.size()));
  }
  return m;
}

// Owned gids of every rank, gathered on rank 0 (owners[gid] = rank).
inline std::map<std::int64_t, int> owners(const Simulation& sim) {
  std::string mine;
  for (std::size_t i = 0; i < sim.discs().n_owned(); ++i) mine += std::to_string(sim.discs().gid[i]) + "\n";
  std::map<std::int64_t, int> out;
  const auto all = gather(mine);
  for (std::size_t r = 0; r < all.size(); ++r)
    for (const auto& l : lines_of(all[r])) out[std::stoll(l)] = static_cast<int>(r);
  return out;
}

// The files written by write_temp, removed when the test binary exits.
struct TempFiles {
  std::set<std::string> paths;
  ~TempFiles() {
    std::error_code ec;
    for (const auto& p : paths) std::filesystem::remove(p, ec);
  }
};
inline TempFiles& temp_files() {
  static TempFiles files;
  return files;
}

// A file with a per-rank name (every rank writes the same content, so no rank waits for another).
inline std::string write_temp(const std::string& stem, const std::string& content) {
  const auto path = std::filesystem::temp_directory_path() /
                    (stem + "-" + std::to_string(::getpid()) + "-r" + std::to_string(world_rank()) + ".csv");
  std::ofstream(path) << content;
  temp_files().paths.insert(path.string());
  return path.string();
}

// World ranks 0 .. size-1 as a communicator (the others get none and just wait). Simulation keeps a
// reference to the Communicator, so this object outlives the simulations built on it.
class SubComm {
 public:
  explicit SubComm(int size) {
    const int r = world_rank();
    MPI_Comm_split(MPI_COMM_WORLD, r < size ? 0 : MPI_UNDEFINED, r, &raw_);
    if (raw_ != MPI_COMM_NULL) comm_ = std::make_unique<Communicator>(raw_);
  }
  ~SubComm() {
    comm_.reset();
    if (raw_ != MPI_COMM_NULL) MPI_Comm_free(&raw_);
  }
  SubComm(const SubComm&) = delete;
  SubComm& operator=(const SubComm&) = delete;
  bool member() const { return comm_ != nullptr; }
  const Communicator& comm() const { return *comm_; }

 private:
  MPI_Comm raw_ = MPI_COMM_NULL;
  std::unique_ptr<Communicator> comm_;
};

// Scene (a): a few hundred polydisperse discs falling into a box (walls bottom, left, right) under gravity,
// Coulomb friction and the Wang rolling law (history: xi, x_r). 9 x 18 cells.
inline std::string deposition_ini() {
  return R"(
[domain]
xlo = 0
xhi = 0.06
ylo = 0
yhi = 0.12
)" + test::falling_contacts_ini() +
         test::rolling_law_ini("wang") + R"([walls]
box = bottom left right
[scene]
type = random
count = 200
radius_min = 0.0015
radius_max = 0.003
seed = 11
vy = -1.5
)";
}

// Scene (b): a dense periodic packing (periodic in x and y): a hex lattice of spacing 2 r0 with radii in
// [0.8, 1.01] r0 (slightly compressed where two large discs meet), random velocities and spins, and a common
// drift (scene.vx, scene.vy) that carries every disc across the rank borders and the periodic seams.
// Coulomb friction and the Jiang plastic rolling law (history: xi, theta_r). 20 x 20 discs, 17 x 15 cells.
inline std::string periodic_ini() {
  constexpr int nx = 20, ny = 20;
  constexpr double r0 = 0.001, a = 2 * r0;
  const double h = a * std::sqrt(3.0) / 2;
  SceneRandom rng(2024);
  std::string csv = "# id,x,y,radius,vx,vy,omega\n";
  int id = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double x = (i + 0.25 + 0.5 * (j % 2)) * a, y = (j + 0.5) * h;
      const double R = r0 * (0.8 + 0.21 * rng.uniform());
      const double vx = 0.5 * (2 * rng.uniform() - 1), vy = 0.5 * (2 * rng.uniform() - 1);
      const double w = 200.0 * (2 * rng.uniform() - 1);
      csv += std::to_string(id++) + "," + num(x) + "," + num(y) + "," + num(R) + "," + num(vx) + "," + num(vy) + "," +
             num(w) + "\n";
    }
  const std::string file = write_temp("rondel-periodic", csv);
  return R"(
[domain]
xlo = 0
xhi = )" +
         num(nx * a) + R"(
ylo = 0
yhi = )" +
         num(ny * h) + R"(
periodic_x = true
periodic_y = true
[linear]
k_n = 1e7
e = 0.7
[coulomb]
k_s = 7.5e6
mu = 0.4
[contact]
rolling = jiang_plastic
[jiang]
delta = 0.5
[scene]
type = csv
file = )" +
         file + R"(
vx = 1.5
vy = 0.8
max_initial_overlap = 0.05
)";
}

// Runs a scene on MPI_COMM_WORLD and, on rank 0, on a 1-rank communicator, in lock step; every `every`
// steps (and at the end) compares the states (state_text) and the merged contact rows bit for bit. The
// first mismatch stops the run. `each_check` (optional, all ranks) sees the N-rank simulation and, on
// rank 0, the 1-rank one (nullptr elsewhere) at every check.
struct LockstepResult {
  bool equal = true;
  std::int64_t first_bad_step = -1;
  std::string what;           // the first difference (all ranks)
  std::int64_t migrated = 0;  // discs moved between ranks in the N-rank run
  std::size_t builds = 0;     // neighbour builds of the N-rank run
  int max_copies = 0;         // most ranks holding one active pair row at a check
  std::string final_state;    // rank 0: the N-rank final state
};

inline LockstepResult run_lockstep(const std::string& ini, const std::vector<std::string>& overrides, int steps,
                                   int every, const std::function<void(Simulation&, Simulation*)>& each_check = {}) {
  static const Communicator self(MPI_COMM_SELF);
  static const Communicator world(MPI_COMM_WORLD);
  const bool root = world_rank() == 0;
  LockstepResult res;
  Simulation par(parse_config_text(ini, overrides), world, false);
  std::unique_ptr<Simulation> ser;
  if (root) ser = std::make_unique<Simulation>(parse_config_text(ini, overrides), self, false);
  auto check = [&]() {
    if (each_check) each_check(par, ser.get());
    const std::string ps = par.state_text();
    const MergedRows pr = merge_rows(gather(rows_text(par)));
    std::string verdict;
    if (root) {
      res.max_copies = std::max(res.max_copies, pr.max_copies);
      const std::string ss = ser->state_text();
      const MergedRows sr = merge_rows({rows_text(*ser)});
      const std::string at = "step " + std::to_string(par.step_count()) + ": ";
      if (ps != ss)
        verdict = at + "state differs, " + first_difference(ss, ps);
      else if (!pr.error.empty())
        verdict = at + pr.error;
      else if (pr.text != sr.text)
        verdict = at + "contact rows differ, " + first_difference(sr.text, pr.text);
      res.final_state = ps;
    }
    verdict = broadcast(verdict);
    if (!verdict.empty()) {
      res.equal = false;
      res.first_bad_step = par.step_count();
      res.what = verdict;
    }
    return verdict.empty();
  };
  bool ok = check();
  for (int s = 1; s <= steps && ok; ++s) {
    if (root) ser->step();
    par.step();
    if (s % every == 0 || s == steps) ok = check();
  }
  MPI_Bcast(&res.max_copies, 1, MPI_INT, 0, MPI_COMM_WORLD);
  res.migrated = par.diagnostics().migrated;
  res.builds = par.counts().neighbour_builds;
  return res;
}

// A decomposition a rank-invariance scene runs with: its name and its options (check_scene).
struct Variant {
  std::string name;
  std::vector<std::string> overrides;
};

// Every partitioner of the registry (core/Partitioners.hpp), keeping its first map and repartitioning every 10
// steps: a new partitioner is tested here without an edit.
inline const std::vector<Variant>& variants() {
  static const std::vector<Variant> v = [] {
    std::vector<Variant> out;
    for (const auto& partitioner : Partitioners::choices()) {
      const std::string option = std::string("--parallel.partitioner=") + partitioner.word;
      out.push_back({partitioner.word, {option}});
      out.push_back({std::string(partitioner.word) + "+rebalance/10",
                     {option, "--parallel.force_balance=true", "--parallel.balance_every=10"}});
    }
    return out;
  }();
  return v;
}

inline void check_scene(const std::string& scene, const std::string& ini, int steps, int every,
                        bool expect_shared_rows) {
  for (const Variant& var : variants()) {
    const auto t0 = std::chrono::steady_clock::now();
    const LockstepResult r = run_lockstep(ini, var.overrides, steps, every);
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (world_rank() == 0)
      std::cout << "[ rank-inv ] " << scene << " / " << var.name << " on " << world_size() << " ranks: " << steps
                << " steps, " << r.builds << " neighbour builds, " << r.migrated
                << " discs migrated, an active pair on up to " << r.max_copies << " ranks, " << secs << " s; "
                << (r.equal ? "bitwise equal" : "DIFFERS") << "\n";
    EXPECT_TRUE(r.equal) << scene << " / " << var.name << " on " << world_size() << " ranks: " << r.what;
    EXPECT_GE(r.builds, 5u) << scene << " / " << var.name;
    if (world_size() > 1) {
      EXPECT_GT(r.migrated, 0) << scene << " / " << var.name << ": no disc crossed a rank border";
      if (expect_shared_rows) {
        EXPECT_GE(r.max_copies, 2) << scene << " / " << var.name << ": no contact across a border";
      }
    }
  }
}

// Runs `body` on every rank; returns the message of a ConfigError thrown by it on every rank ("" when it
// did not throw), and fails when the ranks disagree (some threw, some did not).
template <class Body>
std::string config_error_everywhere(Body&& body, bool* all_threw) {
  std::string msg;
  bool threw = false;
  try {
    body();
  } catch (const ConfigError& e) {
    threw = true;
    msg = e.what();
  }
  const bool every = all_ranks(threw), none = all_ranks(!threw);
  EXPECT_TRUE(every || none) << "ConfigError on some ranks only (rank " << world_rank() << " threw: " << threw << ")";
  *all_threw = every;
  return msg;
}

// A directory made by rank 0 (unique per test and rank count), known to every rank; removed at the end
// unless the test failed (then it is kept and named, for a look at the files).
class SharedTempDir {
 public:
  explicit SharedTempDir(const std::string& tag) {
    std::string path;
    if (world_rank() == 0) {
      std::string tmpl = (std::filesystem::temp_directory_path() /
                          ("rondel-" + tag + "-np" + std::to_string(world_size()) + "-XXXXXX"))
                             .string();
      if (mkdtemp(tmpl.data())) path = tmpl;
    }
    path_ = broadcast(path);
    if (path_.empty()) throw std::runtime_error("mkdtemp failed");
    world_barrier();
  }
  ~SharedTempDir() {
    world_barrier();
    if (world_rank() != 0) return;
    if (::testing::Test::HasFailure()) {
      std::cout << "[ files    ] kept in " << path_ << "\n";
      return;
    }
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace rondel::partest
