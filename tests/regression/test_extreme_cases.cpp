// Stiff and extreme cases (docs/physics.md section 4; the issue on the critical time step): each either runs
// stably with the automatic step (finite energy, bounded overlap, small ledger residual, no energy gained)
// or is refused or stopped with a message that says why. A run that goes unstable anyway stops with an
// InstabilityError naming the step, the disc ids and the quantity that blew up, and keeps what it wrote.
//
// Cases: k_n = 1e12; radius ratio 100 in one packing; mu_r = 1 (wang, constant_torque); mu = 10; no
// damping at all; an impact at 10 m/s that overlaps more than 10 % of a radius; a forced run.dt = 3 x
// critical; the output written before such a failure.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "app/Simulation.hpp"
#include "core/Config.hpp"
#include "core/Errors.hpp"
#include "parallel/Communicator.hpp"
#include "support/Assertions.hpp"
#include "support/Quiet.hpp"
#include "support/TempDir.hpp"

namespace rondel {
namespace {

namespace fs = std::filesystem;

using test::read_file;
using test::TempDir;
using test::write_file;

using test::names;

// The number as Simulation's messages print it (6 significant digits).
std::string fmt6(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

constexpr double kR = 0.005;  // D5 discs

// A "gas" of nx x ny D5 discs on a square lattice with gaps of 1 % of R, random velocities (each component
// uniform in +-v0) and spins (+-v0/R), in a closed box [0, W] x [0, H] with a margin of R.
struct Gas {
  std::string csv;
  double W = 0.0, H = 0.0;
};
Gas make_gas(int nx, int ny, double v0, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double spacing = 2.02 * kR;
  Gas g;
  g.W = (nx + 1) * spacing;
  g.H = (ny + 1) * spacing;
  std::ostringstream s;
  s.precision(17);
  s << "id,x,y,radius,vx,vy,omega\n";
  int id = 1;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double vx = v0 * u(rng), vy = v0 * u(rng), w = v0 / kR * u(rng);
      s << id++ << ',' << (i + 1) * spacing << ',' << (j + 1) * spacing << ',' << kR << ',' << vx << ',' << vy << ','
        << w << '\n';
    }
  g.csv = s.str();
  return g;
}

// The INI of a scene in a closed box with gravity; contact set "k_n = 1e7, k_s = 0.75 k_n, mu = 0.5"
// (k_n = 1e7: a 1.4 m/s impact of D5 discs overlaps 3 % of R), frictionless without `coulomb`. Overrides
// change any of it.
std::string box_ini(const fs::path& csv, double W, double H, long steps, bool coulomb = true) {
  std::ostringstream s;
  s.precision(17);
  s << "[run]\nsteps = " << steps << "\nprogress = false\n"
    << "[diagnostics]\nevery = 50\n"
    << "[domain]\nxlo = 0\nxhi = " << W << "\nylo = 0\nyhi = " << H << "\n"
    << "[gravity]\ny = -9.81\n"
    << "[linear]\nk_n = 1e7\n"
    << (coulomb ? "[coulomb]\nk_s = 7.5e6\nmu = 0.5\n" : "[contact]\ntangential = none\n")
    << "[walls]\nbox = bottom left right top\n"
    << "[scene]\ntype = csv\nfile = " << csv.string() << "\n";
  return s.str();
}

// The gas scene (5 x 4 discs, v0 = 0.5 m/s); the contact laws are set by overrides.
struct GasCase {
  TempDir dir;
  std::string ini, frictionless_ini;
  explicit GasCase(long steps, double v0 = 0.5) {
    const Gas g = make_gas(5, 4, v0, 7u);
    write_file(dir / "gas.csv", g.csv);
    ini = box_ini(dir / "gas.csv", g.W, g.H, steps);
    frictionless_ini = box_ini(dir / "gas.csv", g.W, g.H, steps, false);
  }
};

using test::QuietCout;

// Runs a simulation to its end with the automatic step (Simulation::run checks the kinetic energy and the
// ledger residual at every diagnostics row, and the overlap at every step, here against `max_overlap`) and
// checks that it stayed stable: finite energy, a ledger residual below `max_residual`, and no energy
// gained: KE + stored - W_gravity - W_walls <= KE(0) (1 + `gain`) (the potential energy starts at 0).
// Returns the final diagnostics.
DiagnosticsRow expect_stable_run(const std::string& ini, std::vector<std::string> overrides, double max_overlap = 0.05,
                                 double max_residual = 1e-2, double gain = 1e-3) {
  Communicator comm;
  overrides.push_back("--run.max_overlap=" + fmt6(max_overlap));
  Simulation sim(parse_config_text(ini, overrides), comm, false);
  EXPECT_EQ(sim.dt(), sim.config().safety * sim.critical().dt) << "the automatic step";
  const double E0 = sim.kinetic_energy();
  DiagnosticsRow row;
  try {
    const RunSummary sum = sim.run();
    row = sim.diagnostics();
    EXPECT_LT(sum.ledger_residual, max_residual);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "the run stopped: " << e.what();
    return row;
  }
  const double E = row.ke_trans + row.ke_rot + row.E_stored - row.W_g - row.W_w;
  EXPECT_TRUE(std::isfinite(row.ke_trans + row.ke_rot));
  EXPECT_LT(row.max_overlap, max_overlap);
  EXPECT_LT(row.residual, max_residual);
  EXPECT_LE(E, E0 * (1.0 + gain)) << "energy gained with no work done";
  EXPECT_NE(sim.ledger().W_n, 0.0) << "no contact happened: the case tests nothing";
  std::printf(
      "[%s] dt = %.4g s (%s mode, %s), %lld steps: KE %.4g -> %.4g J, E_mech/E0 = %.6f, residual %.2e, "
      "max overlap %.3g R\n",
      ::testing::UnitTest::GetInstance()->current_test_info()->name(), sim.dt(), sim.critical().mode.c_str(),
      sim.critical().pair.c_str(), static_cast<long long>(sim.step_count()), E0, row.ke_trans + row.ke_rot, E / E0,
      row.residual, row.max_overlap);
  return row;
}

TEST(ExtremeCases, StiffnessOf1e12RunsWithTheAutomaticStep) {
  GasCase c(4000);
  const std::vector<std::string> stiff = {"--linear.k_n=1e12", "--coulomb.k_s=0.75e12", "--linear.e=0.5"};
  expect_stable_run(c.ini, stiff);
  // A user step fit for ordinary stiffness is refused, naming the critical step and its mode.
  std::vector<std::string> user = stiff;
  user.push_back("--run.dt=1e-5");
  try {
    Communicator comm;
    Simulation sim(parse_config_text(c.ini, user), comm, false);
    ADD_FAILURE() << "run.dt = 1e-5 s with k_n = 1e12 was accepted";
  } catch (const ConfigError& e) {
    EXPECT_TRUE(names(e.what(), "run.dt"));
    EXPECT_TRUE(names(e.what(), "critical time step"));
    EXPECT_TRUE(names(e.what(), "tangential mode"));
  }
}

TEST(ExtremeCases, RadiusRatio100InOnePacking) {
  // Two large discs (R = 1 cm) resting just above the floor, and 2 x 50 small ones (R = 0.1 mm) raining
  // onto them at 0.5 m/s (+-0.2 m/s), with gaps of 1 % of their radius.
  TempDir dir;
  const double RL = 0.01, Rs = 1e-4, W = 0.05;
  std::mt19937 rng(3u);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::ostringstream s;
  s.precision(17);
  s << "id,x,y,radius,vx,vy,omega\n";
  int id = 1;
  for (double xc : {0.015, 0.035}) s << id++ << ',' << xc << ',' << RL + 1e-6 << ',' << RL << ",0,0,0\n";
  for (double xc : {0.015, 0.035})
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 10; ++i)
        s << id++ << ',' << xc + (i - 4.5) * 2.02 * Rs << ',' << 2.0 * RL + 1e-6 + Rs * (1.02 + 2.02 * j) << ',' << Rs
          << ',' << 0.2 * u(rng) << ',' << -0.5 + 0.2 * u(rng) << ',' << 0.2 / Rs * u(rng) << '\n';
  write_file(dir / "bimodal.csv", s.str());
  const std::string ini = box_ini(dir / "bimodal.csv", W, 0.04, 3000);
  // k_n = 1e7: a small disc hitting a large one at 0.7 m/s overlaps 2 % of its radius.
  const DiagnosticsRow row = expect_stable_run(ini, {"--linear.e=0.5"});
  Communicator comm;
  const Simulation sim(parse_config_text(ini, {"--linear.e=0.5"}), comm, false);
  EXPECT_TRUE(names(sim.critical().pair, "R=0.0001")) << "the small discs limit the step";
  EXPECT_GT(row.contacts + row.wall_contacts, 0);
}

TEST(ExtremeCases, RollingFrictionOf1WangAndConstantTorque) {
  GasCase c(3000);
  SCOPED_TRACE("wang");
  expect_stable_run(c.ini, {"--linear.e=0.5", "--contact.rolling=wang", "--wang.k_r=3e5", "--wang.mu_r=1"});
  SCOPED_TRACE("constant_torque");
  expect_stable_run(c.ini, {"--linear.e=0.5", "--contact.rolling=constant_torque", "--constant_torque.mu_r=1"});
  SCOPED_TRACE("constant_torque without the moment limiter");
  expect_stable_run(c.ini, {"--linear.e=0.5", "--contact.rolling=constant_torque", "--constant_torque.mu_r=1",
                            "--constant_torque.f_lim=0"});
}

TEST(ExtremeCases, FrictionOf10) {
  GasCase c(3000);
  expect_stable_run(c.ini, {"--linear.e=0.5", "--coulomb.mu=10"});
}

TEST(ExtremeCases, NoDampingAtAll) {
  GasCase c(3000);
  // No dashpot anywhere; Coulomb slip still dissipates, so energy may fall but never grow.
  expect_stable_run(c.ini, {"--linear.zeta=0", "--coulomb.zeta_t=0"});
  // Frictionless and undamped: the mechanical energy is conserved to the integration error, which is first
  // order in dt here (contacts open and close within a step): a ledger residual of 0.025, 0.0093, 0.0056,
  // 0.0026 at run.safety = 0.2, 0.1, 0.05, 0.025 for this scene. Allow 3 % at the default step.
  const DiagnosticsRow row = expect_stable_run(c.frictionless_ini, {"--linear.zeta=0"}, 0.05, 0.03, 0.03);
  const double E = row.ke_trans + row.ke_rot + row.E_stored - row.W_g - row.W_w;
  Communicator comm;
  const Simulation fresh(parse_config_text(c.frictionless_ini, {"--linear.zeta=0"}), comm, false);
  EXPECT_NEAR(E / fresh.kinetic_energy(), 1.0, 0.03) << "the undamped, frictionless gas must conserve its energy";
  // With a Jiang rolling spring and no damping either.
  expect_stable_run(c.ini, {"--linear.zeta=0", "--contact.rolling=jiang_plastic", "--jiang.delta=1"});
}

// Steps `sim` until it throws; returns the InstabilityError's message ("" after a failure otherwise).
std::string step_until_instability(Simulation& sim, long max_steps) {
  try {
    for (long s = 0; s < max_steps; ++s) sim.step();
  } catch (const InstabilityError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InstabilityError, got: " << e.what();
    return "";
  }
  ADD_FAILURE() << "no InstabilityError within " << max_steps << " steps";
  return "";
}

// Two D5 discs (ids 1 and 2) meeting head-on at `v_rel`, or one disc (id 1) hitting the floor at `v_rel`.
std::string impact_ini(const TempDir& dir, double v_rel, bool wall) {
  const fs::path csv = dir / (wall ? "wall_impact.csv" : "impact.csv");
  std::ostringstream s;
  s.precision(17);
  s << "id,x,y,radius,vx,vy,omega\n";
  if (wall) {
    s << "1,0.05," << kR + 1e-4 << ',' << kR << ",0," << -v_rel << ",0\n";
  } else {
    s << "1," << 0.05 - kR - 1e-4 << ",0.05," << kR << ',' << 0.5 * v_rel << ",0,0\n";
    s << "2," << 0.05 + kR + 1e-4 << ",0.05," << kR << ',' << -0.5 * v_rel << ",0,0\n";
  }
  write_file(csv, s.str());
  return box_ini(csv, 0.1, 0.1, 1000);
}

TEST(ExtremeCases, FastImpactOverlappingMoreThan10PercentStopsNamingStepDiscsAndOverlap) {
  TempDir dir;
  // k_n = 1e7 at 10 m/s: the undamped peak overlap v sqrt(m_eff/k_n) is 0.2 R between discs, 0.29 R at the wall.
  for (bool wall : {false, true}) {
    SCOPED_TRACE(wall ? "disc on the floor" : "two discs");
    Communicator comm;
    Simulation sim(parse_config_text(impact_ini(dir, 10.0, wall), {"--linear.e=0.5"}), comm, false);
    EXPECT_EQ(sim.config().max_overlap, 0.1) << "the default run.max_overlap";
    const std::string m = step_until_instability(sim, 1000);
    // The state is that of the failing step's drift: the overlap it reports can be recomputed from it.
    const DiscStore& D = sim.discs();
    double ratio = 0.0;
    if (wall) {
      std::size_t i = 0;
      while (i < D.n_owned() && D.gid[i] != 1) ++i;
      ASSERT_LT(i, D.n_owned());
      ratio = (kR - D.position[i].y) / kR;
    } else {
      const Vec2 d = D.position[1] - D.position[0];
      ratio = (2.0 * kR - std::sqrt(dot(d, d))) / kR;
    }
    EXPECT_GT(ratio, 0.1);
    // Stopped at the first step past the limit: one step earlier (closing at most v_rel dt) it was below.
    EXPECT_LE(ratio - 10.0 * sim.dt() / kR, 0.1) << "stopped at the first step past the limit";
    EXPECT_TRUE(names(m, "step " + std::to_string(sim.step_count() + 1)));
    EXPECT_TRUE(names(m, wall ? "disc 1 and wall" : "discs 1 and 2"));
    EXPECT_TRUE(names(m, "overlap"));
    EXPECT_TRUE(names(m, fmt6(ratio))) << "the overlap / radius";
    EXPECT_TRUE(names(m, "run.max_overlap"));
  }
  // The same impact with stiff contacts (k_n = 1e10: peak overlap 0.6 % of R) runs with the automatic step.
  expect_stable_run(impact_ini(dir, 10.0, false), {"--linear.k_n=1e10", "--coulomb.k_s=0.75e10", "--linear.e=0.5"},
                    0.01);
}

std::string three_times_critical(const std::string& ini, std::vector<std::string> overrides) {
  Communicator comm;
  const Simulation probe(parse_config_text(ini, overrides), comm, false);
  std::ostringstream dt;
  dt.precision(17);
  dt << "--run.dt=" << 3.0 * probe.critical().dt;
  return dt.str();
}

TEST(ExtremeCases, ForcedStepOfThreeTimesCriticalStopsNamingStepDiscsAndQuantity) {
  GasCase c(2000);
  std::vector<std::string> forced = {"--linear.e=0.5"};
  forced.push_back(three_times_critical(c.ini, forced));
  forced.push_back("--run.force_dt=true");
  Communicator comm;
  Simulation sim(parse_config_text(c.ini, forced), comm, false);
  const std::string m = step_until_instability(sim, 2000);
  std::printf("[forced 3 x critical, overlap guard] %s\n", m.c_str());
  EXPECT_TRUE(names(m, "step " + std::to_string(sim.step_count() + 1)));
  EXPECT_TRUE(m.find("discs ") != std::string::npos || m.find("disc ") != std::string::npos) << m;
  EXPECT_TRUE(names(m, "overlap"));
}

TEST(ExtremeCases, EnergyGrowingWithNoWorkDoneStopsNamingStepDiscsAndQuantity) {
  // The overlap guard switched off (run.max_overlap = 1e9): the energy guard of Simulation::run must stop
  // the run, naming the step, the quantity (the ledger residual or a non-finite energy) and the discs.
  GasCase c(2000);
  std::vector<std::string> forced = {"--linear.e=0.5", "--run.max_overlap=1e9", "--diagnostics.every=1"};
  forced.push_back(three_times_critical(c.ini, forced));
  forced.push_back("--run.force_dt=true");
  Communicator comm;
  Simulation sim(parse_config_text(c.ini, forced), comm, false);
  std::string m;
  try {
    sim.run();
    ADD_FAILURE() << "the run at 3 x critical completed";
  } catch (const InstabilityError& e) {
    m = e.what();
  }
  std::printf("[forced 3 x critical, energy guard] %s\n", m.c_str());
  EXPECT_TRUE(names(m, "step " + std::to_string(sim.step_count())));
  EXPECT_TRUE(m.find("residual") != std::string::npos || m.find("energy") != std::string::npos) << m;
  EXPECT_TRUE(m.find("disc") != std::string::npos) << "the issue asks for the disc ids: '" << m << "'";
}

TEST(ExtremeCases, ContactsCreatingEnergyAtAForcedStepStopTheRun) {
  // Two discs meeting head-on with a forced step just above the critical one: the ledger's books close (its
  // residual stays at round-off, the normal contact's work is booked), but the contact does positive work,
  // which a closed spring-dashpot cannot: D_other < 0. The guard (run.max_energy_gain) stops the run; below
  // the critical step the same impact completes, with D_other >= 0.
  // The scene inputs/two_disc_impact.ini (D5 discs, k_n = 2e8, e = 0.5, 1 m/s head-on).
  const fs::path inputs = fs::path(RONDEL_SOURCE_DIR) / "inputs";
  std::ifstream file(inputs / "two_disc_impact.ini");
  const std::string ini((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(ini.empty());
  const std::vector<std::string> base = {"--scene.file=" + (inputs / "two_disc_impact.csv").string()};
  Communicator comm;
  const double critical = Simulation(parse_config_text(ini, base), comm, false).critical().dt;
  for (double factor : {0.9, 1.05, 3.0}) {
    SCOPED_TRACE("dt = " + std::to_string(factor) + " x critical");
    std::vector<std::string> forced = base;
    std::ostringstream dt;
    dt.precision(17);
    dt << "--run.dt=" << factor * critical;
    forced.push_back(dt.str());
    forced.push_back("--run.force_dt=true");
    Simulation sim(parse_config_text(ini, forced), comm, false);
    if (factor < 1.0) {
      EXPECT_NO_THROW(sim.run());
      const DiagnosticsRow row = sim.diagnostics();
      EXPECT_GE(row.D_other, -1e-12 * row.scale) << "a stable impact dissipates";
      continue;
    }
    std::string m;
    try {
      sim.run();
      ADD_FAILURE() << "the run at " << factor << " x critical completed";
    } catch (const InstabilityError& e) {
      m = e.what();
    }
    EXPECT_TRUE(names(m, "created")) << m;
    EXPECT_TRUE(names(m, "run.max_energy_gain")) << m;
    EXPECT_TRUE(names(m, "disc")) << m;
    EXPECT_LT(sim.diagnostics().D_other, 0.0);
  }
}

TEST(ExtremeCases, OutputWrittenBeforeAFailureIsKept) {
  GasCase c(2000);
  TempDir out_root;
  const fs::path out = out_root / "run";
  std::vector<std::string> forced = {"--linear.e=0.5", "--diagnostics.every=1", "--run.output=" + out.string()};
  forced.push_back(three_times_critical(c.ini, forced));
  forced.push_back("--run.force_dt=true");
  std::string m;
  {
    QuietCout quiet;
    Communicator comm;
    Simulation sim(parse_config_text(c.ini, forced), comm, true);
    try {
      sim.run();
      ADD_FAILURE() << "the run at 3 x critical completed";
    } catch (const InstabilityError& e) {
      m = e.what();
    }
  }
  ASSERT_FALSE(m.empty());
  ASSERT_TRUE(fs::exists(out / "diagnostics.csv"));
  std::istringstream diag(read_file(out / "diagnostics.csv"));
  int lines = 0;
  for (std::string line; std::getline(diag, line);)
    if (!line.empty()) ++lines;
  EXPECT_GE(lines, 2) << "a header and at least the step-0 row";
  EXPECT_TRUE(fs::exists(out / "config.ini"));
  if (fs::exists(out / "summary.txt")) {
    EXPECT_EQ(read_file(out / "summary.txt").find("complete"), std::string::npos) << "a failed run claims completion";
  }
  const std::string log = read_file(out / "log.txt");
  EXPECT_TRUE(names(log, "FAILED"));
  EXPECT_TRUE(names(log, m)) << "the log keeps the message";
}

}  // namespace
}  // namespace rondel
