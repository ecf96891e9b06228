// rondel_scaling_audit: runs one scene on the ranks it is started on and prints, on rank 0, one JSON line
// with the largest per-rank byte counts of the parallel structures and what the steps asked of MPI
// (tests/audit/scaling_audit.py runs it on 1, 2, 4 and 8 ranks and checks the scaling; docs/scaling.md), and
// what the set-up took on the largest rank: the growth of its resident set (peak during the set-up less the
// resident set before it) and its seconds (tests/audit/setup_audit.py). With --setup-twice the set-up is done,
// undone and done again and both are timed ("first_setup_seconds", "setup_seconds"): the second touches memory the
// first has just freed, as a set-up does on a machine where fresh memory costs no more than used memory (on a
// virtual machine whose balloon hands freed pages back to the host it costs a host fault a page; docs/scaling.md).
// With --paired-setups=K (on 2 ranks or more) it only times set-ups: K pairs, each a set-up on rank 0 alone and one
// on all the ranks, seconds apart in one job (see paired_setups).
//   mpirun -n P rondel_scaling_audit SCENE.ini STEPS OUTPUT_DIR [--setup-twice | --paired-setups=K] [--key=value ...]
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "BenchSupport.hpp"
#include "app/HugePages.hpp"
#include "app/Launch.hpp"
#include "app/Simulation.hpp"
#include "parallel/Communicator.hpp"
#include "parallel/StateFile.hpp"
#include "physics/LawRegistry.hpp"

