// Rank invariance (docs/design.md section 5, docs/validation.md section 8): a run on N ranks gives the bits of the
// 1-rank run, with every partitioner and with forced rebalancing; contact history travels with its discs.
// Also: the METIS partition balances a strongly non-uniform pile (docs/design.md section 6), and bad parallel
// input is refused on every rank.
//
// Every test is collective (the whole binary runs on 1 to 4 ranks, mpi.np1 ... mpi.np4). The 1-rank
// reference runs on rank 0 only, on MPI_COMM_SELF, in lock step with the N-rank run (ParallelTestUtil.hpp):
// the states (state_text) and the contact rows that carry state (every copy on every rank, all columns)
// are compared bit for bit at intervals, so a failure names its first differing step and line. Verdicts
// are broadcast, so rank 0 reports them.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "ParallelTestUtil.hpp"
#include "core/Partitioners.hpp"

namespace rondel {
namespace {

using namespace partest;

// 1. (a) Deposition into a box with walls, gravity, friction and the Wang rolling law.
TEST(RankInvariance, DepositionBitwiseEqualToOneRank) { check_scene("deposition", deposition_ini(), 4000, 250, true); }

// 1. (a') The deposition of (a) with local damping (run.local_damping = 0.7): the damped kicks (their sign
// tests on each velocity component) give the 1-rank bits.
TEST(RankInvariance, DepositionWithLocalDampingBitwiseEqualToOneRank) {
  check_scene("deposition, damped", deposition_ini() + "[run]\nlocal_damping = 0.7\n", 4000, 250, true);
}

// 1. (b) Dense periodic packing with random velocities and a drift across the seams (Jiang plastic rolling).
TEST(RankInvariance, PeriodicPackingBitwiseEqualToOneRank) { check_scene("periodic", periodic_ini(), 3000, 250, true); }

// 1. (c) Plane shear: the packing of (b), periodic in x only, between rough walls (the bottom and top rows are
// glued to them); the top wall is a servo and both walls shear in opposite directions, so glued discs cross
// the periodic seam and the rank borders and free discs press on glued ghosts.
TEST(RankInvariance, RoughShearCellBitwiseEqualToOneRank) {
  std::string ini = periodic_ini();
  const std::string from = "periodic_y = true";
  ini.replace(ini.find(from), from.size(), "periodic_y = false");
  ini +=
      "[walls]\nbox = bottom top\nrough = bottom top\n"
      "control = top:servo:5e3 top:shear:0.3 bottom:shear:-0.3\n";
  check_scene("rough shear", ini, 3000, 250, true);
}

// --- docs/validation.md section 8: a rolling disc and a two-disc impact at a subdomain boundary ---------------

constexpr double kR = 0.002, kDensity = 2650.0, kG = 9.81, kKn = 1e7;

// A probe of the cell map for a domain: the first x (scanning from the left along y) where the owner
// rank changes, or the middle of the box on one rank. Collective (constructs a Simulation).
double border_x(const std::string& ini, const std::vector<std::string>& overrides, double y) {
  static const Communicator world(MPI_COMM_WORLD);
  Simulation probe(parse_config_text(ini, overrides), world, false);
  const Domain& d = probe.config().domain;
  const int first = probe.decomposition().owner({d.xlo, y});
  const double step = 1e-5;
  for (double x = d.xlo; x < d.xhi; x += step)
    if (probe.decomposition().owner({x, y}) != first) return x;
  return 0.5 * (d.xlo + d.xhi);
}

std::string csv_line(int id, double x, double y, double R, double vx, double vy, double w) {
  return std::to_string(id) + "," + num(x) + "," + num(y) + "," + num(R) + "," + num(vx) + "," + num(vy) + "," +
         num(w) + "\n";
}

std::string rolling_ini(const std::string& law, const std::string& file) {
  return R"(
[domain]
xlo = 0
xhi = 0.06
ylo = 0
yhi = 0.02
)" + test::falling_contacts_ini() +
         test::rolling_law_ini(law) + R"(
[walls]
box = bottom left right
[scene]
type = csv
file = )" +
         file + "\n";
}

// 1. (f) A rotating drum (docs/physics.md section 8): 120 discs fall into a circle wall turning at 20 rad/s that
// carries a rotating lifter (a segment turning with it about the drum's centre), with gravity, Coulomb friction
// and the Wang rolling law: wall rows whose wall moves under the discs and turns (omega2 = Omega), and the
// neighbour list rebuilt for the lifter's sweep. The domain is wider than tall, so that the grid partitioner
// cuts the bed at the bottom of the drum with vertical borders (a horizontal one would leave it to one rank).
TEST(RankInvariance, RotatingDrumBitwiseEqualToOneRank) {
  const std::string ini = R"(
[domain]
xlo = -0.04
xhi = 0.04
ylo = -0.032
yhi = 0.032
)" + test::falling_contacts_ini() +
                          test::rolling_law_ini("wang") + R"(
