// Parallel bonds on any rank count (docs/bonds.md): a bonded block of 160 discs dropped onto a floor breaks as it
// lands; with every partitioner, with and without forced rebalancing, the run on N ranks gives the 1-rank run's
// bits every 250 steps: every disc, every contact row and every bond row (each bond's copies on the ranks holding
// it identical), while bonds break, migrate with their discs and sit across rank borders.
#include <gtest/gtest.h>

#include <string>

#include "ParallelTestUtil.hpp"

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

}  // namespace
}  // namespace rondel