namespace {

// A barrier of all the ranks in which each waits asleep (a rank spinning in MPI_Barrier would take a vCPU).
void sleeping_barrier() {
  MPI_Request request;
  MPI_Ibarrier(MPI_COMM_WORLD, &request);
  for (int done = 0; !done;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (!done) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

// The set-up as the executable does it (app/Launch.hpp, then the Simulation) on `comm`, and its slowest rank's
// seconds.
std::unique_ptr<rondel::Simulation> set_up(const rondel::Communicator& comm, const std::vector<std::string>& args,
                                           double& seconds) {
  comm.barrier();
  const double t0 = MPI_Wtime();
  rondel::Launch launch = rondel::prepare_launch({args}, comm);
  auto made = std::make_unique<rondel::Simulation>(std::move(launch.config), comm, true, launch.checkpoint);
  seconds = comm.max(MPI_Wtime() - t0);
  return made;
}

// The seconds of a set-up; the Simulation is then destroyed, untimed.
double timed_setup(const rondel::Communicator& comm, const std::vector<std::string>& args) {
  double seconds = 0.0;
  set_up(comm, args, seconds).reset();
  return seconds;
}

// --paired-setups=K: one untimed set-up on rank 0 alone (a communicator of one, the other ranks asleep) and one on
// all the ranks, then K timed pairs of the two, alternately first. Run with malloc keeping what it frees
// (MALLOC_MMAP_MAX_=0, no trim), every timed set-up touches memory its process has used, and the two of a pair
// run seconds apart: in the same minute of a host whose speed varies from minute to minute (docs/scaling.md).
void paired_setups(const rondel::Communicator& world, std::vector<std::string> args, const std::string& out,
                   int pairs) {
  MPI_Comm alone_comm;
  MPI_Comm_split(MPI_COMM_WORLD, world.root() ? 0 : MPI_UNDEFINED, 0, &alone_comm);
  std::string& output = *std::find_if(args.begin(), args.end(), [](const std::string& a) {
    return a.rfind("--run.output=", 0) == 0;  // main's, first of the keys
  });
  auto alone = [&] {
    double seconds = 0.0;
    output = "--run.output=" + out + "/alone";
    if (world.root()) {
      try {
        seconds = timed_setup(rondel::Communicator(alone_comm), args);
      } catch (const std::exception& e) {  // the other ranks wait in a barrier that rank 0 would not reach
        std::cerr << "rondel_scaling_audit: " << e.what() << '\n';
        MPI_Abort(MPI_COMM_WORLD, 1);
      }
    }
    sleeping_barrier();
    return seconds;
  };
  auto all = [&] {
    output = "--run.output=" + out + "/all";
    return timed_setup(world, args);
  };
  alone(), all();
  std::vector<double> one, two;
  for (int k = 0; k < pairs; ++k) {
    if (k % 2 == 0)
      one.push_back(alone()), two.push_back(all());
    else
      two.push_back(all()), one.push_back(alone());
  }
  const auto list = [](const std::vector<double>& v) {
    std::string text;
    for (double x : v) text += (text.empty() ? "" : ", ") + std::to_string(x);
    return text;
  };
  if (world.root())
    std::printf("{\"ranks\": %d, \"one\": [%s], \"all\": [%s]}\n", world.size(), list(one).c_str(), list(two).c_str());
  if (alone_comm != MPI_COMM_NULL) MPI_Comm_free(&alone_comm);
}

// The K of --paired-setups=K: a whole number from 1 to 1000.
int paired_count(const std::string& text) {
  std::size_t used = 0;
  int k = 0;
  try {
    k = std::stoi(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty() || k < 1 || k > 1000)
    throw std::invalid_argument("--paired-setups=" + text +
                                ": the number of pairs must be a whole number from 1 to 1000");
  return k;
}

}  // namespace

int main(int argc, char** argv) {
  const char* why = nullptr;
  if (!rondel::use_huge_pages(argv, why)) {  // as the executable does
    std::cerr << "rondel_scaling_audit: " << why << '\n';
    return 2;
  }
  rondel::MpiEnvironment mpi(&argc, &argv);
  rondel::Communicator comm;
  if (argc < 4) {
    if (comm.root())
      std::cerr << "usage: rondel_scaling_audit SCENE.ini STEPS OUTPUT_DIR [--setup-twice | --paired-setups=K] "
                   "[--key=value ...]\n";
    return 2;
  }
  try {
    std::vector<std::string> args{argv[1], "--run.output=" + std::string(argv[3]), "--run.progress=false",
                                  "--run.overwrite=true"};
    bool twice = false;
    int pairs = 0;
    for (int i = 4; i < argc; ++i)
      if (std::string(argv[i]) == "--setup-twice")
        twice = true;
      else if (std::string(argv[i]).rfind("--paired-setups=", 0) == 0)
        pairs = paired_count(std::string(argv[i]).substr(16));
      else
        args.emplace_back(argv[i]);
    if (pairs > 0) {
      if (comm.size() < 2) throw std::invalid_argument("--paired-setups needs 2 ranks or more");
      if (twice) throw std::invalid_argument("--paired-setups and --setup-twice are two protocols: give one");
      paired_setups(comm, args, argv[3], pairs);
      return 0;
    }
    const std::int64_t steps = std::stoll(argv[2]);
    // The set-up from a reset peak; the bytes are those of the first set-up.
    const bool peak_reset = rondel::reset_peak_rss();
    const long rss0 = rondel::resident_kib();
    double first_seconds = 0, setup_seconds = 0;
    auto made = set_up(comm, args, first_seconds);
    const std::int64_t setup_bytes =
        peak_reset ? comm.max(static_cast<std::int64_t>(rondel::peak_rss_kib() - rss0) * 1024) : -1;
    if (twice) {
      made.reset();
      made = set_up(comm, args, setup_seconds);
    } else {
      setup_seconds = first_seconds;
    }
    rondel::Simulation& sim = *made;
    for (std::int64_t s = 0; s < steps; ++s) sim.step();
    sim.settle_errors();
    const auto before = comm.stats();
    if (sim.config().checkpoint_at_end) sim.write_checkpoint();  // the checkpoint's bytes and collectives (0 if not)
    const auto after = comm.stats();
    auto max_of = [&](std::size_t v) { return comm.max(static_cast<std::int64_t>(v)); };
    const std::int64_t n = static_cast<std::int64_t>(sim.counts().steps_taken);
    const auto& c = sim.counts().step_comm;
    const std::int64_t owned = max_of(sim.discs().n_owned()), ghosts = max_of(sim.state().ghosts);
    const std::int64_t dec = max_of(sim.decomposition_bytes()), exch = max_of(sim.exchange_bytes()),
                       neigh = max_of(sim.neighbour_bytes()), ckpt = max_of(rondel::peak_checkpoint_structure_bytes());
    const std::int64_t coll = comm.max(c.collectives), msgs = comm.max(c.messages), bytes = comm.max(c.bytes);
    const std::int64_t total_discs = comm.sum(static_cast<std::int64_t>(sim.discs().n_owned()));
    const std::int64_t ckpt_coll = comm.max(after.collectives - before.collectives);
    if (comm.root())
      std::printf(
          "{\"ranks\": %d, \"discs\": %lld, \"steps\": %lld, \"max_owned\": %lld, \"max_ghosts\": %lld, "
          "\"decomposition_bytes\": %lld, \"exchange_bytes\": %lld, \"neighbour_bytes\": %lld, "
          "\"checkpoint_bytes\": %lld, \"step_collectives\": %lld, \"step_messages\": %lld, \"step_bytes\": %lld, "
          "\"checkpoint_collectives\": %lld, \"neighbour_builds\": %lld, \"setup_bytes\": %lld, "
          "\"first_setup_seconds\": %.6g, \"setup_seconds\": %.6g}\n",
          comm.size(), static_cast<long long>(total_discs), static_cast<long long>(n), static_cast<long long>(owned),
          static_cast<long long>(ghosts), static_cast<long long>(dec), static_cast<long long>(exch),
          static_cast<long long>(neigh), static_cast<long long>(ckpt), static_cast<long long>(coll),
          static_cast<long long>(msgs), static_cast<long long>(bytes), static_cast<long long>(ckpt_coll),
          static_cast<long long>(sim.counts().neighbour_builds), static_cast<long long>(setup_bytes), first_seconds,
          setup_seconds);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "rondel_scaling_audit: " << e.what() << '\n';
    return 1;
  }
}
