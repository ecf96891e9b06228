// A disc rolling on a flat wall against each rolling law, docs/validation.md sections 2 and 6.
//
// Set-up (docs/validation.md sections 0 and 2): disc D5 (R = 0.005 m, rho = 2650 kg/m^3, thickness 1 m) on the
// bottom wall (a line at y = 0 with normal +y), contact set S (k_n = 1e6, k_s = 0.75e6 N/m, mu = 0.5,
// undamped unless a case says so), gravity 9.81 m/s^2, dt = 1e-4 s, 2 s. The disc starts at the static
// overlap u_n0 = mg/k_n with zero normal velocity (so F_n = mg throughout), v0 = 1 m/s along the contact's
// t = (1, 0) and omega0 = -v0/a, a = R - u_n0/2 (rolling without slip). Every law uses the equal-cap
// parameter map of docs/validation.md section 0: wall cap M = 0.1 F_n R (force_proportional: 0.1 F_n a) and,
// where there is a spring, K = 0.75 N m/rad (displacement_damping: K = M/theta_rmax).
//
// Expected values, computed below from these inputs (checked once against the numbers printed in
// docs/validation.md section 2 by RollingWall.FormulaCodeMatchesReferenceNumbers):
//   deceleration  M a/(I + m a^2);   KE0 = (m v0^2 + I omega0^2)/2
//   rigid-plastic stop            s      = a KE0/M
//   elastic-plastic first stop    s1     = a (KE0/M + M/(2K))
//   elastic-plastic rest          s_rest = s1 - a M/K
//   undamped band after the stop  [s1 - 2aM/K, s1];  jiang_brittle breaks at theta_r0 = 2F_n/(k_n B).
// s and s1 are the first-stop (largest) displacement: the largest x up to the first zero of vx.
// Tolerances (docs/validation.md section 2): rigid-plastic |s - s_exact| <= 1e-6 m; an elastic-plastic law
// whose rolling spring starts unloaded may overshoot s1 by up to v0 dt/2 (its spring loads within the
// first step, theta_r0/omega0 = 7e-6 s << dt, while the couple only acts from the second half-kick on).
#include <gtest/gtest.h>

#include "validation/RollingWall.hpp"

