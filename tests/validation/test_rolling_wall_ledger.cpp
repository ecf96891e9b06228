// The disc rolling on a flat wall (docs/validation.md sections 2 and 6): jiang_brittle's break, the energy ledger of
// the rolling laws (plastic work, break energy) and its residual's order in dt. Set-up and formulas: RollingWall.hpp.
#include <gtest/gtest.h>

#include "validation/RollingWall.hpp"

namespace rondel {
namespace {

using namespace test::rolling_wall;

// ---------------------------------------------------------------------------------------------------------
// Section 2, jiang_brittle with jiang.after_break = open: the rolling spring passes theta_r0 = 2 F_n/(k_n B)
// after theta_r0/|omega0| (7e-6 s, inside the first step), the contact breaks (M = 0 from then on, the contact
// stays closed) and the disc rolls on at v0: it never stops.

TEST(RollingWall, JiangBrittleBreaksAndNeverStops) {
  const DiscOnWall d;
  Law law = equal_cap("jiang_brittle");
  law.overrides.push_back("--jiang.after_break=open");  // reform restarts the spring: test_rolling_jiang_brittle.cpp
  WallRun run(law);
  const double B = 0.3 * 2 * kR;
  const double theta_r0 = 2 * d.mg / (kKn * B);
  const double t_expected = theta_r0 / std::fabs(d.omega0(kV0));
  double t_break = -1.0, dv_after = 0.0;
  bool reclosed = false, opened = false;
  const Trace tr = run_trace(run, kDuration, [&](std::size_t) {
    const double broken = run.slot("broken");
    if (std::isnan(broken)) opened = true;  // no loaded wall row: the contact opened
    if (t_break < 0 && broken == 1.0) t_break = run.sim().time();
    if (t_break >= 0) {
      if (broken != 1.0) reclosed = true;
      dv_after = std::max(dv_after, std::fabs(run.vx() - kV0));
    }
  });
  std::printf("  jiang_brittle (theta_r0 = %.7e rad)\n", theta_r0);
  print("time of break [s]", t_break, t_expected);
  std::printf("    largest |vx - v0| after the break %.3e m/s\n", dv_after);
  print("x at t = 2 s [m]", tr.x_end(), kV0 * kDuration);
  print_residual(tr);
  ASSERT_GE(t_break, 0.0) << "never broke";
  EXPECT_GE(t_break, t_expected);
  EXPECT_LE(t_break, t_expected + 2 * kDt);
  EXPECT_FALSE(opened);
  EXPECT_FALSE(reclosed);
  EXPECT_LE(dv_after, 1e-6 * kV0);
  EXPECT_EQ(tr.first_zero, 0u);  // never stops
  EXPECT_NEAR(tr.x_end(), kV0 * kDuration, 1e-6);
  EXPECT_LE(tr.residual_max, 1e-3);
}

// ---------------------------------------------------------------------------------------------------------
// Section 6, jiang_plastic (undamped): the rolling plastic work at the first stop equals KE0 - M0^2/(2K_m)
// (the kinetic energy less what the spring holds there), and max_t |E_total(t) - E0|/E0 <= 2e-4.
//
// The split is exact (docs/physics.md section 5): the law books as dissipation what the trapezoid work of the
// couple, -(M' + M)/2 thetadot_r dt, leaves after the change of the stored K_m theta_r^2/2, so
// D_r_plastic + D_r_dashpot + the stored rolling energy = -W_rolling to round-off, and the plastic work at the
// first stop differs from KE0 - M0^2/(2K_m) only by what the motion's integration leaves (the ledger residual)
// and the energy of the other springs. Measured: 4.8e-8 J (3e-7 of KE0), max |E_total - E0|/E0 = 3.3e-9. (Booked
// with the end-of-step couple, as before, the first step's slip overshot by M0 |omega0| dt/2 - M0^2/(2K_m) =
// 1e-5 J, 6e-5 of KE0, and D_other went negative.) Every dissipation term stays >= 0 throughout, and D_other,
// measured from its start, within the ledger residual.

TEST(RollingWall, JiangPlasticLedgerPlasticWorkAndEnergyBalance) {
  const DiscOnWall d;
  const Law law = equal_cap("jiang_plastic");
  WallRun run(law);
  Simulation& sim = run.sim();
  const double E0 = energy_total(sim.diagnostics());
  // D_other = -W_c - E_stored - the dissipations counts the springs' energy at t = 0 (the static overlap) as
  // if it had been taken from the motion: it starts at -E_stored(0).
  const double E_stored0 = sim.diagnostics().E_stored;
  std::vector<double> plastic;
  double worst = 0.0, lowest = INFINITY, split = 0.0, lowest_other = INFINITY, residual = 0.0;
  const Trace tr = run_trace(run, kDuration, [&](std::size_t) {
    const DiagnosticsRow row = sim.diagnostics();
    plastic.push_back(row.D_r_plastic);
    worst = std::max(worst, std::fabs(energy_total(row) - E0) / E0);
    lowest = std::min({lowest, row.D_r_plastic, row.D_r_dashpot, row.D_slip});
    lowest_other = std::min(lowest_other, row.D_other);
    residual = std::max(residual, sim.ledger().absolute_residual(sim.kinetic_energy()));
    const EnergyLedger& L = sim.ledger();
    split = std::max(split, std::fabs(L.D_r_plastic + L.D_r_dashpot + sim.last_contacts().rolling + L.W_r));
  });
  ASSERT_GT(tr.first_zero, 0u);
  const double KE0 = d.KE0(kV0);
  const double expected = KE0 - law.M * law.M / (2 * law.K);
  const double tol = 1e-6 * KE0;
  const double got = plastic[tr.first_stop()];
  std::printf("  jiang_plastic ledger (E0 = %.9e J, KE0 = %.9e J)\n", E0, KE0);
  print("D_r_plastic at the first stop [J]", got, expected);
  std::printf(
      "    tolerance 1e-6 KE0 = %.3e J; max |E_total - E0|/E0 = %.3e (limit 1e-6); rolling split off by "
      "%.3e J; smallest dissipation term %.3e J; smallest D_other %.3e J (largest residual %.3e J)\n",
      tol, worst, split, lowest, lowest_other, residual);
  print_residual(tr);
  EXPECT_NEAR(got, expected, tol);
  EXPECT_LE(worst, 1e-6);
  EXPECT_LE(split, 1e-12 * KE0) << "D_r_plastic + D_r_dashpot + stored rolling energy = -W_rolling";
  EXPECT_GE(lowest, -1e-12 * KE0) << "every dissipation term is non-negative";
  EXPECT_GE(lowest_other + E_stored0, -(residual + 1e-12 * KE0))
      << "D_other (the dashpots) is non-negative but for the integration error";
  EXPECT_LE(tr.residual_max, 1e-3);
}

// ---------------------------------------------------------------------------------------------------------
// Section 6, jiang_brittle: at the break the stored rolling energy K_m theta_r^2/2 of that step (theta_r as
// the step found it, so at most M0^2/(2K_m)) moves from stored to E_r_break, with the work the couple took from
// the disc in the step's first half (-M_prev thetadot_r dt/2 of the trapezoid), and the ledger residual does
// not jump. At v0 = 1 m/s the break comes in the first step with nothing stored yet (checked above), so
// this runs at v0 = 0.01 m/s: omega0 dt = 2e-4 rad, the spring loads over about 7 steps and breaks with
// about 5e-7 J stored.
//
// The couple still acted in the first half-kick of the breaking step (trapezoid), work M_prev |omega| dt/2 that
// the release books with the stored energy: E_total does not change at the break beyond the integration's
// error (before, it dropped by that work, up to M0 |omega0| dt/2).

TEST(RollingWall, JiangBrittleLedgerAtBreak) {
  const DiscOnWall d;
  Law law = equal_cap("jiang_brittle");
  law.overrides.push_back("--jiang.after_break=open");  // the first break's release; reform's: the unit test
  const double v0 = 0.01;
  WallRun run(law, v0);
  Simulation& sim = run.sim();
  const double B = 0.3 * 2 * kR;
  const double theta_r0 = 2 * d.mg / (kKn * B);
  const double t_expected = theta_r0 / std::fabs(d.omega0(v0));
  // State before each step: theta_r, rolling stored energy, E_r_break, E_total, absolute residual.
  double theta_before = run.slot("theta_r"), break_before = 0.0, residual_before = run.absolute_residual();
  double E_before = energy_total(sim.diagnostics());
  double t_break = -1.0, released = 0.0, theta_at_break = 0.0, stored_after = -1.0, dE_total = 0.0;
  double residual_jump = 0.0, residual_step_max = 0.0;
  const Trace tr = run_trace(run, 0.05, [&](std::size_t k) {
    if (k == 0) return;
    const DiagnosticsRow row = sim.diagnostics();
    const double residual = run.absolute_residual(), E = energy_total(row);
    const double theta = run.slot("theta_r");
    if (t_break < 0 && run.slot("broken") == 1.0) {
      t_break = sim.time();
      released = row.E_r_break - break_before;
      theta_at_break = theta_before;
      stored_after = 0.5 * law.K * theta * theta;
      dE_total = E - E_before;
      residual_jump = std::fabs(residual - residual_before);
    } else {
      residual_step_max = std::max(residual_step_max, std::fabs(residual - residual_before));
    }
    theta_before = theta, break_before = row.E_r_break, residual_before = residual, E_before = E;
  });
  const double stored_before = 0.5 * law.K * theta_at_break * theta_at_break;
  const double cap_energy = law.M * law.M / (2 * law.K);
  // The couple's work in the breaking step's first half, K_m |theta_before| |thetadot_r| dt / 2 (no dashpot here;
  // the half-step spin a few per cent below omega0 by then).
  const double half_step = 0.5 * law.K * std::fabs(theta_at_break * d.omega0(v0)) * kDt;
  std::printf("  jiang_brittle ledger at v0 = %.2f m/s (theta_r0 = %.7e rad)\n", v0, theta_r0);
  print("time of break [s]", t_break, t_expected);
  print("E_r_break booked at the break [J]", released, stored_before + half_step);
  std::printf("    theta_r before the break %.7e rad; stored before %.6e J (cap M0^2/(2K_m) = %.6e J), after %.3e J\n",
              theta_at_break, stored_before, cap_energy, stored_after);
  std::printf("    E_total change over the breaking step %.3e J (bound M0 |omega0| dt/2 = %.3e J)\n", dE_total,
              0.5 * law.M * std::fabs(d.omega0(v0)) * kDt);
  std::printf("    ledger residual change over the breaking step %.3e J, largest over other steps %.3e J\n",
              residual_jump, residual_step_max);
  print_residual(tr);
  ASSERT_GE(t_break, 0.0) << "never broke";
  EXPECT_GE(t_break, t_expected);
  EXPECT_LE(t_break, t_expected + 2 * kDt);
  EXPECT_GT(stored_before, 0.5 * cap_energy);  // a real transfer, not the trivial one
  EXPECT_LE(stored_before, cap_energy);
  EXPECT_NEAR(released, stored_before + half_step, 0.1 * half_step);  // omega0 for the half-step spin
  EXPECT_GT(released, stored_before + 0.5 * half_step) << "the first half-step's work is released too";
  EXPECT_EQ(stored_after, 0.0);
  EXPECT_LE(std::fabs(dE_total), 1e-2 * half_step) << "E_total unchanged at the break";
  EXPECT_LE(residual_jump, 1e-3 * released);
  EXPECT_LE(residual_jump, 2 * residual_step_max);
  EXPECT_LE(tr.residual_max, 1e-3);
}

// ---------------------------------------------------------------------------------------------------------
// Section 6: the ledger residual |KE - KE0 - W_g - W_w - W_c| over the energy scale (largest KE so far) is
// below 1e-3 in every run above, and falls when the step is halved (here: constant_torque with the limiter
// off and jiang_plastic; velocity Verlet with trapezoidal work leaves a residual that scales as dt^2, so
// the largest residual must fall at least by half).

TEST(RollingWall, LedgerResidualFallsWhenStepHalved) {
  for (const char* name : {"constant_torque", "jiang_plastic"}) {
    const Law law = equal_cap(name);
    WallRun coarse(law, kV0, kDt), fine(law, kV0, 0.5 * kDt);
    const Trace a = run_trace(coarse), b = run_trace(fine);
    std::printf("  %s: largest relative ledger residual %.3e at dt = %g s, %.3e at dt/2 (ratio %.2f)\n", name,
                a.residual_max, kDt, b.residual_max, a.residual_max / b.residual_max);
    EXPECT_LE(a.residual_max, 1e-3) << name;
    EXPECT_LT(b.residual_max, 0.5 * a.residual_max) << name;
  }
}

}  // namespace
}  // namespace rondel