[walls]
circles = 0 0 0.03 20
segments = 0 -0.0295 0 -0.023 20 0 0
[scene]
type = random
count = 120
region = -0.02 0.02 -0.02 0.02
radius_min = 0.001
radius_max = 0.0016
seed = 5
vy = -1
)";
  check_scene("drum", ini, 4000, 250, true);
}

// 2. A disc rolling without slip on the bottom wall crosses a rank border: its wall contact row (tangential
// spring xi and rolling spring x_r or theta_r) goes with it; every step is compared with the 1-rank run.
TEST(RankInvariance, RollingDiscCrossesBorderWithItsHistory) {
  for (const std::string law : {"wang", "jiang_plastic"}) {
    const double m = kDensity * std::numbers::pi * kR * kR, u0 = m * kG / kKn, a = kR - 0.5 * u0;
    const double y = kR - u0, v0 = 1.0;
    // Probe the border with the disc anywhere on the floor, then start it 4 mm to the left of the border.
    const std::string probe_file = write_temp("rondel-roll-probe", csv_line(0, 0.03, y, kR, 0, 0, 0));
    const std::vector<std::string> ov{"--parallel.partitioner=grid"};
    const double b = border_x(rolling_ini(law, probe_file), ov, y);
    const double x0 = b - 0.004;
    const std::string ini = rolling_ini(law, write_temp("rondel-roll", csv_line(0, x0, y, kR, v0, 0, -v0 / a)));
    // The run lasts 8 mm of rolling.
    static const Communicator world(MPI_COMM_WORLD);
    const double dt = Simulation(parse_config_text(ini, ov), world, false).dt();
    const int steps = static_cast<int>(std::ceil(0.008 / v0 / dt));
    std::map<std::int64_t, int> owner_start, owner_end;
    int dec_start = -1, dec_end = -1;
    double loaded = 0.0;  // largest |rolling spring| of the wall row seen (1-rank run)
    std::int64_t seen = 0;
    auto each = [&](Simulation& par, Simulation* ser) {
      const auto own = owners(par);
      if (world_rank() == 0) {
        if (seen == 0) owner_start = own;
        owner_end = own;
        const ContactTable& w = ser->wall_rows();
        for (std::size_t r = 0; r < w.size(); ++r)
          for (std::size_t k = 0; k < w.slot.size(); ++k)
            if (w.slot_names()[k] == "x_r" || w.slot_names()[k] == "theta_r")
              loaded = std::max(loaded, std::fabs(w.slot[k][r]));
        // The rank whose cell holds the disc now (from the 1-rank positions, same bits).
        const int dec = par.decomposition().owner(ser->discs().position[0]);
        if (seen == 0) dec_start = dec;
        dec_end = dec;
      }
      ++seen;
    };
    const LockstepResult r = run_lockstep(ini, ov, steps, 1, each);
    EXPECT_TRUE(r.equal) << law << ": " << r.what;
    if (world_rank() == 0) {
      std::cout << "[ rank-inv ] rolling disc (" << law << ") from x = " << x0 << " across x = " << b << ", " << steps
                << " steps: cell owner " << dec_start << " -> " << dec_end << ", stored on rank " << owner_start[0]
                << " -> " << owner_end[0] << ", largest rolling spring " << loaded << "\n";
      EXPECT_GT(loaded, 0.0) << law << ": the rolling spring never loaded";
      if (world_size() > 1) {
        EXPECT_NE(dec_start, dec_end) << law << ": the disc did not cross a rank border";
        EXPECT_NE(owner_start[0], owner_end[0]) << law << ": the disc did not change rank";
        EXPECT_EQ(owner_end[0], dec_end) << law << ": the disc is not stored on the owner of its cell";
      }
    }
  }
}

std::string impact_ini(const std::string& file) {
  return R"(
[domain]
xlo = 0
xhi = 0.06
ylo = 0
yhi = 0.02
[linear]
k_n = 1e7
e = 0.6
[coulomb]
k_s = 7.5e6
mu = 0.3
[contact]
rolling = jiang_brittle
[jiang]
delta = 0.2
[neighbour]
skin = 0.0001
[parallel]
partitioner = grid
[scene]
type = csv
file = )" +
         file + "\n";
}

