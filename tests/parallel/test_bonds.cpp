// Parallel bonds on any rank count (docs/bonds.md): a bonded block of 160 discs dropped onto a floor breaks as it
// lands; with every partitioner, with and without forced rebalancing, the run on N ranks gives the 1-rank run's
// bits every 250 steps: every disc, every contact row and every bond row (each bond's copies on the ranks holding
// it identical), while bonds break, migrate with their discs and sit across rank borders. The snapshots' bonds
// (segments) and breaks are the same datasets on any rank count, and a run resumed on another rank count from a
// checkpoint taken between two snapshots writes the breaks it held into its next snapshot as the run would have.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "ParallelTestUtil.hpp"
#include "parallel/StateFile.hpp"
#include "support/Quiet.hpp"

namespace rondel {
namespace {

using namespace partest;

std::string bonded_drop_ini() {
  return R"(
[domain]
xlo = 0
xhi = 0.1
ylo = 0
yhi = 0.06
[gravity]
y = -9.81
[material]
density = 2650
[linear]
k_n = 2e6
e = 0.3
[coulomb]
k_s = 1.5e6
mu = 0.5
[contact]
rolling = wang
[wang]
k_r = 2e3
mu_r = 0.1
[bonds]
kb_n = 1e9
kb_s = 5e8
sigma_c = 1.5e4
tau_c = 1.5e4
sigma_spread = 0.5
tau_spread = 0.5
[walls]
box = bottom left right
[scene]
type = lattice_hex
nx = 20
ny = 8
radius = 0.002
x0 = 0.01
y0 = 0.006
vy = -0.4
)";
}

TEST(RankInvariance, ABondedBlockBreakingOnImpactBitwiseEqualToOneRank) {
  check_scene("bonded block", bonded_drop_ini(), 3000, 250, true);
}

// The scene breaks bonds in the window the test compares, and keeps some (else it would test neither).
TEST(RankInvariance, TheBondedBlockBreaksSomeOfItsBondsDuringTheRun) {
  const Communicator world(MPI_COMM_WORLD);
  Simulation sim(parse_config_text(bonded_drop_ini()), world, false);
  const DiagnosticsRow start = sim.diagnostics();
  for (int s = 0; s < 3000; ++s) sim.step();
  const DiagnosticsRow end = sim.diagnostics();
  EXPECT_GT(start.bonds, 300);
  EXPECT_EQ(start.n_b_tension + start.n_b_shear, 0.0);
  EXPECT_GT(end.n_b_tension + end.n_b_shear, 5.0);
  EXPECT_EQ(static_cast<double>(start.bonds - end.bonds), end.n_b_tension + end.n_b_shear);
  EXPECT_GT(end.bonds, start.bonds / 4);
}

// bonds.file: the horizontal neighbours of each row only, read in blocks on every rank and routed to their owners;
// the run on N ranks is the 1-rank run's, and a bad line is refused with the same message on any rank count.
TEST(RankInvariance, BondsFromAListBitwiseEqualToOneRankAndItsRefusalOnAnyRankCount) {
  SharedTempDir tmp("bond-list");
  const std::string list = (tmp.path() / "pairs.csv").string(), bad = (tmp.path() / "bad.csv").string();
  if (world_rank() == 0) {
    std::ofstream out(list);
    out << "gid1,gid2\n";
    for (int k = 0; k < 160; ++k)
      if (k % 20 != 19) out << k << ',' << k + 1 << '\n';
    std::ofstream(bad) << "gid1,gid2\n0,1\n# fine so far\n1,2\n5,150\n";
  }
  world_barrier();
  const LockstepResult r = run_lockstep(bonded_drop_ini(), {"--bonds.file=" + list}, 1500, 250);
  EXPECT_TRUE(r.equal) << r.what;
  const Communicator world(MPI_COMM_WORLD);
  std::string message = "accepted";
  try {
    Simulation sim(parse_config_text(bonded_drop_ini(), {"--bonds.file=" + bad}), world, false);
  } catch (const InputError& e) {
    message = e.what();
  }
  EXPECT_EQ(message, broadcast(message));
  EXPECT_NE(message.find("bad.csv' line 5: discs 5 and 150"), std::string::npos) << message;
}

// h5diff of the bonds' and breaks' groups of two snapshots: "" when equal. Rank 0 only.
std::string bond_groups_differ(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::string out;
  for (const char* group : {"/bonds", "/breaks"}) {
    const std::string cmd = "h5diff -q '" + a.string() + "' '" + b.string() + "' " + group + " > /dev/null 2>&1";
    const int status = std::system(cmd.c_str());
    if (!(status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0)) out += std::string(group) + " differs; ";
  }
  return out;
}

TEST(RankInvariance, TheSnapshotsBondsAndBreaksAreTheSameOnAnyRankCountAndAcrossAResume) {
  namespace fs = std::filesystem;
  SharedTempDir tmp("bond-snapshots");
  const fs::path one = tmp.path() / "one", many = tmp.path() / "many", resumed = tmp.path() / "resumed";
  const auto run = [&](const Communicator& comm, const fs::path& out, const std::string& from = "") {
    const std::vector<std::string> o{
        "--run.output=" + out.string(), "--run.overwrite=true",          "--run.steps=1500",
        "--output.snapshot_every=500",  "--output.checkpoint_every=750", "--output.checkpoint_keep=4",
        "--run.progress=false"};
    Simulation sim(parse_config_text(bonded_drop_ini(), o), comm, true, from);
    test::QuietCout quiet;
    sim.run();
  };
  if (world_rank() == 0) run(Communicator(MPI_COMM_SELF), one);
  world_barrier();
  const Communicator world(MPI_COMM_WORLD);
  run(world, many);
  world_barrier();
  // The checkpoint at step 750, after the block's first breaks (near step 700) and before the snapshot of 1000 that
  // records them, resumed on all ranks.
  if (world_rank() == 0) {
    fs::create_directories(resumed);
    fs::copy_file(one / "checkpoint_0000000750.h5", resumed / "checkpoint_0000000750.h5");
    fs::copy_file(one / "config.ini", resumed / "config.ini");
  }
  world_barrier();
  run(world, resumed, (resumed / "checkpoint_0000000750.h5").string());
  world_barrier();
  if (world_rank() != 0) return;
  for (const char* snap : {"snapshot_0000000500.h5", "snapshot_0000001000.h5", "snapshot_0000001500.h5"}) {
    EXPECT_EQ(bond_groups_differ(one / snap, many / snap), "") << snap << " on " << world_size() << " ranks";
    if (std::string(snap) != "snapshot_0000000500.h5") {
      EXPECT_EQ(bond_groups_differ(one / snap, resumed / snap), "") << snap << " resumed on " << world_size();
    }
  }
  EXPECT_NE(bond_groups_differ(one / "snapshot_0000000500.h5", one / "snapshot_0000001000.h5"), "")
      << "h5diff sees no difference between two steps";
  // The breaks of the window the resume cuts are in the snapshot of 1000 (none before, none after).
  const Communicator self(MPI_COMM_SELF);
  EXPECT_EQ(state_file_rows((one / "snapshot_0000000500.h5").string(), "/breaks/key", self), 0);
  EXPECT_GT(state_file_rows((one / "snapshot_0000001000.h5").string(), "/breaks/key", self), 0);
  EXPECT_GT(state_file_rows((one / "checkpoint_0000000750.h5").string(), "/breaks/key", self), 0);
  EXPECT_GT(state_file_rows((one / "snapshot_0000001500.h5").string(), "/bonds/key", self), 100);
}

}  // namespace
}  // namespace rondel
