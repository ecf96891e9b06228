// Walton-Braun (normal = walton_braun), docs/validation.md section 14, against the formulas of docs/physics.md
// section 11:
//  - the loading-unloading-reloading cycle by prescribed overlap (to the first maximum U, back to 50 % and 20 % of
//    it, up to 120 %): the force follows K1, then K2 (and 0 below u_0 = U (1 - K1/K2), the history kept), then K2
//    back to the loading line and K1 beyond it, to 1e-12 relative; the stored energy F^2/(2 K2) and the loss
//    K1 (1 - K1/K2) (u_max'^2 - u_max^2)/2 close the work of every leg;
//  - two D5 discs head-on (K1 = 1e6 N/m, e = 0.5, 0.1 m/s each, no tangential force), stepped by the run's own
//    step core (OneContactRig): the largest overlap v_rel sqrt(m_eff/K1), the rebound within 5e-3 of e at
//    dt = t_c/50 (t_c = pi sqrt(m_eff/K1), the loading half-period), its worst error over the onset's phase in a
//    step falling as dt^2 (measured: 2.0 from t_c/100 to t_c/800), the dissipation
//    (1 - e^2) KE0 in D_n_hyst and the ledger closed; the same disc on a wall;
//  - the contact's duration (pi/2)(sqrt(m_eff/K1) + sqrt(m_eff/K2)) and e = sqrt(K1/K2) at any speed;
//  - the critical step's normal mode at K2, and the keys: e or K2 (one of them), K2 below K1 refused naming it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "OneContactRig.hpp"
#include "core/Errors.hpp"
#include "physics/CriticalTimeStep.hpp"
#include "physics/LawRegistry.hpp"
#include "physics/NormalWaltonBraun.hpp"
#include "physics/PairConstants.hpp"
#include "support/StandardObjects.hpp"

