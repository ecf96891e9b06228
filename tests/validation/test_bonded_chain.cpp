// A straight chain of bonded discs as a cantilever (docs/validation.md section 15, docs/bonds.md): 21 D5 discs
// 0.1 % apart (no contact ever forms), bonded (lambda = 1, kb_n = 1e9 Pa/m, kb_s = 0.5e9 Pa/m), the first held fixed
// in position and rotation, a small transverse force P on the last, damped to rest (run.local_damping). Each bond is
// a beam element between two centres l apart (axial kb_n A, shear kb_s A, bending kb_n I), so the discrete chain's
// static solution is exact: with n bonds, EI = kb_n I l and L = n l, the bond k from the fixed end carries the
// moment P l (n - k + 1/2) and the shear P, whence
//   tip rotation    P L^2 / (2 EI)
//   tip deflection  P L^3 / (3 EI) (1 - 1/(4 n^2)) + n P / (kb_s A)
// (the rotations summed bond by bond, each bond's shear slip P/(kb_s A) added). The run's tip must equal them to
// 1e-6 relative (P is small enough that the rotations, about 1e-4 rad, leave the geometry linear to 1e-8). The
// Timoshenko cantilever of the continuum (E = kb_n l, G = kb_s l, shear area 2 Rb t, factor 5/6) is within a few
// percent of it: the chain's deflection is 0.9994 of Euler-Bernoulli's, the discrete sum's 1 - 1/(4 n^2).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "app/Simulation.hpp"
#include "physics/BondParallel.hpp"
#include "support/StandardObjects.hpp"

