// Two-disc normal impact with the linear spring-dashpot without tension, docs/validation.md sections 4 and 6:
// two D5 discs, contact set J (k_n = 2e8 N/m, frictionless), head-on at v0 = 1 m/s relative. The expected
// values are the closed forms of docs/validation.md section 4, evaluated here:
//   m_eff = m/2, w0 = sqrt(k_n/m_eff), w_d = w0 sqrt(1 - zeta^2),
//   t_c = arccos(2 zeta^2 - 1)/w_d,  e = exp(-zeta arccos(2 zeta^2 - 1)/sqrt(1 - zeta^2)),
//   dissipated energy m_eff v0^2 (1 - e^2)/2.
// The onset of contact falls at an arbitrary point inside a step; the test shifts the initial gap by
// fractions of v0 dt to sample five onset phases and keeps the worst case.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "app/Simulation.hpp"
#include "support/Format.hpp"
#include "support/StandardObjects.hpp"
#include "support/TempDir.hpp"

namespace rondel {
namespace {

namespace fs = std::filesystem;

constexpr double kR = test::d5::R;  // D5
constexpr double kKn = test::kSetJ.k_n;
constexpr double kV0 = 1.0;  // relative approach speed [m/s]
const double kPhases[] = {0.1, 0.3, 0.5, 0.7, 0.9};

double disc_mass() { return test::d5::mass(); }
double m_eff() { return 0.5 * disc_mass(); }
double w0() { return std::sqrt(kKn / m_eff()); }
double exact_contact_time(double zeta) { return std::acos(2 * zeta * zeta - 1) / (w0() * std::sqrt(1 - zeta * zeta)); }
double exact_restitution(double zeta) {
  return std::exp(-zeta * std::acos(2 * zeta * zeta - 1) / std::sqrt(1 - zeta * zeta));
}
double exact_dissipation(double e) { return 0.5 * m_eff() * kV0 * kV0 * (1 - e * e); }

using test::num;

// A scratch directory for the scene file, removed when the test ends.
struct ScratchDir : test::TempDir {
  ScratchDir() : test::TempDir("rondel-test-impact") {}
};

struct ImpactResult {
  double dt = 0.0;
  double e = 0.0;          // (v2 - v1).n after / v0
  double t_contact = 0.0;  // steps with F_n > 0, times dt
  double KE0 = 0.0, KE_end = 0.0;
  double W_nt = 0.0;                              // W_n + W_t after separation
  double residual_end = 0.0, residual_max = 0.0;  // ledger |KE - KE0 - W|, at the end and its largest
  double lateral = 0.0;  // largest |v_y| and |omega| after the impact (must stay 0: a head-on impact)
  double zeta_n = 0.0;   // the damping ratio the run used (derived from linear.e when that is given)
};

// Runs one impact. `law` holds the normal-damping override ("--linear.zeta=0.3" or "--linear.e=0.5");
// dt is given explicitly; `phase` in (0, 1) places the onset of contact inside a step: the surfaces start
// (2 + phase) v0 dt apart.
ImpactResult run_impact(const std::string& law, double dt, double phase) {
  ScratchDir dir;
  const fs::path csv = dir.path() / "pair.csv";
  const double gap = (2.0 + phase) * kV0 * dt;
  {
    std::ofstream f(csv);
    f.precision(17);
    f << "id,x,y,radius,vx,vy,omega\n";
    f << "0," << -(kR + 0.5 * gap) << ",0," << kR << "," << 0.5 * kV0 << ",0,0\n";
    f << "1," << (kR + 0.5 * gap) << ",0," << kR << "," << -0.5 * kV0 << ",0,0\n";
  }
  const std::string ini = R"(
[domain]
xlo = -0.05
xhi = 0.05
ylo = -0.05
yhi = 0.05
[material]
density = 2650
[contact]
tangential = none
[linear]
k_n = 2e8
[scene]
type = csv
)";
  Communicator comm;
  // The checks read every disc from this rank's store: a one-rank run (the binary's normal launch).
  EXPECT_EQ(comm.size(), 1);
  Simulation sim(parse_config_text(ini, {"--scene.file=" + csv.string(), "--run.dt=" + num(dt), law}), comm,
                 /*write_files=*/false);
  ImpactResult r;
  r.dt = sim.dt();
  r.zeta_n = sim.config().params.pair(0, 0).zeta_n;
  r.KE0 = sim.kinetic_energy();
  const DiscStore& D = sim.discs();
  bool touched = false;
  int contact_steps = 0;
  for (int s = 0; s < 100000; ++s) {
    sim.step();
    double F = 0.0;
    for (double f : sim.pairs().F_n) F = std::max(F, f);
    if (F > 0.0) ++contact_steps, touched = true;
    r.residual_max = std::max(r.residual_max, sim.ledger().absolute_residual(sim.kinetic_energy()));
    const Vec2 d = D.position[1] - D.position[0];
    // Separated: the force is off and the surfaces are apart, so the velocities are final.
    if (touched && F == 0.0 && std::sqrt(dot(d, d)) > 2 * kR) break;
  }
  EXPECT_TRUE(touched);
  // Disc order in the store is not assumed: pick them by gid.
  const std::size_t i0 = D.gid[0] == 0 ? 0 : 1, i1 = 1 - i0;
  r.e = (D.velocity[i1].x - D.velocity[i0].x) / kV0;
  r.t_contact = contact_steps * r.dt;
  r.KE_end = sim.kinetic_energy();
  r.W_nt = sim.ledger().W_n + sim.ledger().W_t;
  r.residual_end = sim.ledger().absolute_residual(r.KE_end);
  for (std::size_t i = 0; i < 2; ++i)
    r.lateral = std::max({r.lateral, std::fabs(D.velocity[i].y), std::fabs(D.omega[i])});
  return r;
}

std::string zeta_key(double zeta) { return "--linear.zeta=" + num(zeta); }

TEST(Impact, ReferenceNumbersOfD5AndSetJ) {
  // One cross-check of the formula code against docs/validation.md's printed values.
  EXPECT_NEAR(disc_mass(), 0.20813051, 1e-8);
  EXPECT_NEAR(exact_contact_time(0.0), 7.166181e-5, 1e-11);
  EXPECT_NEAR(exact_contact_time(0.0), std::numbers::pi / w0(), 1e-20);
  EXPECT_EQ(exact_restitution(0.0), 1.0);
}

TEST(Impact, UndampedIsElasticAtFortyStepsPerContact) {
  const double dt = exact_contact_time(0.0) / 40.0;
  double worst = 0.0, worst_half = 0.0;
  for (double phase : kPhases) {
    const ImpactResult r = run_impact(zeta_key(0.0), dt, phase);
    worst = std::max(worst, std::fabs(1.0 - r.e));
    EXPECT_LE(std::fabs(1.0 - r.e), 5e-5) << "phase " << phase << ": e = " << r.e;
    EXPECT_EQ(r.lateral, 0.0);
    EXPECT_LE(std::fabs(r.t_contact - exact_contact_time(0.0)), 2.0 * dt) << "phase " << phase;
    worst_half = std::max(worst_half, std::fabs(1.0 - run_impact(zeta_key(0.0), 0.5 * dt, phase).e));
  }
  // Without a dashpot there is no force jump at onset. The error is second order in general, but with t_c/dt an
  // integer (40 and 80 here) the errors of entry and exit cancel and it is third order (docs/validation.md
  // sections 4 and 7): halving the step divides it by about 8.
  EXPECT_GT(worst / worst_half, 6.0) << worst << " at t_c/40, " << worst_half << " at t_c/80";
  std::printf("  zeta 0: worst |1 - e| = %.3e at t_c/40, %.3e at t_c/80\n", worst, worst_half);
}

TEST(Impact, DampedRestitutionAndContactTimeMatchNoTensionFormula) {
  for (double zeta : {0.1, 0.3, 0.5, 0.7}) {
    const double t_c = exact_contact_time(zeta), e_exact = exact_restitution(zeta);
    const double dt = t_c / 100.0;
    double worst_e = 0.0, worst_t = 0.0;
    for (double phase : kPhases) {
      const ImpactResult r = run_impact(zeta_key(zeta), dt, phase);
      worst_e = std::max(worst_e, std::fabs(r.e - e_exact));
      worst_t = std::max(worst_t, std::fabs(r.t_contact - t_c) / dt);
      EXPECT_LE(std::fabs(r.e - e_exact), 1e-2)
          << "zeta " << zeta << " phase " << phase << ": e " << r.e << " vs " << e_exact;
      // The force is sampled once per step, so the counted duration is t_c within one step at each end.
      EXPECT_LE(std::fabs(r.t_contact - t_c), 2.0 * dt)
          << "zeta " << zeta << " phase " << phase << ": contact " << r.t_contact << " s vs " << t_c << " s";
    }
    std::printf("  zeta %.1f, dt = t_c/100: e_exact %.6f, worst |e - e_exact| = %.3e, worst |t - t_c| = %.2f dt\n",
                zeta, e_exact, worst_e, worst_t);
  }
}

// The dissipated energy three ways. After separation the kinetic energy lost equals
// m_eff v0^2 (1 - e^2)/2 with the measured e (momentum is conserved, so this is exact up to rounding), and the
// ledger's -(W_n + W_t) equals it too: with the trapezoid of the step's forces and the half-step velocities,
// KE - KE0 - W differs from zero by dt^2 (F_end^2 - F_start^2)/(8 m_eff) summed over the run, which vanishes
// once the force is off again. Against the exact e the dissipation converges at first order (the dashpot force
// jumps by c_n v0 at onset): at t_c/100 it is off by up to ~7e-3 (zeta = 0.1, consistent with the 1e-2 allowed
// on e), so the 1e-3 of docs/validation.md section 6 is checked at t_c/1000 (observed worst 7.2e-4 over the phases).
TEST(Impact, DissipatedEnergyFromKineticEnergyAndLedger) {
  for (double zeta : {0.1, 0.3, 0.5, 0.7}) {
    const double t_c = exact_contact_time(zeta);
    for (double phase : kPhases) {
      const ImpactResult r = run_impact(zeta_key(zeta), t_c / 100.0, phase);
      const double lost = r.KE0 - r.KE_end;
      EXPECT_NEAR(r.KE0, 0.5 * m_eff() * kV0 * kV0, 1e-14);  // both discs at v0/2: all of it relative motion
      EXPECT_NEAR(lost, exact_dissipation(r.e), 1e-9 * lost) << "zeta " << zeta << " phase " << phase;
      EXPECT_NEAR(-r.W_nt, lost, 1e-11 * r.KE0) << "zeta " << zeta << " phase " << phase;
    }
    const double expected = exact_dissipation(exact_restitution(zeta));
    double worst = 0.0;
    for (double phase : kPhases) {
      const ImpactResult r = run_impact(zeta_key(zeta), t_c / 1000.0, phase);
      const double lost = r.KE0 - r.KE_end;
      worst = std::max(worst, std::fabs(lost - expected) / expected);
      EXPECT_NEAR(lost, expected, 1e-3 * expected) << "kinetic energy lost, zeta " << zeta << " phase " << phase;
      EXPECT_NEAR(-r.W_nt, expected, 1e-3 * expected) << "ledger, zeta " << zeta << " phase " << phase;
    }
    std::printf("  zeta %.1f, dt = t_c/1000: dissipation %.6e J, worst relative error %.3e\n", zeta, expected, worst);
  }
}

// The ledger residual |KE - KE0 - W_n - W_t| during the contact is the O(dt^2) term above (largest at the
// peak force, about KE0 (w0 dt)^2/4); it must stay below 1e-3 of KE0 at t_c/100 (docs/validation.md section 6),
// fall as the step is halved (by 4 for a second-order term), and return to rounding after separation.
TEST(Impact, LedgerResidualIsSmallAndFallsWithTheStep) {
  for (double zeta : {0.0, 0.1, 0.3, 0.5, 0.7}) {
    const double dt = exact_contact_time(zeta) / 100.0;
    double worst[2] = {0.0, 0.0};
    for (int k = 0; k < 2; ++k)
      for (double phase : kPhases) {
        const ImpactResult r = run_impact(zeta_key(zeta), k == 0 ? dt : 0.5 * dt, phase);
        worst[k] = std::max(worst[k], r.residual_max / r.KE0);
        EXPECT_LE(r.residual_end, 1e-11 * r.KE0) << "zeta " << zeta << " phase " << phase;
      }
    EXPECT_LE(worst[0], 1e-3) << "zeta " << zeta;
    EXPECT_GT(worst[0] / worst[1], 3.0) << "zeta " << zeta << ": " << worst[0] << " at dt, " << worst[1] << " at dt/2";
    EXPECT_LT(worst[0] / worst[1], 5.0) << "zeta " << zeta;
    std::printf("  zeta %.1f: largest ledger residual / KE0 %.3e at t_c/100, %.3e at t_c/200\n", zeta, worst[0],
                worst[1]);
  }
}

// `linear.e` sets the damping through the inverse of the restitution formula; the run must give that e back.
TEST(Impact, RestitutionInputIsRecovered) {
  const double e_in = 0.5;
  const double t_c0 = exact_contact_time(0.0);
  double worst_coarse = 0.0, worst_fine = 0.0;
  for (double phase : kPhases) {
    const ImpactResult coarse = run_impact("--linear.e=0.5", t_c0 / 100.0, phase);
    const ImpactResult fine = run_impact("--linear.e=0.5", t_c0 / 1000.0, phase);
    // The derived damping ratio, checked against the formula written in this test.
    EXPECT_NEAR(exact_restitution(coarse.zeta_n), e_in, 1e-9);
    EXPECT_GT(coarse.zeta_n, 0.1);
    worst_coarse = std::max(worst_coarse, std::fabs(coarse.e - e_in));
    worst_fine = std::max(worst_fine, std::fabs(fine.e - e_in));
    EXPECT_LE(std::fabs(coarse.e - e_in), 1e-2) << "phase " << phase << ": e " << coarse.e;
    // First order in dt: ten times finer, ten times closer.
    EXPECT_LE(std::fabs(fine.e - e_in), 1e-3) << "phase " << phase << ": e " << fine.e;
  }
  std::printf("  linear.e = 0.5: worst |e - 0.5| = %.3e at t_c0/100, %.3e at t_c0/1000\n", worst_coarse, worst_fine);
}

}  // namespace
}  // namespace rondel