namespace rondel {
namespace {

constexpr double kK1 = 1e6, kE = 0.5, kK2 = kK1 / (kE * kE);  // 4e6 N/m
constexpr double kR = test::d5::R;
const LawSelection kLaws{"walton_braun", "none", "none"};

ContactParams wb_params(double K1 = kK1, double e = kE) {
  ContactParams p;
  p.k_n = K1;
  p.e_wb = e;
  ContactParamTable t(1);
  t.pair(0, 0) = p;
  t.wall(0) = p;
  Material m;
  m.name = "grain";
  resolve_pair_constants(t, {m});
  return t.pair(0, 0);
}

// The law at overlap u with the history u_max (read and written): its force and its hysteresis.
NormalForce at(const ContactParams& p, double u, double& u_max) {
  const ContactBodies b = disc_disc_bodies(1.0, 1.0, 1.0, 1.0);
  ContactKinematics k;
  k.u_n = u;
  return NormalWaltonBraun::force(ContactInput{p, b, k}, {u_max});
}
double stored(const ContactParams& p, double u, double u_max) {
  const ContactBodies b = disc_disc_bodies(1.0, 1.0, 1.0, 1.0);
  ContactKinematics k;
  k.u_n = u;
  return NormalWaltonBraun::stored(ContactInput{p, b, k}, {u_max});
}

TEST(WaltonBraun, TheK2FollowsFromEOrIsGiven) {
  EXPECT_DOUBLE_EQ(wb_params().k_unload, kK2);
  ContactParams p;
  p.k_n = kK1, p.k_unload = 5e6;
  ContactParamTable t(1);
  t.pair(0, 0) = p, t.wall(0) = p;
  resolve_pair_constants(t, {Material{}});
  EXPECT_EQ(t.pair(0, 0).k_unload, 5e6);
}

TEST(WaltonBraun, ALoadingUnloadingReloadingCycleFollowsK1ThenK2ThenK1) {
  const ContactParams p = wb_params();
  const double U = 1e-5, u0 = U * (1.0 - kK1 / kK2);  // 0.75 U
  double u_max = 0.0, loss = 0.0, work = 0.0, u_prev = 0.0, F_prev = 0.0;
  auto expect = [&](double u, double F_exact, const char* leg) {
    const NormalForce f = at(p, u, u_max);
    if (F_exact == 0.0)
      EXPECT_EQ(f.F_n, 0.0) << leg << " at u = " << u;
    else
      EXPECT_NEAR(f.F_n, F_exact, 1e-12 * F_exact) << leg << " at u = " << u;
    loss += f.hysteresis;
    work += 0.5 * (F_prev + f.F_n) * (u - u_prev);  // the work done on the contact (exact: F is linear on a leg)
    u_prev = u, F_prev = f.F_n;
  };
  constexpr int kN = 200;
  for (int s = 1; s <= kN; ++s) expect(U * s / kN, kK1 * U * s / kN, "loading K1");
  EXPECT_EQ(u_max, U);
  for (int s = 1; s <= kN; ++s) {  // unloading to 50 %: K2, then no tension below u_0
    const double u = U * (1.0 - 0.5 * s / kN);
    // The legs cross u_0 at a sample (u_0 = 0.75 U), so the trapezoid stays exact.
    expect(u, std::max(0.0, kK2 * (u - u0)), "unloading K2");
  }
  for (int s = 1; s <= kN; ++s) expect(U * (0.5 - 0.3 * s / kN), 0.0, "unloaded to 20 %, no tension");
  EXPECT_EQ(u_max, U) << "the contact keeps its largest overlap at F_n = 0";
  for (int s = 1; s <= kN; ++s) {  // reloading to 120 %: K2 up to the loading line at U, then K1
    const double u = U * (0.2 + 1.0 * s / kN);
    const bool on_line = u >= U;
    expect(u, on_line ? kK1 * u : std::max(0.0, kK2 * (u - u0)), on_line ? "loading K1 beyond U" : "reloading K2");
  }
  EXPECT_EQ(u_max, 1.2 * U);
  // The work done on the contact is its stored energy plus the loss of the loading line, every leg exactly.
  const double loss_exact = 0.5 * kK1 * (1.0 - kK1 / kK2) * (1.2 * U) * (1.2 * U);
  EXPECT_NEAR(loss, loss_exact, 1e-12 * loss_exact);
  EXPECT_NEAR(work, stored(p, 1.2 * U, u_max) + loss, 1e-9 * work);
  EXPECT_NEAR(stored(p, 1.2 * U, u_max), std::pow(kK1 * 1.2 * U, 2) / (2.0 * kK2), 1e-12 * work);
}

struct Impact {
  double e = 0.0;         // rebound: -(v_n after)/(v_n before)
  double u_max = 0.0;     // the largest overlap
  double duration = 0.0;  // steps with F_n > 0, times dt
  double KE0 = 0.0, KE_end = 0.0;
  double D_hyst = 0.0;    // the ledger's D_n_hyst
  double W_n = 0.0;       // the normal force's work
  double residual = 0.0;  // |KE_end - KE0 - W_n|
};

// A head-on impact at the relative speed v (two D5 discs, or one on the bottom wall), the contact starting a
// fraction `phase` of a step after t = 0.
Impact impact(bool wall, double v, double dt, double phase = 0.37) {
  const ContactParams p = wb_params();
  const double R2 = wall ? INFINITY : kR;
  testing_rig::OneContactRig rig(kLaws, p, kR, R2, -phase * v * dt, 0.0);
  DiscStore& d = rig.discs();
  if (wall) {
    d.velocity[0] = v * rig.n;  // n points from the disc to the wall
  } else {
    d.velocity[0] = 0.5 * v * rig.n, d.velocity[1] = -0.5 * v * rig.n;
  }
  auto ke = [&] {
    double e = 0.0;
    for (std::size_t i = 0; i < d.size(); ++i) e += 0.5 * d.mass[i] * dot(d.velocity[i], d.velocity[i]);
    return e;
  };
  rig.start(dt);
  Impact out;
  out.KE0 = ke();
  const double v_in = rig.normal_velocity();  // < 0: approaching
  bool touched = false;
  for (int s = 0; s < 1000000; ++s) {
    LedgerStep L;
    rig.step(&L);
    out.D_hyst += L.D_n_hyst, out.W_n += L.W_n;
    out.u_max = std::max(out.u_max, rig.overlap());
    const double F_n = rig.row_table().F_n[0];
    if (F_n > 0.0) touched = true, out.duration += dt;
    if (touched && rig.overlap() < 0.0 && rig.normal_velocity() > 0.0) break;
  }
  out.e = -rig.normal_velocity() / v_in;
  out.KE_end = ke();
  out.residual = std::fabs(out.KE_end - out.KE0 - out.W_n);
  return out;
}

double m_eff(bool wall) { return wall ? test::d5::mass() : 0.5 * test::d5::mass(); }
double t_c(bool wall) { return std::numbers::pi * std::sqrt(m_eff(wall) / kK1); }

TEST(WaltonBraun, AHeadOnImpactReboundsWithEAndItsErrorFallsAsDtSquared) {
  for (const bool wall : {false, true}) {
    const double v = 0.2, dt = t_c(wall) / 50.0;
    const Impact a = impact(wall, v, dt);
    EXPECT_NEAR(a.e, kE, 5e-3) << "wall " << wall;
    EXPECT_NEAR(a.u_max, v * std::sqrt(m_eff(wall) / kK1), 1e-2 * a.u_max) << "wall " << wall;
    // The order: the worst error over 16 onset phases at dt/2 to dt/16, the slope of its logarithm fitted by least
    // squares (the kinks at the onset and at u_max fall anywhere in a step, so one phase is noisy; from t_c/100 on
    // the worst error falls by 4.0 per halving, while t_c/50 happens to lie below that line).
    auto worst_at = [&](double h) {
      double w = 0.0;
      for (int k = 0; k < 16; ++k) w = std::max(w, std::fabs(impact(wall, v, h, (k + 0.5) / 16.0).e - kE));
      return w;
    };
    const double at_dt = worst_at(dt);
    std::vector<double> worst;
    for (const double h : {dt / 2, dt / 4, dt / 8, dt / 16}) worst.push_back(worst_at(h));
    double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
    for (int k = 0; k < 4; ++k) {
      const double x = -k, y = std::log2(worst[static_cast<std::size_t>(k)]);  // x = log2(h/(dt/2))
      sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    const double order = (4.0 * sxy - sx * sy) / (4.0 * sxx - sx * sx);
    std::printf(
        "[ wb       ] wall %d: worst |e - 0.5| at t_c/50 %.3e; /100 %.3e, /200 %.3e, /400 %.3e, /800 %.3e: "
        "order %.2f\n",
        wall, at_dt, worst[0], worst[1], worst[2], worst[3], order);
    EXPECT_LT(at_dt, 5e-3) << "wall " << wall;
    EXPECT_GE(order, 1.9) << "wall " << wall;
  }
}

TEST(WaltonBraun, TheImpactDissipatesOneMinusESquaredAndTheLedgerCloses) {
  for (const bool wall : {false, true}) {
    const Impact a = impact(wall, 0.2, t_c(wall) / 200.0);
    const double lost = (1.0 - kE * kE) * a.KE0;
    EXPECT_NEAR(a.D_hyst, lost, 2e-3 * lost) << "wall " << wall;
    EXPECT_NEAR(a.KE0 - a.KE_end, lost, 2e-3 * lost) << "wall " << wall;
    // Apart, the contact stores nothing: its work is its loss, to the integration error.
    EXPECT_NEAR(-a.W_n, a.D_hyst, 1e-3 * lost) << "wall " << wall;
    EXPECT_LT(a.residual, 1e-3 * a.KE0) << "wall " << wall;
  }
}

TEST(WaltonBraun, WithoutADashpotTheDurationAndEDoNotDependOnTheSpeed) {
  for (const bool wall : {false, true}) {
    const double m = m_eff(wall), duration = 0.5 * std::numbers::pi * (std::sqrt(m / kK1) + std::sqrt(m / kK2));
    for (const double v : {0.01, 0.2, 5.0}) {
      const double dt = t_c(wall) / 2000.0;
      const Impact a = impact(wall, v, dt);
      EXPECT_NEAR(a.e, kE, 5e-4) << "v " << v << " wall " << wall;
      EXPECT_NEAR(a.duration, duration, 2.0 * dt) << "v " << v << " wall " << wall;
    }
  }
}

TEST(WaltonBraun, TheCriticalStepTakesTheNormalModeAtK2) {
  const ContactParams p = wb_params();
  const ContactBody disc{test::d5::mass(), test::d5::inertia(), kR};
  std::string mode;
  const double dt = contact_critical_step(kLaws, p, disc, disc, &mode);
  EXPECT_EQ(mode, "normal");
  EXPECT_DOUBLE_EQ(dt, 2.0 / std::sqrt(kK2 / (0.5 * test::d5::mass())));
}

std::string wb_ini(const std::string& block) {
  return "[run]\nsteps = 1\n[domain]\nxlo = 0\nxhi = 0.1\nylo = 0\nyhi = 0.1\n[material]\ndensity = 2650\n"
         "[contact]\nnormal = walton_braun\ntangential = none\n[walton_braun]\n" +
         block + "[scene]\ntype = lattice_square\nnx = 2\nny = 1\nradius = 0.005\nx0 = 0.01\ny0 = 0.01\n";
}

std::string refusal(const std::string& block) {
  try {
    ContactParamTable t = parse_config_text(wb_ini(block)).params;
    resolve_pair_constants(t, {Material{}});
  } catch (const std::exception& ex) {
    return ex.what();
  }
  return "";
}

TEST(WaltonBraun, BadKeysAreRefusedNamingThem) {
  EXPECT_EQ(refusal("K1 = 1e6\ne = 0.5\n"), "");
  EXPECT_EQ(refusal("K1 = 1e6\nK2 = 4e6\n"), "");
  EXPECT_NE(refusal("K1 = 1e6\n").find("'walton_braun.e', 'walton_braun.K2': give one"), std::string::npos)
      << refusal("K1 = 1e6\n");
  EXPECT_NE(refusal("K1 = 1e6\ne = 0.5\nK2 = 4e6\n").find("give at most one"), std::string::npos);
  EXPECT_NE(refusal("K1 = 1e6\nK2 = 5e5\n").find("walton_braun.K2 = 500000"), std::string::npos)
      << refusal("K1 = 1e6\nK2 = 5e5\n");
  for (const std::string bad : {"e = 0\n", "e = 1.5\n", "e = nan\n", "e = inf\n", "K2 = -1\n", "K2 = inf\n"})
    EXPECT_NE(refusal("K1 = 1e6\n" + bad).find("walton_braun." + bad.substr(0, bad.find(' '))), std::string::npos)
        << bad << ": " << refusal("K1 = 1e6\n" + bad);
  for (const std::string bad : {"0", "-1", "nan", "inf"})
    EXPECT_NE(refusal("K1 = " + bad + "\ne = 0.5\n").find("walton_braun.K1"), std::string::npos) << bad;
  EXPECT_NE(refusal("e = 0.5\n").find("walton_braun.K1"), std::string::npos) << "K1 is required";
}

}  // namespace
}  // namespace rondel