namespace rondel {
namespace {

using namespace test::rolling_wall;

// ---------------------------------------------------------------------------------------------------------
// The formula code against the reference numbers printed in docs/validation.md section 2 (checked once).

TEST(RollingWall, FormulaCodeMatchesReferenceNumbers) {
  const DiscOnWall d;
  EXPECT_NEAR(d.m, 0.20813051, 1e-8);
  EXPECT_NEAR(d.I, 2.6016314e-6, 1e-13);
  EXPECT_NEAR(d.mg, 2.0417603, 1e-7);
  EXPECT_NEAR(d.u_n0, 2.0417603e-6, 1e-13);
  EXPECT_NEAR(d.a, 4.9989791e-3, 1e-10);
  const Law ct = equal_cap("constant_torque"), fp = equal_cap("force_proportional");
  EXPECT_NEAR(d.deceleration(ct.M), 0.654044504, 1e-9);
  EXPECT_NEAR(kV0 / d.deceleration(ct.M), 1.52894794, 1e-8);
  EXPECT_NEAR(d.rigid_plastic_stop(ct.M, kV0), 0.764473972, 1e-9);
  EXPECT_NEAR(d.rigid_plastic_stop(fp.M, kV0), 0.764630091, 1e-9);
  for (const char* name : {"jiang_plastic", "jiang_brittle", "wang", "alonso_marroquin", "iwashita_oda"}) {
    SCOPED_TRACE(name);
    const Law l = equal_cap(name);
    EXPECT_NEAR(l.K, 0.75, 1e-12);
    EXPECT_NEAR(l.M, ct.M, 1e-15);  // equal caps
    EXPECT_NEAR(d.first_stop(l.M, l.K, kV0), 0.764477374, 1e-9);
    EXPECT_NEAR(d.rest(l.M, l.K, kV0), 0.76447057, 1e-8);
  }
  const Law dd = equal_cap("displacement_damping");
  EXPECT_NEAR(dd.K, 0.0291680, 1e-7);
  EXPECT_NEAR(dd.M, ct.M, 1e-15);
  const Law jb = equal_cap("jiang_brittle");
  const double theta_r0 = 2 * d.mg / (kKn * 0.3 * 2 * kR);  // 2 F_n/(k_n B)
  EXPECT_NEAR(theta_r0, 1.3611736e-3, 1e-10);
  EXPECT_NEAR(jb.K * theta_r0, jb.M, 1e-15);  // K_m theta_r0 = M0
  // The simulation builds the same disc.
  WallRun run(ct);
  EXPECT_NEAR(run.sim().discs().mass[0], d.m, 1e-14 * d.m);
  EXPECT_NEAR(run.sim().discs().inertia[0], d.I, 1e-14 * d.I);
  EXPECT_NEAR(run.sim().kinetic_energy(), d.KE0(kV0), 1e-14 * d.KE0(kV0));
}

// ---------------------------------------------------------------------------------------------------------
// Section 2, rigid-plastic laws: first stop s = a KE0/M to 1e-6 m, deceleration M a/(I + m a^2), stop time
// v0/decel (to the tangential ripple 1/w_t plus a step). After the stop neither law has a state that holds
// the disc: the couple follows sign(omega) of the half-step spin, chatters, and the disc creeps a little
// (reported, bounded loosely at 1e-4 m; it is not proportional to dt).

void check_rigid_plastic(const std::string& name) {
  const DiscOnWall d;
  const Law law = equal_cap(name);
  WallRun run(law);
  const Trace tr = run_trace(run);
  const double s = d.rigid_plastic_stop(law.M, kV0);
  const double decel = d.deceleration(law.M);
  const double t_stop = kV0 / decel;
  ASSERT_GT(tr.first_zero, 0u) << "the disc never stopped";
  std::printf("  %s (rigid-plastic, M = %.9e N m)\n", name.c_str(), law.M);
  print("first stop [m]", tr.first_stop_x(), s);
  print("deceleration, fit over 0.1-1.4 s [m/s^2]", fitted_deceleration(tr, 0.1, 1.4), decel);
  print("first time vx <= 0 [s]", tr.t[tr.first_zero], t_stop);
  print("x at t = 2 s (creep after the stop) [m]", tr.x_end(), s);
  print_residual(tr);
  EXPECT_LE(std::fabs(tr.first_stop_x() - s), 1e-6);
  EXPECT_NEAR(fitted_deceleration(tr, 0.1, 1.4), decel, 1e-5 * decel);
  EXPECT_NEAR(tr.t[tr.first_zero], t_stop, 1 / tangential_frequency() + kDt);
  EXPECT_LE(std::fabs(tr.x_end() - s), 1e-4);
  EXPECT_LE(tr.residual_max, 1e-3);
}

TEST(RollingWall, ConstantTorqueLimiterOffStopsAtRigidPlasticDistance) { check_rigid_plastic("constant_torque"); }

TEST(RollingWall, ForceProportionalStopsAtRigidPlasticDistance) { check_rigid_plastic("force_proportional"); }

// With the default limiter f_lim = 0.08 the couple is cut to f_lim I |omega|/dt once
// |omega| < omega_c = M dt/(f_lim I), after which omega decays geometrically (time constant
// tau = dt (I + m a^2)/(f_lim I)) instead of stopping: the disc creeps on, comes to rest later and further.
// Continuous estimate of the extra distance over s: a omega_c tau - a omega_c^2 (I + m a^2)/(2M)
//   = a M dt^2 (I + m a^2)/(2 f_lim^2 I^2)   (proportional to dt^2; 4.6e-6 m here), checked to 15 %.
TEST(RollingWall, ConstantTorqueDefaultLimiterCreepsOnAndStopsLater) {
  const DiscOnWall d;
  const Law off = equal_cap("constant_torque");
  Law on = off;
  on.overrides.erase(std::remove(on.overrides.begin(), on.overrides.end(), "--constant_torque.f_lim=0"),
                     on.overrides.end());
  ASSERT_EQ(on.overrides.size() + 1, off.overrides.size());
  WallRun run_off(off), run_on(on);
  ASSERT_DOUBLE_EQ(run_on.sim().config().params.wall(0).f_lim, 0.08);  // the default
  const Trace a = run_trace(run_off), b = run_trace(run_on);
  const double s = d.rigid_plastic_stop(off.M, kV0);
  const double t_stop = kV0 / d.deceleration(off.M);
  const double f_lim = 0.08, I_eff = d.I + d.m * d.a * d.a;
  const double extra = d.a * off.M * kDt * kDt * I_eff / (2 * f_lim * f_lim * d.I * d.I);
  // The stop of each run: where it comes within 1e-7 m of its first-stop displacement.
  const double t_off = a.time_within(a.first_stop_x(), 1e-7), t_on = b.time_within(b.first_stop_x(), 1e-7);
  std::printf("  constant_torque, limiter off (f_lim = 0) and on (f_lim = 0.08)\n");
  print("first stop, limiter off [m]", a.first_stop_x(), s);
  print("first stop, limiter on [m]", b.first_stop_x(), s + extra);
  print("x at t = 2 s, limiter on [m]", b.x_end(), s + extra);
  print("within 1e-7 m of the stop, limiter off [s]", t_off, t_stop);
  print("within 1e-7 m of the stop, limiter on [s]", t_on, t_stop);
  print_residual(b);
  EXPECT_NEAR(b.first_stop_x() - s, extra, 0.15 * extra);
  EXPECT_GT(b.first_stop_x(), a.first_stop_x() + 1e-6);  // further
  EXPECT_GT(t_on, t_off + 50 * kDt);                     // later
  EXPECT_NEAR(b.x_end(), b.first_stop_x(), 1e-9);        // and then at rest
  EXPECT_LE(b.residual_max, 1e-3);
}

// ---------------------------------------------------------------------------------------------------------
// Section 2, elastic-plastic laws without rolling damping. The first stop (largest displacement) is s1 to
// v0 dt/2; afterwards the rolling spring swings between +M and -M and x stays in [s1 - 2aM/K, s1]. Because
// the first stop may overshoot s1 by up to v0 dt/2, the band is checked twice: against s1 with that
// allowance, and against the observed first stop with a tight slack (2 % of the band plus 5e-7 m for the
// tangential spring's share of the compliance, 2 F_t/k_s with F_t ~ m decel).

void check_elastic_plastic(const std::string& name) {
  const DiscOnWall d;
  const Law law = equal_cap(name);
  WallRun run(law);
  const Trace tr = run_trace(run);
  const double s1 = d.first_stop(law.M, law.K, kV0);
  const double band = 2 * d.a * law.M / law.K;
  const double overshoot = 0.5 * kV0 * kDt;
  ASSERT_GT(tr.first_zero, 0u) << "the disc never stopped";
  const std::size_t after = tr.first_stop();
  const double top = tr.first_stop_x();
  const double lo = tr.min_from(after), hi = tr.max_from(after);
  std::printf("  %s (elastic-plastic, M = %.9e N m, K = %.7g N m/rad)\n", name.c_str(), law.M, law.K);
  print("first stop [m]", top, s1);
  print("largest x after the first stop [m]", hi, top);
  print("smallest x after the first stop [m]", lo, top - band);
  print("band width [m]", hi - lo, band);
  print("mean x after the first stop [m]", tr.mean_from(after), top - 0.5 * band);
  print_residual(tr);
  EXPECT_LE(top, s1 + overshoot);
  EXPECT_GE(top, s1 - overshoot);
  const double slack = 0.02 * band + 5e-7;
  // Band against the formula.
  EXPECT_LE(hi, s1 + overshoot);
  EXPECT_GE(lo, s1 - band - slack);
  // Band against the observed first stop.
  EXPECT_LE(hi, top + 1e-7);  // the first zero of vx may come early by the ripple: x then gains ~3e-8 m
  EXPECT_GE(lo, top - band - slack);
  EXPECT_NEAR(hi - lo, band, slack);
  EXPECT_NEAR(tr.mean_from(after), top - 0.5 * band, slack);
  EXPECT_LE(tr.residual_max, 1e-3);
}

TEST(RollingWall, JiangPlasticFirstStopAndUndampedBand) { check_elastic_plastic("jiang_plastic"); }
TEST(RollingWall, WangFirstStopAndUndampedBand) { check_elastic_plastic("wang"); }
TEST(RollingWall, IwashitaOdaFirstStopAndUndampedBand) { check_elastic_plastic("iwashita_oda"); }
TEST(RollingWall, DisplacementDampingFirstStopAndUndampedBand) { check_elastic_plastic("displacement_damping"); }

// ---------------------------------------------------------------------------------------------------------
// Section 2, elastic-plastic laws with rolling damping: they settle at s_rest = s1 - aM/K (to v0 dt/2, as
// the first stop), 0.1 s before the end at the latest (to 1e-8 m).
//
// With a rolling dashpot the capping rule (docs/physics.md section 1) loads the spring at t = 0+: the dashpot
// alone, mu |omega0|, exceeds the cap, so the couple is M from the start and the spring is reset to M/K
// without any rotation or work. The spring is then no longer "unloaded", and the law behaves exactly as a
// rigid-plastic one: first stop a KE0/M = s1 - aM/(2K), rest a KE0/M - aM/K (both checked to 1e-6 m, the
// rigid-plastic tolerance), 3.4e-6 m below s1 and s_rest for K = 0.75, inside VALIDATION's allowance.
// displacement_damping is different: its viscous part -nu C_crit omega acts in the elastic regime, i.e.
// during the initial loading at full spin (|omega0| = 200 rad/s, about 90 times the cap for two steps), and
// removes 2 % of KE0 there (and excites Coulomb slip); s1 does not apply, the first stop is 14 mm short
// (reported, only checked to lie below s1). It is checked for settling at first stop - aM/K.

void check_settles(const std::string& name) {
  const DiscOnWall d;
  const Law law = equal_cap(name, true);
  WallRun run(law);
  const bool dd = name == "displacement_damping";
  Simulation& sim = run.sim();
  double KE_loaded = 0.0;  // kinetic energy after the second step (displacement_damping: loading done)
  const Trace tr = run_trace(run, kDuration, [&](std::size_t k) {
    if (k == 2) KE_loaded = sim.kinetic_energy();
  });
  const double s1 = d.first_stop(law.M, law.K, kV0), s_rest = d.rest(law.M, law.K, kV0);
  const double overshoot = 0.5 * kV0 * kDt;
  const double spring = d.a * law.M / law.K;  // aM/K
  const double top = tr.first_stop_x();
  std::printf("  %s with rolling damping (%s)\n", name.c_str(), law.damping.c_str());
  print("first stop [m]", top, s1);
  print("rest (t = 2 s) [m]", tr.x_end(), s_rest);
  print("rest against first stop - aM/K [m]", tr.x_end(), top - spring);
  std::printf("    |vx| at t = 2 s %.3e m/s; at rest to 1e-8 m from t = %.4f s\n", std::fabs(tr.vx.back()),
              tr.settle_time(1e-8));
  print_residual(tr);
  // To 1 % of aM/K (the reversal near the stop is not exactly at the cap) plus the tangential spring.
  EXPECT_NEAR(tr.x_end(), top - spring, 0.01 * spring + 5e-7);
  EXPECT_LT(tr.settle_time(1e-8), kDuration - 0.1);
  EXPECT_LE(tr.residual_max, 1e-3);
  if (!dd) {
    const double s = d.rigid_plastic_stop(law.M, kV0);
    print("first stop against a KE0/M (spring loaded at t = 0+) [m]", top, s);
    print("rest against a KE0/M - aM/K [m]", tr.x_end(), s - spring);
    EXPECT_NEAR(top, s1, overshoot);
    EXPECT_NEAR(tr.x_end(), s_rest, overshoot);
    EXPECT_NEAR(top, s, 1e-6);
    EXPECT_NEAR(tr.x_end(), s - spring, 1e-6);
  } else {
    // Report where the energy went: the viscous pulses of the first two steps (and the Coulomb slip they
    // excite: ~0.1 N m excites the tangential mode beyond mu F_n) take KE0 - KE(2 dt) before the couple
    // reaches its cap; the first stop is short of s1 accordingly, never beyond it.
    std::printf(
        "    kinetic energy lost in the first two steps %.4e J (%.2f %% of KE0); ledger at t = 2 s: "
        "D_r_dashpot %.3e J, D_slip %.3e J, D_r_plastic %.4e J\n",
        d.KE0(kV0) - KE_loaded, 100 * (d.KE0(kV0) - KE_loaded) / d.KE0(kV0), sim.ledger().D_r_dashpot,
        sim.ledger().D_slip, sim.ledger().D_r_plastic);
    EXPECT_LT(top, s1);
  }
}

TEST(RollingWall, JiangPlasticWithNormalDampingSettlesAtRest) { check_settles("jiang_plastic"); }
TEST(RollingWall, WangWithRollingDashpotSettlesAtRest) { check_settles("wang"); }
TEST(RollingWall, IwashitaOdaWithRollingDashpotSettlesAtRest) { check_settles("iwashita_oda"); }
TEST(RollingWall, DisplacementDampingWithViscousPartSettlesAtRest) { check_settles("displacement_damping"); }

// ---------------------------------------------------------------------------------------------------------
// docs/validation.md section 10: alonso_marroquin with wang's parameters stops where wang stops. At a wall
// s1 = R omega and s2 = -V_t, so a rolling disc has s1 = s2 up to its lever (no slip at the contact point is
// V_t = -a omega, so s2 = a omega, u_n0/(2R) = 2e-4 below s1) and the tangential spring's ripple; until the
// first stop the couple is at its cap R mu_r F_n in both laws, so the first stop is the same (measured: the
// same bits), with or without the rolling dashpot.
// After the stop the laws differ. Near rest the undamped tangential spring of set S rings, s1 and s2 then
// often have different signs, and alonso_marroquin's spring and dashpot stop acting (W15: model 2 gives no
// rolling resistance then): the disc keeps rocking (undamped band 1.62e-5 m wide against 2aM/K = 1.36e-5 m;
// with c_r = 100 N s/m still 2e-6 m/s at t = 2 s, where wang is at rest from 1.57 s). Both are reported. With
// the tangential spring damped (coulomb.zeta_t = 0.5) the two laws end within 2e-8 m (c_r = 100, both at
// rest) and 9e-8 m (undamped rolling) of each other: checked to 1e-7 m and 5e-7 m.
// The ledger: the capped couple's work M |omega| dt is booked as plastic slip only for the spring's V_r2 dt =
// a |omega| dt, so D_rolling_plastic is smaller than wang's, and D_other larger, by M |theta| u_n0/(2R) over the
// rolling (3.2e-5 J, 2e-4 of the plastic work; checked to 1 % with the tangential spring damped, where the
// ripple adds nothing; 7.7e-5 J with it).

TEST(RollingWall, AlonsoMarroquinStopsWhereWangStops) {
  const DiscOnWall d;
  const Law wang = equal_cap("wang");
  const double s1 = d.first_stop(wang.M, wang.K, kV0), s = d.rigid_plastic_stop(wang.M, kV0);
  std::printf("  alonso_marroquin against wang, equal-cap parameters\n");
  for (bool tangential_damping : {false, true})
    for (bool damped : {false, true}) {
      Law w = equal_cap("wang", damped), am = equal_cap("alonso_marroquin", damped);
      if (tangential_damping) {
        w.overrides.push_back("--coulomb.zeta_t=0.5");
        am.overrides.push_back("--coulomb.zeta_t=0.5");
      }
      WallRun run_w(w), run_am(am);
      const Trace a = run_trace(run_w), b = run_trace(run_am);
      const std::string what = std::string(damped ? ", c_r = 100" : "") + (tangential_damping ? ", zeta_t = 0.5" : "");
      std::printf("  %s\n", what.empty() ? "set S" : ("set S" + what).c_str());
      ASSERT_GT(a.first_zero, 0u);
      ASSERT_GT(b.first_zero, 0u);
      print("first stop, alonso_marroquin against wang [m]", b.first_stop_x(), a.first_stop_x());
      print("x at t = 2 s, alonso_marroquin against wang [m]", b.x_end(), a.x_end());
      std::printf("    |vx| at t = 2 s %.3e m/s (wang %.3e m/s)\n", std::fabs(b.vx.back()), std::fabs(a.vx.back()));
      const DiagnosticsRow ra = run_w.sim().diagnostics(), rb = run_am.sim().diagnostics();
      print_residual(b);
      EXPECT_NEAR(b.first_stop_x(), a.first_stop_x(), 1e-9);
      if (damped)
        EXPECT_NEAR(b.first_stop_x(), s, 1e-6);  // the dashpot loads the spring at t = 0+ (check_settles)
      else
        EXPECT_NEAR(b.first_stop_x(), s1, 0.5 * kV0 * kDt);
      const double unbooked = wang.M * std::fabs(run_am.sim().discs().theta[0]) * d.u_n0 / (2 * kR);
      print("D_rolling_plastic, wang less alonso_marroquin [J]", ra.D_r_plastic - rb.D_r_plastic, unbooked);
      print("D_other, alonso_marroquin less wang [J]", rb.D_other - ra.D_other, unbooked);
      if (tangential_damping) {
        EXPECT_NEAR(ra.D_r_plastic - rb.D_r_plastic, unbooked, 0.01 * unbooked);
        EXPECT_NEAR(rb.D_other - ra.D_other, unbooked, 0.01 * unbooked);
        EXPECT_NEAR(b.x_end(), a.x_end(), damped ? 1e-7 : 5e-7);
        if (damped) {
          EXPECT_LT(std::fabs(b.vx.back()), 1e-12);
          EXPECT_LT(std::fabs(a.vx.back()), 1e-12);
        }
      }
      EXPECT_GT(rb.D_other, ra.D_other);
      EXPECT_LE(b.residual_max, 1e-3);
    }
}

}  // namespace
}  // namespace rondel
