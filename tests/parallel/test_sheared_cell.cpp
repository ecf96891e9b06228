// The deforming periodic cell across ranks (docs/physics.md section 10, docs/validation.md section 13): the dense
// periodic packing of RankInvariance sheared at a constant rate (Lees-Edwards) to a shear strain of 3, through
// three flips of the cell, gives the bits of the 1-rank run on 1 to 4 ranks (states and contact rows, compared in
// lock step), with or without a servo on the cell's height; a checkpoint written after the first flip and resumed
// on another rank count ends in the same bits. A gas that a servo compresses to under half its lengths takes a new
// decomposition grid on the way, with the same bits on any rank count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "ParallelTestUtil.hpp"
#include "app/Checkpointing.hpp"
#include "support/Assertions.hpp"
#include "support/Quiet.hpp"

namespace rondel {
namespace {

using namespace partest;
namespace fs = std::filesystem;

const Communicator& self_comm() {
  static const Communicator self(MPI_COMM_SELF);
  return self;
}

constexpr int kSteps = 3000;
constexpr double kStrain = 3.0;

// The packing sheared at the rate that reaches kStrain in kSteps steps of its time step. Rank 0's text on every
// rank: its scene file (the same bytes as every rank's) is then the one named in a checkpoint's configuration.
std::string sheared_ini() {
  static const std::string ini = [] {
    const Simulation probe(parse_config_text(periodic_ini(), {}), self_comm(), false);
    const double rate = kStrain / (kSteps * probe.dt());
    return broadcast(periodic_ini() + "[cell]\nrate_xy = " + num(rate) + "\n");
  }();
  return ini;
}

TEST(ShearedCellRanks, ShearedToStrainThreeBitwiseOnAnyRankCount) {
  std::int64_t flips = 0;
  double strain = 0.0;
  const LockstepResult r = run_lockstep(sheared_ini(), {}, kSteps, 250, [&](Simulation& par, Simulation*) {
    flips = par.state().flips;
    strain = par.measures().shear_strain;
  });
  if (world_rank() == 0)
    std::cout << "[ sheared  ] " << world_size() << " ranks: strain " << strain << ", " << flips << " flips, "
              << r.builds << " neighbour builds, " << r.migrated << " discs migrated; "
              << (r.equal ? "bitwise equal" : "DIFFERS") << "\n";
  EXPECT_TRUE(r.equal) << r.what;
  EXPECT_GE(flips, 2);
  EXPECT_NEAR(strain, kStrain, 0.01);
  if (world_size() > 1) {
    EXPECT_GT(r.migrated, 0);
    EXPECT_GE(r.max_copies, 2) << "no contact across a rank border";
  }
}

// The same shear with the cell's height servo-controlled to a contact stress S_yy (the exact sums in the step's
// reduction, every step): the rates the servo sets, and so every bit, are the 1-rank run's.
TEST(ShearedCellRanks, AStressControlledShearBitwiseOnAnyRankCount) {
  const LockstepResult r =
      run_lockstep(sheared_ini() + "stress_yy = 2e4\nservo_gain = 5\nservo_max_rate = 50\n", {}, kSteps / 2, 250);
  EXPECT_TRUE(r.equal) << r.what;
}

// Written on every rank of the world after the first flip, resumed on another rank count (1 -> 1, else one
// rank fewer): the 1-rank uninterrupted run's bits.
void restart_case(const std::string& ini) {
  constexpr int kHalf = kSteps / 2;  // past the first flip (strain 0.58)
  const int W = world_size();
  const bool root = world_rank() == 0;
  SharedTempDir tmp("sheared-restart");
  const fs::path out = tmp.path() / "run";
  const std::vector<std::string> common{"--run.output=" + out.string(), "--run.overwrite=true",
                                        "--output.checkpoint_every=" + std::to_string(kHalf), "--run.progress=false"};
  std::vector<std::string> overrides = common, half = common;
  overrides.push_back("--run.steps=" + std::to_string(kSteps));
  half.push_back("--run.steps=" + std::to_string(kHalf));
  std::string reference;
  if (root) {
    Simulation ref(parse_config_text(ini, overrides), self_comm(), false);
    for (int s = 0; s < kSteps; ++s) ref.step();
    reference = ref.state_text();
  }
  world_barrier();
  {
    static const Communicator world(MPI_COMM_WORLD);
    Simulation writer(parse_config_text(ini, half), world, true);
    test::QuietCout quiet;
    writer.run();
    EXPECT_EQ(writer.state().flips, 1) << "the checkpoint should come after the first flip";
  }
  world_barrier();
  const fs::path checkpoint = out / Checkpointing::file_name("checkpoint", kHalf);
  std::string restarted;
  {
    SubComm rc(W == 1 ? 1 : W - 1);
    if (rc.member()) {
      Simulation r(parse_config_text(ini, overrides), rc.comm(), true, checkpoint.string());
      EXPECT_EQ(r.state().flips, 1);
      test::QuietCout quiet;
      r.run();
      restarted = r.state_text();
    }
  }
  world_barrier();
  if (root) {
    EXPECT_EQ(test::first_difference(reference, restarted, "expected", "got"), "")
        << W << " ranks to step " << kHalf << ", resumed on " << (W == 1 ? 1 : W - 1) << " to " << kSteps;
  }
}

TEST(ShearedCellRanks, ARestartAfterAFlipOnAnotherRankCountIsBitwise) { restart_case(sheared_ini()); }

// The servo holds the mean contact stress S_yy of the sheared packing within 1 % of its target over strain 1 to 3
// (sampled every 10 steps), while the stress of 400 discs in flow fluctuates about it. Its gain scaled with the
// rate, as tools/mu_i.py scales it (0.163 x rate_xy: 38 /s here): a gain of 5 /s, 50 times slower than the
// shear, leaves the mean 30 % below the target at this I = 0.16.
TEST(ShearedCellRanks, TheServoHoldsTheMeanStressWithinOnePercent) {
  const std::string ini = sheared_ini() + "stress_yy = 2e4\nservo_gain = 38\nservo_max_rate = 50\n";
  if (world_rank() != 0) return;  // one run is enough: the bits are the same on any rank count (above)
  Simulation s(parse_config_text(ini, {}), self_comm(), false);
  double sum = 0.0, sum2 = 0.0;
  int n = 0;
  for (int k = 1; k <= kSteps; ++k) {
    s.step();
    if (k > kSteps / 3 && k % 10 == 0) {
      const double syy = s.measures().syy;
      sum += syy, sum2 += syy * syy, ++n;
    }
  }
  const double mean = sum / n, sd = std::sqrt(std::max(0.0, sum2 / n - mean * mean));
  std::cout << "[ servo    ] rate " << s.config().domain.L.xy << " /s, I " << s.measures().inertial
            << "; S_yy over strain 1 to 3: mean " << mean << " Pa (target 2e4), sd " << sd << " Pa, " << n
            << " samples\n";
  EXPECT_NEAR(mean, 2e4, 0.01 * 2e4);
}

// With the height held by the servo: its first step after the restart steers with the stress sums formed from the
// checkpoint's rows, as the uninterrupted run's did after its kernel.
TEST(ShearedCellRanks, AStressControlledRestartOnAnotherRankCountIsBitwise) {
  restart_case(sheared_ini() + "stress_yy = 2e4\nservo_gain = 5\nservo_max_rate = 50\n");
}

// A random gas of 250 discs at a packing fraction of 0.16, both lengths servo-controlled to 1e5 Pa: the cell
// shrinks at up to 40 /s to 0.44 of its lengths, below the half its grid was sized for, and takes a new
// decomposition grid (Simulation::regrid: the discs and their rows to the new grid's owners) before it jams: every
// bit the 1-rank run's, on any rank count, through the regrid.
TEST(ShearedCellRanks, AGasCompressedPastItsGridTakesANewGridBitwise) {
  const std::string gas =
      "[run]\nprogress = false\n[domain]\nxlo = 0\nxhi = 0.07\nylo = 0\nyhi = 0.07\nperiodic_x = true\n"
      "periodic_y = true\n[cell]\nstress_xx = 1e5\nstress_yy = 1e5\nservo_gain = 40\nservo_max_rate = 40\n"
      "[material]\ndensity = 2650\n[linear]\nk_n = 1e8\ne = 0.3\n[coulomb]\nk_s = 7.5e7\nmu = 0.1\n[scene]\n"
      "type = random\ncount = 250\nradius_min = 0.0008\nradius_max = 0.0012\nseed = 3\n";
  std::size_t regrids = 0;
  double lx = 0.0;
  const LockstepResult r = run_lockstep(gas, {}, 30000, 1000, [&](Simulation& par, Simulation*) {
    regrids = par.state().regrids;
    lx = par.measures().cell_lx;
  });
  if (world_rank() == 0)
    std::cout << "[ gas      ] " << world_size() << " ranks: L_x " << lx << " m, " << regrids << " new grids; "
              << (r.equal ? "bitwise equal" : "DIFFERS") << "\n";
  EXPECT_TRUE(r.equal) << r.what;
  EXPECT_LT(lx, 0.5 * 0.07) << "the cell should have shrunk past half its length";
  EXPECT_GE(regrids, 1u);
}

}  // namespace
}  // namespace rondel