// 2. A two-disc oblique impact with spins, Coulomb friction and the Jiang brittle rolling law (history xi,
// theta_r, broken) (i) straddling a rank border: the pair row lives on both ranks, and every copy must be
// the 1-rank row; (ii) drifting across the border during the contact: the row migrates mid-contact.
TEST(RankInvariance, TwoDiscImpactAtBorder) {
  const double y = 0.01, R1 = kR, R2 = 1.25 * kR;
  const std::string probe_file =
      write_temp("rondel-impact-probe", csv_line(0, 0.01, y, R1, 0, 0, 0) + csv_line(1, 0.05, y, R2, 0, 0, 0));
  const double b = border_x(impact_ini(probe_file), {}, y);
  struct Case {
    const char* name;
    std::string csv;
  };
  // (i) Approach at +-0.5 m/s, centres offset by 0.3 R in y, contact point on the border.
  const double g0 = 0.0003;  // initial surface gap
  const Case straddle{"straddling", csv_line(0, b - R1 - g0 / 2, y, R1, 0.5, 0, 150) +
                                        csv_line(1, b + R2 + g0 / 2, y + 0.3 * kR, R2, -0.5, 0, -80)};
  // (ii) Common drift 2 m/s, approach +-0.5 m/s: the contact starts with disc 1 0.1 mm left of the border.
  const double V = 2.0, u = 0.5, t_c = g0 / (2 * u), xB = b - 0.0001 - (V - u) * t_c;
  const Case drift{"drifting across",
                   csv_line(0, xB - R1 - R2 - g0, y, R1, V + u, 0, 300) + csv_line(1, xB, y, R2, V - u, 0, -100)};
  for (const Case& c : {straddle, drift}) {
    const std::string ini = impact_ini(write_temp("rondel-impact", c.csv));
    std::vector<int> owner1;   // rank storing disc 1 at each step
    std::vector<bool> active;  // the pair in contact at each step (1-rank run)
    bool broken = false;
    auto each = [&](Simulation& par, Simulation* ser) {
      const auto own = owners(par);
      if (world_rank() == 0) {
        owner1.push_back(own.at(1));
        bool on = false;
        const ContactTable& p = ser->pairs();
        for (std::size_t r = 0; r < p.size(); ++r) {
          on = on || p.F_n[r] > 0.0;
          for (std::size_t k = 0; k < p.slot.size(); ++k)
            if (p.slot_names()[k] == "broken" && p.slot[k][r] != 0.0) broken = true;
        }
        active.push_back(on);
      }
    };
    const LockstepResult r = run_lockstep(ini, {}, 120, 1, each);
    EXPECT_TRUE(r.equal) << c.name << ": " << r.what;
    if (world_rank() == 0) {
      int contact_steps = 0, moved_in_contact = 0;
      for (std::size_t s = 0; s < active.size(); ++s) {
        contact_steps += active[s];
        if (s > 0 && active[s] && active[s - 1] && owner1[s] != owner1[s - 1]) ++moved_in_contact;
      }
      std::cout << "[ rank-inv ] impact " << c.name << " x = " << b << ": " << contact_steps << " steps in contact, "
                << "active pair row on up to " << r.max_copies << " ranks, disc 1 changed rank during the contact "
                << moved_in_contact << " time(s), rolling contact broken: " << broken << "\n";
      EXPECT_GT(contact_steps, 3) << c.name << ": the discs never met";
      if (world_size() > 1) {
        if (std::string(c.name) == straddle.name) {
          EXPECT_GE(r.max_copies, 2) << "the contact did not straddle a border";
        } else {
          EXPECT_GE(moved_in_contact, 1) << "disc 1 did not change rank during the contact";
        }
      }
    }
  }
}

// --- docs/design.md section 6: METIS balance on a strongly non-uniform scene ---------------------------------

