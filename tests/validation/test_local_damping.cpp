// Local (non-viscous) damping, run.local_damping = alpha (docs/physics.md section 9, docs/validation.md
// section 12):
//  - a disc in free fall accelerates at g (1 - alpha) exactly (to round-off) once it moves; a force-free
//    component (horizontal motion, spin) is not damped at all; the stored force stays the undamped m g;
//  - the ledger books the damping's work as D_damping and closes with it: to round-off in free fall, and on a
//    granular scene (130 discs, walls, friction, rolling resistance) as well as it closes without damping,
//    while leaving D_damping out would open it by the damping's whole work;
//  - a checkpoint and restart continue the damped run bit for bit, D_damping included.
// Rank invariance with damping: tests/parallel/test_rank_invariance.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "app/Checkpointing.hpp"
#include "app/Simulation.hpp"
#include "support/Quiet.hpp"
#include "support/Scenes.hpp"
#include "support/TempDir.hpp"

namespace rondel {
namespace {

constexpr double kG = 9.81;

std::string num(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// One disc (radius 1 cm) in an open box under gravity, moving sideways at 0.3 m/s and spinning at 20 rad/s.
std::string free_fall_ini(double alpha) {
  return "[run]\nprogress = false\ndt = 2e-5\nlocal_damping = " + num(alpha) +
         "\n[domain]\nxlo = -1\nxhi = 1\nylo = -10\nyhi = 1\n[gravity]\ny = " + num(-kG) +
         "\n[linear]\nk_n = 1e5\n[coulomb]\nk_s = 7.5e4\nmu = 0.5\n[scene]\ntype = lattice_square\nnx = 1\nny = "
         "1\nradius = 0.01\nvx = 0.3\n"
         "omega = 20\n";
}

struct FreeFall {
  double accel = 0.0;  // (v_y(t2) - v_y(t1)) / (t2 - t1), after the first step
  double vx = 0.0, omega = 0.0;
  double force_y = 0.0, mass = 0.0;
  double residual = 0.0;  // |KE - KE0 - W_g + D_damping| [J]
  double W_g = 0.0, dt = 0.0;
  double damping_share = 0.0;  // D_damping / W_g
};

FreeFall free_fall(double alpha) {
  const Communicator comm;
  Simulation sim(parse_config_text(free_fall_ini(alpha)), comm, false);
  EXPECT_EQ(sim.config().local_damping, alpha);
  for (int s = 0; s < 2; ++s) sim.step();
  const double v1 = sim.discs().velocity[0].y, t1 = sim.time();
  for (int s = 0; s < 2000; ++s) sim.step();
  FreeFall f;
  f.accel = (sim.discs().velocity[0].y - v1) / (sim.time() - t1);
  f.vx = sim.discs().velocity[0].x;
  f.omega = sim.discs().omega[0];
  f.force_y = sim.discs().force[0].y;
  f.mass = sim.discs().mass[0];
  const EnergyLedger g = sim.global_ledger();
  f.residual = g.absolute_residual(sim.kinetic_energy());
  f.W_g = g.W_g;
  f.dt = sim.dt();
  f.damping_share = g.D_damping / g.W_g;
  return f;
}

TEST(LocalDamping, FreeFallAcceleratesAtGTimesOneMinusAlpha) {
  for (double alpha : {0.0, 0.3, 0.7, 0.95}) {
    SCOPED_TRACE("alpha = " + num(alpha));
    const FreeFall f = free_fall(alpha);
    const double expected = -kG * (1.0 - alpha);
    // The one kick that is not damped, the first (from rest), leaves KE above the per-kick booking by the
    // trapezoid's start term: the kicks use m g and (1 - alpha) m g, gravity's work m g v_1/2 dt, so
    // KE - KE0 - W_g + D_damping = alpha m g^2 h^2 / 2 (h = dt/2), and nothing after it.
    const double h = 0.5 * f.dt, start = alpha * f.mass * kG * kG * h * h / 2.0;
    std::printf(
        "[ damping  ] alpha %.2f: free-fall acceleration %.15g m/s^2 (g (1 - alpha) = %.15g), "
        "D_damping / W_g = %.6f, ledger residual %.6e J (alpha m g^2 h^2/2 = %.6e J; W_g %.4e J)\n",
        alpha, f.accel, expected, f.damping_share, f.residual, start, f.W_g);
    EXPECT_NEAR(f.accel, expected, 1e-11 * kG);
    // No force, no damping: the horizontal motion and the spin keep their values exactly.
    EXPECT_EQ(f.vx, 0.3);
    EXPECT_EQ(f.omega, 20.0);
    // The stored force is the undamped one (the body force m g).
    EXPECT_EQ(f.force_y, f.mass * -kG);
    // The ledger closes to round-off but for that start term, the damping taking alpha of gravity's work
    // (less the first kick from rest, undamped: a share of order 1/steps).
    EXPECT_NEAR(f.residual, start, 1e-12 * f.W_g);
    EXPECT_NEAR(f.damping_share, alpha, 1e-3);
    if (alpha == 0.0) {
      EXPECT_EQ(f.damping_share, 0.0);
    }
  }
}

// The granular scene of the checkpoint tests (130 discs dropped into a box whose left wall moves into the pile;
// friction and wang rolling resistance), 4000 steps.
struct Closure {
  double residual = 0.0;          // largest relative residual over the run (every 100 steps)
  double residual_without = 0.0;  // the same with D_damping left out of the balance
  double D_damping = 0.0, scale = 0.0;
};

Closure granular(double alpha) {
  const Communicator comm;
  Simulation sim(parse_config_text(test::moving_wall_box_ini("wang"), {"--run.local_damping=" + num(alpha)}), comm,
                 false);
  Closure c;
  for (int s = 1; s <= 4000; ++s) {
    sim.step();
    if (s % 100) continue;
    EnergyLedger g = sim.global_ledger();
    const double KE = sim.kinetic_energy();
    const double scale = std::max({g.scale, KE, std::fabs(g.W_g), std::fabs(g.W_w)});
    c.residual = std::max(c.residual, g.absolute_residual(KE) / scale);
    c.residual_without = std::max(c.residual_without, (g.absolute_residual(KE - g.D_damping)) / scale);
    c.D_damping = g.D_damping, c.scale = scale;
  }
  return c;
}

TEST(LocalDamping, LedgerClosesOnAGranularScene) {
  const Closure off = granular(0.0), on = granular(0.7);
  std::printf(
      "[ damping  ] granular scene: largest ledger residual %.3e (alpha 0) and %.3e (alpha 0.7; %.3e "
      "without D_damping); D_damping %.4e J of the energy scale %.4e J\n",
      off.residual, on.residual, on.residual_without, on.D_damping, on.scale);
  EXPECT_EQ(off.D_damping, 0.0);
  EXPECT_GT(on.D_damping, 0.05 * on.scale) << "the damping took little: the test would prove nothing";
  // With damping the ledger closes as well as without (the integration error of the contacts' trapezoid).
  EXPECT_LT(on.residual, 2.0 * off.residual + 1e-6);
  EXPECT_LT(on.residual, 1e-3);
  // Without D_damping it would not close.
  EXPECT_GT(on.residual_without, 30.0 * on.residual);
}

// N steps, a checkpoint, a restart and N more steps give the bits of 2N steps, and the ledger's D_damping
// continues through the checkpoint (/ledger/D_damping).
TEST(LocalDamping, CheckpointRestartIsBitwise) {
  test::TempDir tmp("rondel-test-damping");
  const std::string out = (tmp.path() / "run").string();
  const std::vector<std::string> overrides{"--run.local_damping=0.7", "--run.output=" + out, "--run.overwrite=true",
                                           "--run.steps=2000", "--output.checkpoint_every=1000"};
  const std::string ini = test::moving_wall_box_ini("wang", "[diagnostics]\nevery = 500\n");
  const Communicator comm;
  std::string reference;
  double D_reference = 0.0;
  {
    Simulation w(parse_config_text(ini, overrides), comm, true);
    test::QuietCout quiet;
    w.run();
    reference = w.state_text();
    D_reference = w.global_ledger().D_damping;
  }
  const std::string held = (tmp.path() / "step_1000.h5").string();
  std::filesystem::rename(std::filesystem::path(out) / Checkpointing::file_name("checkpoint", 1000), held);
  Simulation r(parse_config_text(ini, overrides), comm, true, held);
  EXPECT_EQ(r.step_count(), 1000);
  const double D_at_restart = r.global_ledger().D_damping;
  {
    test::QuietCout quiet;
    r.run();
  }
  EXPECT_GT(D_at_restart, 0.0) << "the checkpoint carried no D_damping";
  EXPECT_GT(D_reference, D_at_restart);
  EXPECT_EQ(r.state_text(), reference) << "N steps + checkpoint + restart + N steps differ from 2N steps";
  EXPECT_EQ(r.global_ledger().D_damping, D_reference);
}

}  // namespace
}  // namespace rondel