namespace rondel {
namespace {

constexpr double kR = test::d5::R;
constexpr int kDiscs = 21;
constexpr double kSpacing = 2.0 * kR * 1.001;
constexpr double kP = 4e-3;  // [N per thickness]

std::string chain_ini() {
  char b[1024];
  std::snprintf(b, sizeof b, R"([run]
progress = false
local_damping = 0.8
[domain]
xlo = -0.01
xhi = 0.23
ylo = -0.02
yhi = 0.02
[material]
density = %.17g
[linear]
k_n = 1e6
[coulomb]
k_s = 7.5e5
mu = 0.5
[bonds]
kb_n = 1e9
kb_s = 0.5e9
sigma_c = 1e9
tau_c = 1e9
[scene]
type = lattice_square
nx = %d
ny = 1
radius = %.17g
spacing = %.17g
)",
                test::d5::density, kDiscs, kR, kSpacing);
  return b;
}

struct Tip {
  double deflection = 0.0, rotation = 0.0;
  std::int64_t bonds = 0;
  double ke = 0.0;
};

Tip tip_at_rest() {
  const Communicator comm;
  Simulation sim(parse_config_text(chain_ini()), comm, false);
  const std::size_t last = kDiscs - 1;
  EXPECT_EQ(sim.discs().gid[last], static_cast<std::int64_t>(last));
  const double y0 = sim.discs().position[last].y;
  sim.edit_discs([](DiscStore& d) {
    d.flags[0] |= kFlagFixed;
    return 0.0;
  });
  sim.set_driver_forces({static_cast<std::int64_t>(last)}, {Vec2{0.0, kP}});
  // Damped to rest: until the tip moves less than 1e-10 of its deflection in 20,000 steps.
  double before = 0.0;
  for (int chunk = 0; chunk < 200; ++chunk) {
    for (int s = 0; s < 20000; ++s) sim.step();
    const double now = sim.discs().position[last].y - y0;
    if (chunk > 2 && std::fabs(now - before) < 1e-10 * std::fabs(now)) break;
    before = now;
  }
  Tip t;
  t.deflection = sim.discs().position[last].y - y0;
  t.rotation = sim.discs().theta[last];
  t.bonds = static_cast<std::int64_t>(sim.bonds().size());
  t.ke = sim.kinetic_energy();
  return t;
}

TEST(BondedChain, TheCantileverTipIsTheDiscreteChainsExactStaticSolution) {
  const Tip tip = tip_at_rest();
  EXPECT_EQ(tip.bonds, kDiscs - 1);
  const BondGeometry g = BondGeometry::of(kR, kR, 1.0, 1.0);
  const double n = kDiscs - 1, l = kSpacing, L = n * l;
  const double EI = 1e9 * g.I * l;
  const double rotation = kP * L * L / (2.0 * EI);
  const double bending = kP * L * L * L / (3.0 * EI) * (1.0 - 1.0 / (4.0 * n * n));
  const double deflection = bending + n * kP / (0.5e9 * g.A);
  std::printf(
      "[ chain    ] tip deflection %.10g m (exact %.10g), rotation %.10g rad (exact %.10g); kinetic energy "
      "%.3g J\n",
      tip.deflection, deflection, tip.rotation, rotation, tip.ke);
  EXPECT_NEAR(tip.rotation / rotation, 1.0, 1e-6);
  EXPECT_NEAR(tip.deflection / deflection, 1.0, 1e-6);
  // Timoshenko's continuum cantilever with E = kb_n l and G = kb_s l (docs/bonds.md): within 1 %.
  const double timoshenko = kP * L * L * L / (3.0 * EI) + kP * L / ((5.0 / 6.0) * 0.5e9 * l * g.A);
  EXPECT_NEAR(tip.deflection / timoshenko, 1.0, 0.01);
}

// A bonded pair that breaks while rolling resistance acts (docs/validation.md section 15): two touching D5 discs spun
// in opposite senses bend their bond until it breaks; the contact's rolling couple (wang) is the law's from its own
// history before and after, so the break leaves no jump in it: its change in the breaking step is at most the law's
// own increment, k_r R*^2 |omega1 - omega2| dt, nothing of the bond's moment, which is a hundred times larger.
TEST(BondedChain, ABreakLeavesTheRollingCoupleToItsOwnHistory) {
  const std::string ini = R"([run]
progress = false
[domain]
xlo = -0.05
xhi = 0.05
ylo = -0.05
yhi = 0.05
[material]
density = 2650
[linear]
k_n = 1e6
[coulomb]
k_s = 7.5e5
mu = 0.5
[contact]
rolling = wang
[wang]
k_r = 3e4
mu_r = 0.1
[bonds]
kb_n = 1e9
kb_s = 5e8
sigma_c = 3e3
tau_c = 1e9
[scene]
type = lattice_square
nx = 2
ny = 1
radius = 0.005
spacing = 0.009999
x0 = -0.005
)";
  const Communicator comm;
  Simulation sim(parse_config_text(ini), comm, false);
  sim.edit_discs([](DiscStore& d) {
    d.omega[0] = 5.0, d.omega[1] = -5.0;
    return 0.0;
  });
  ASSERT_EQ(sim.bonds().size(), 1u);
  ASSERT_EQ(sim.pairs().size(), 1u);
  // wang's spring in rolling: dM = -k_r R*^2 dtheta_r, R* = R/2; the law's own increment in a step is at most
  // k_r R*^2 |omega1 - omega2| dt.
  const double k_rR2 = 3e4 * 0.0025 * 0.0025;
  double M_before = sim.pairs().M1[0], Mb_before = 0.0, jump = NAN, own = 0.0;
  for (int s = 0; s < 20000 && std::isnan(jump); ++s) {
    const double spin_before = std::fabs(sim.discs().omega[0] - sim.discs().omega[1]);
    sim.step();
    ASSERT_EQ(sim.pairs().size(), 1u);
    const double M = sim.pairs().M1[0];
    if (sim.bonds().size() == 0) {
      jump = std::fabs(M - M_before);
      own = k_rR2 * std::max(spin_before, std::fabs(sim.discs().omega[0] - sim.discs().omega[1])) * sim.dt();
      break;
    }
    M_before = M, Mb_before = sim.bonds().slot[2][0];
  }
  ASSERT_FALSE(std::isnan(jump)) << "the bond did not break";
  std::printf(
      "[ roll     ] at the break: bond moment %.4g N m, the rolling couple's change %.4g N m (the law's own "
      "increment at most %.4g)\n",
      Mb_before, jump, own);
  EXPECT_GT(std::fabs(Mb_before), 100.0 * jump);
  EXPECT_LE(jump, own);
}