// A random pile in the bottom-left quarter of a wide box, settling under gravity; balance checks every 1000
// steps with forced repartitioning. sim.state().imbalance is measured at a check before that check repartitions,
// so the value at step 2000 is the quality of the partition made at step 1000 (after the migration).
// 4 ranks: METIS must reach max/mean <= 1.05; fewer ranks: no worse than the grid blocks.
TEST(MetisBalance, PileOnWideFloor) {
  const std::string ini = R"(
[domain]
xlo = 0
xhi = 0.24
ylo = 0
yhi = 0.12
[gravity]
y = -9.81
[linear]
k_n = 1e7
e = 0.3
[coulomb]
k_s = 7.5e6
mu = 0.5
[walls]
box = bottom left right
[scene]
type = random
count = 300
radius_min = 0.002
radius_max = 0.003
region = 0 0.1 0 0.12
seed = 5
vy = -0.5
[parallel]
balance_every = 100
force_balance = true
)";
  static const Communicator world(MPI_COMM_WORLD);
  std::map<std::string, double> imbalance;
  for (const std::string part : {"grid", "metis", "sfc"}) {
    Simulation sim(parse_config_text(ini, {"--parallel.partitioner=" + part}), world, false);
    for (int s = 0; s < 1001; ++s) sim.step();
    // Step 1001 has moved the discs to the map made at step 1000 (agreed in step 1001's reduction): per
    // rank, the work that the balance check measures (owned discs + booked contact rows).
    const auto rows = gather("  rank " + std::to_string(world_rank()) + ": " + std::to_string(sim.discs().n_owned()) +
                             " owned discs + " + std::to_string(sim.pairs().size()) + " contact rows; work " +
                             std::to_string(Decomposition::rank_work(sim.discs(), sim.pairs())) + "\n");
    if (world_rank() == 0) {
      std::cout << "[ balance  ] " << part << " map after step 1000:\n";
      for (const auto& l : rows) std::cout << l;
    }
    // The check at step 3000 measures the map of step 2900; step 3001 agrees on it (its reduction).
    for (int s = 1001; s < 3001; ++s) sim.step();
    imbalance[part] = sim.state().imbalance;
    if (world_rank() == 0)
      std::cout << "[ balance  ] pile on a wide floor (" << sim.decomposition().grid().nx() << " x "
                << sim.decomposition().grid().ny() << " cells), " << world_size() << " ranks, " << part
                << ": imbalance (max/mean of owned discs + booked contact rows) = " << sim.state().imbalance << "\n";
  }
  if (world_size() == 4) {
    EXPECT_LE(imbalance["metis"], 1.05) << "METIS imbalance on 4 ranks (grid: " << imbalance["grid"] << ")";
    EXPECT_LE(imbalance["sfc"], 1.05) << "Hilbert-cut imbalance on 4 ranks (grid: " << imbalance["grid"] << ")";
  }
  EXPECT_LE(imbalance["metis"], imbalance["grid"]) << "METIS is worse balanced than the grid blocks";
  EXPECT_LE(imbalance["sfc"], imbalance["grid"]) << "the Hilbert cuts are worse balanced than the grid blocks";
}

// --- Bad input: refused on every rank, no hang -------------------------------------------------------------

TEST(BadParallelInput, UnknownPartitionerRefused) {
  bool all = false;
  const std::string msg =
      config_error_everywhere([] { parse_config_text(deposition_ini(), {"--parallel.partitioner=zoltan"}); }, &all);
  EXPECT_TRUE(all) << "parallel.partitioner = zoltan was accepted";
  EXPECT_NE(msg.find("parallel.partitioner"), std::string::npos) << msg;
}

std::string tiny_ini(double xhi, const std::string& file) {
  return R"(
[domain]
xlo = 0
xhi = )" +
         num(xhi) + R"(
ylo = 0
yhi = 0.006
[gravity]
y = -9.81
[linear]
k_n = 1e7
e = 0.5
[contact]
tangential = none
[walls]
box = bottom left right
[scene]
type = csv
file = )" +
         file + "\n";
}

// A 6 mm box with one 2 mm disc has 1 x 1 cells (range 4.5 mm); a 10 mm box has 2 x 1. More ranks than
// cells is a ConfigError saying so, on every rank; otherwise the run steps normally.
TEST(BadParallelInput, MoreRanksThanCells) {
  static const Communicator world(MPI_COMM_WORLD);
  const std::string file = write_temp("rondel-tiny", csv_line(0, 0.003, 0.0025, kR, 0, 0, 0));
  for (const double xhi : {0.006, 0.010}) {
    const int cells = xhi < 0.008 ? 1 : 2;
    for (const auto& partitioner : Partitioners::choices()) {
      const std::string part = partitioner.word;
      bool all = false;
      const std::string msg = config_error_everywhere(
          [&] {
            Simulation sim(parse_config_text(tiny_ini(xhi, file), {"--parallel.partitioner=" + part}), world, false);
            EXPECT_EQ(sim.decomposition().grid().size(), static_cast<std::size_t>(cells));
            for (int s = 0; s < 20; ++s) sim.step();
          },
          &all);
      if (world_size() > cells) {
        EXPECT_TRUE(all) << world_size() << " ranks on " << cells << " cells (" << part << ") was accepted";
        EXPECT_NE(msg.find("ranks"), std::string::npos) << msg;
        EXPECT_NE(msg.find("only " + std::to_string(cells) + " cell"), std::string::npos) << msg;
        if (world_rank() == 0 && xhi < 0.008 && part == "grid") std::cout << "[ bad-input ] " << msg << "\n";
      } else {
        EXPECT_FALSE(all) << msg;
      }
    }
  }
}

}  // namespace
}  // namespace rondel