// bonds.file: the pairs of a list instead of every pair within bonds.gap; its refusals name the file and the line.
TEST(BondedChain, BondsFromAListAndItsRefusals) {
  const Communicator comm;
  const std::string list = (std::filesystem::temp_directory_path() / "rondel-bond-list-test.csv").string();
  const auto error_of = [&](const std::string& text, std::int64_t* bonds = nullptr) -> std::string {
    std::ofstream(list) << text;
    try {
      Simulation sim(parse_config_text(chain_ini(), {"--bonds.file=" + list}), comm, false);
      if (bonds) *bonds = static_cast<std::int64_t>(sim.bonds().size());
      for (int s = 0; s < 10; ++s) sim.step();
    } catch (const std::exception& e) {
      return e.what();
    }
    return "accepted";
  };
  std::int64_t bonds = -1;
  EXPECT_EQ(error_of("gid1,gid2\n# the chain's first two bonds\n0,1\n\n2, 1\n", &bonds), "accepted");
  EXPECT_EQ(bonds, 2);
  const auto line2 = [&](const std::string& pair, const std::string& part) {
    const std::string e = error_of("gid1,gid2\n" + pair + "\n");
    EXPECT_NE(e.find("bonds.file '" + list + "' line 2: "), std::string::npos) << e;
    EXPECT_NE(e.find(part), std::string::npos) << e;
  };
  line2("0,99", "does not exist");
  line2("0,3", "of the smaller radius apart, above bonds.gap");
  line2("0,x", "is not a pair");
  line2("4,4", "is not a pair");
  line2("0,1,2", "is not a pair");
  const std::string twice = error_of("0,1\n1,0\n");
  EXPECT_NE(twice.find("lists 2 pairs but 1 distinct pairs"), std::string::npos) << twice;
  std::filesystem::remove(list);
  const std::string unreadable = [&] {
    try {
      Simulation sim(parse_config_text(chain_ini(), {"--bonds.file=" + list}), comm, false);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  }();
  EXPECT_NE(unreadable.find("bonds.file '" + list + "' cannot be read"), std::string::npos) << unreadable;
  Simulation plain(parse_config_text(chain_ini()), comm, false);  // without the list: every pair within bonds.gap
  EXPECT_EQ(static_cast<std::int64_t>(plain.bonds().size()), kDiscs - 1);
}

// Refused before any step, naming the keys: a gap that reaches beyond the neighbour skin (the pairs searched), and
// bonds in a deforming cell.
TEST(BondedChain, AGapBeyondTheSkinAndADeformingCellAreRefused) {
  const Communicator comm;
  const auto error_of = [&](const std::vector<std::string>& overrides) -> std::string {
    try {
      Simulation sim(parse_config_text(chain_ini(), overrides), comm, false);
    } catch (const std::exception& e) {
      return e.what();
    }
    return "accepted";
  };
  const std::string far = error_of({"--bonds.gap=0.5", "--neighbour.skin=0.001"});
  EXPECT_NE(far.find("bonds.gap = 0.5"), std::string::npos) << far;
  EXPECT_NE(far.find("neighbour.skin"), std::string::npos) << far;
  EXPECT_EQ(error_of({"--bonds.gap=0.5", "--neighbour.skin=0.003"}), "accepted");
  const std::string cell = error_of({"--domain.periodic_x=true", "--domain.periodic_y=true", "--cell.rate_xy=0.1"});
  EXPECT_NE(cell.find("[bonds] in a deforming cell"), std::string::npos) << cell;
}

}  // namespace
}  // namespace rondel
