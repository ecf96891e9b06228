// Frequencies of one contact (docs/validation.md section 5; docs/physics.md section 4), from the formulas and
// measured on a small simulation that uses the library's kinematics, laws, kernel, force assembly and
// integrator (OneContactRig.hpp), compared with velocity Verlet's discrete frequency (2/dt) asin(w dt/2):
//  - the rolling mode of a D5 disc resting on a wall (slip spring k_s and rolling spring K in series):
//    m I w^4 - [k_s (I + m a^2) + m K] w^2 + k_s K = 0, set S, K = 0.75 and 7.5 (307.288 and 897.932 rad/s);
//  - the tangential mode alone: w_t/w_n = sqrt(3 k_s/k_n) (1.5 for set J);
//  - the Jiang rolling mode with the centres fixed, same density:
//    W/w_n = delta sqrt(2(1 + rho^4)/(3(1 + rho)^2 (1 + rho^2))) (0.408 delta equal discs, 0.816 delta wall).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "OneContactRig.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/CriticalTimeStep.hpp"
#include "physics/LawRegistry.hpp"
#include "physics/LawTypes.hpp"
#include "physics/RollingJiangPlastic.hpp"
#include "support/StandardObjects.hpp"

namespace rondel {
namespace {

using testing_rig::frequency_from_zero_crossings;
using testing_rig::OneContactRig;
using testing_rig::verlet_frequency;

// Disc D5 and contact sets S and J (docs/validation.md section 0).
constexpr double kR = test::d5::R, kDensity = test::d5::density, kG = test::d5::g;
const double kMass = test::d5::mass();
const double kInertia = test::d5::inertia();
using test::set_J;
using test::set_S;

LawSelection laws_with(const std::string& t, const std::string& r) {
  LawSelection laws;
  laws.tangential = t;
  laws.rolling = r;
  return laws;
}

// --- the rolling mode of a disc on a wall --------------------------------------------------------------

// The lower root of m I w^4 - [k_s (I + m a^2) + m K] w^2 + k_s K = 0.
double rolling_mode_formula(double m, double I, double a, double k_s, double K) {
  const double A = m * I, B = k_s * (I + m * a * a) + m * K, C = k_s * K;
  const double w2 = (B - std::sqrt(B * B - 4.0 * A * C)) / (2.0 * A);
  return std::sqrt(w2);
}

// The (tangential displacement, rotation) problem of a disc on a wall: K = [[k_s, k_s a], [k_s a, k_s a^2 + K]],
// M = diag(m, I). Eigenvalues ascending, eigenvectors M-normalised.
Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> wall_rolling_problem(double m, double I, double a, double k_s,
                                                                               double K) {
  Eigen::Matrix2d Ks, Ms;
  Ks << k_s, k_s * a, k_s * a, k_s * a * a + K;
  Ms << m, 0.0, 0.0, I;
  return Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d>(Ks, Ms);
}

TEST(Frequencies, RollingModeFormulaGivesTheValidationNumbers) {
  const ContactParams p = set_S();
  const double u0 = kMass * kG / p.k_n;  // static wall overlap
  const double a = kR - 0.5 * u0;
  EXPECT_NEAR(u0, 2.0417603e-6, 1e-12);
  EXPECT_NEAR(a, 4.9989791e-3, 1e-10);
  const struct { double K, expected; } cases[] = {{0.75, 307.288}, {7.5, 897.932}};
  for (const auto& c : cases) {
    const double w = rolling_mode_formula(kMass, kInertia, a, p.k_s, c.K);
    EXPECT_NEAR(w / c.expected, 1.0, 1e-3) << "K = " << c.K;
    // The same root from the 2x2 generalised eigenproblem.
    const auto solver = wall_rolling_problem(kMass, kInertia, a, p.k_s, c.K);
    EXPECT_NEAR(std::sqrt(solver.eigenvalues()(0)), w, 1e-9 * w) << "K = " << c.K;
    // sqrt(K/I_c), I_c = I + m a^2 (rolling about the contact point), is not good enough.
    const double w_rigid = std::sqrt(c.K / (kInertia + kMass * a * a));
    EXPECT_GT(std::fabs(w_rigid / w - 1.0), 1e-3) << "K = " << c.K;
    std::printf("[rolling mode on a wall] K = %g: w_low = %.6f rad/s (VALIDATION %.3f), sqrt(K/I_c) = %.3f\n", c.K, w,
                c.expected, w_rigid);
  }
}

struct RollingCase {
  std::string law;
  double K;       // the rolling spring [N m/rad]
  double safety;  // dt / the code's critical step
};

class RollingModeOnWall : public ::testing::TestWithParam<RollingCase> {};

TEST_P(RollingModeOnWall, MeasuredFrequencyIsVerletsDiscreteFrequency) {
  const RollingCase c = GetParam();
  ContactParams p = set_S();
  const double u0 = kMass * kG / p.k_n;
  const double a = kR - 0.5 * u0;
  // The same K from either law: jiang K_m = k_n (delta 2R)^2/12; wang K = k_r R^2. Caps far above the motion.
  if (c.law == "jiang_plastic") {
    p.delta = std::sqrt(12.0 * c.K / p.k_n) / (2.0 * kR);
    const ContactKinematics k = disc_wall_kinematics({0.0, -1.0}, kR - u0, kR, {}, {}, 0.0);
    EXPECT_NEAR(jiang_geometry(ContactInput{p, disc_wall_bodies(kMass, kInertia), k}).K_m, c.K, 1e-12 * c.K);
  } else {
    p.k_r = c.K / (kR * kR);
    p.mu_r = 1.0;
  }
  const LawSelection laws = laws_with("coulomb", c.law);
  const ContactBody wall{INFINITY, INFINITY, INFINITY};
  const double dt = c.safety * contact_critical_step(laws, p, ContactBody{kMass, kInertia, kR}, wall);

  const double w = rolling_mode_formula(kMass, kInertia, a, p.k_s, c.K);
  // A pure spin would put two thirds of omega's amplitude into the fast (tangential) mode; start instead in
  // the slow mode's shape (v_t, omega) from the same 2x2 problem (it sets the amplitudes, not the frequency).
  const auto solver = wall_rolling_problem(kMass, kInertia, a, p.k_s, c.K);
  const Eigen::Vector2d shape = solver.eigenvectors().col(0) / solver.eigenvectors()(1, 0);
  const double omega0 = 1e-3;  // rad/s: rotation amplitude ~3e-6 rad, couple ~1e-3 of the cap

  OneContactRig rig(laws, p, kR, INFINITY, u0, 0.0, {0.0, -kG});
  DiscStore& D = rig.discs();
  D.velocity[0] = (shape(0) * omega0) * rig.t;
  D.omega[0] = omega0;
  rig.start(dt);
  const double periods = 40.0;
  const auto steps = static_cast<int>(periods * 2.0 * M_PI / w / dt);
  std::vector<double> omega{D.omega[0]};
  double worst_cap_use = 0.0;
  const double cap = c.law == "jiang_plastic" ? kMass * kG * p.delta * 2.0 * kR / 6.0 : p.mu_r * kMass * kG * kR;
  for (int s = 0; s < steps; ++s) {
    rig.step();
    omega.push_back(D.omega[0]);
    const ContactTable& row = rig.row_table();
    worst_cap_use = std::max({worst_cap_use, std::fabs(row.M1[0]) / cap, std::fabs(row.F_t[0]) / (p.mu * row.F_n[0])});
  }
  const double measured = frequency_from_zero_crossings(omega, dt);
  const double discrete = verlet_frequency(w, dt);
  std::printf(
      "[rolling mode on a wall, %s, K = %g, dt = %.2f x critical = %.4g s] measured %.6f rad/s, "
      "discrete (2/dt)asin(w dt/2) %.6f, exact %.6f; measured/discrete - 1 = %.2e, measured/exact - 1 = %.2e\n",
      c.law.c_str(), c.K, c.safety, dt, measured, discrete, w, measured / discrete - 1.0, measured / w - 1.0);
  EXPECT_LT(worst_cap_use, 0.01) << "the springs must stay elastic";
  EXPECT_NEAR(measured / discrete, 1.0, 1e-5);
  EXPECT_NEAR(measured / w, 1.0, 1e-3 + (discrete / w - 1.0));
  if (c.safety > 0.5) {
    // At a large step the discrete correction (about (w dt)^2/24) is visible and the measurement follows it.
    EXPECT_GT(discrete / w - 1.0, 1e-4);
    EXPECT_LT(std::fabs(measured - discrete), 0.1 * std::fabs(discrete - w));
  }
}

std::string rolling_case_name(const ::testing::TestParamInfo<RollingCase>& info) {
  std::string s =
      info.param.law + (info.param.K < 1.0 ? "_K0p75" : "_K7p5") + (info.param.safety < 0.5 ? "_dt0p2" : "_dt0p9");
  return s;
}

INSTANTIATE_TEST_SUITE_P(SetS, RollingModeOnWall,
                         ::testing::Values(RollingCase{"jiang_plastic", 0.75, 0.2},
                                           RollingCase{"jiang_plastic", 0.75, 0.9},
                                           RollingCase{"jiang_plastic", 7.5, 0.2},
                                           RollingCase{"jiang_plastic", 7.5, 0.9}, RollingCase{"wang", 0.75, 0.2},
                                           RollingCase{"wang", 7.5, 0.9}),
                         rolling_case_name);

// --- the tangential mode alone -------------------------------------------------------------------------

TEST(Frequencies, TangentialModeRatioInTheCodesEstimate) {
  const LawSelection laws = laws_with("coulomb", "none");
  for (const ContactParams& p : {set_S(), set_J()}) {
    const double expected = std::sqrt(3.0 * p.k_s / p.k_n);
    // A disc on a wall and two equal discs: w_t^2 = k_s/m_t with 1/m_t = sum 1/m + R^2/I = 3/m per disc.
    const ContactBody disc{kMass, kInertia, kR};
    for (const ContactBody& other : {ContactBody{INFINITY, INFINITY, INFINITY}, disc}) {
      const bool wall = std::isinf(other.m);
      const double m_eff = wall ? kMass : 0.5 * kMass;
      const double w_n = std::sqrt(p.k_n / m_eff);
      std::string mode;
      const double dt = contact_critical_step(laws, p, disc, other, &mode);
      EXPECT_EQ(mode, "tangential") << (wall ? "wall" : "pair");
      EXPECT_NEAR((2.0 / dt) / w_n, expected, 1e-12 * expected) << (wall ? "wall" : "pair");
    }
    if (p.k_n == 2e8) {
      EXPECT_NEAR(expected, 1.5, 1e-15);  // set J: the tangential mode, not the normal one, sets the step
    }
  }
}

TEST(Frequencies, TangentialAndNormalModesMeasuredOnAWall) {
  const ContactParams p = set_J();
  const LawSelection laws = laws_with("coulomb", "none");
  const double u0 = kMass * kG / p.k_n;
  const double a = kR - 0.5 * u0;
  const double w_n = std::sqrt(p.k_n / kMass);
  const double w_t = std::sqrt(p.k_s * (1.0 / kMass + a * a / kInertia));  // 1/m_t with the lever a
  const double dt =
      0.1 * contact_critical_step(laws, p, ContactBody{kMass, kInertia, kR}, ContactBody{INFINITY, INFINITY, INFINITY});
  OneContactRig rig(laws, p, kR, INFINITY, u0, 0.0, {0.0, -kG});
  DiscStore& D = rig.discs();
  // Pure sliding (no spin) and a small normal velocity: V_s is the tangential mode alone (rolling freely
  // without a rolling spring is a zero-frequency mode that V_s does not see); v_n is the normal mode.
  D.velocity[0] = 1e-5 * rig.t + 1e-5 * rig.n;
  rig.start(dt);
  std::vector<double> V_s{rig.sliding_velocity()}, v_n{rig.normal_velocity()};
  const auto steps = static_cast<int>(30.0 * 2.0 * M_PI / w_n / dt);
  for (int s = 0; s < steps; ++s) {
    rig.step();
    V_s.push_back(rig.sliding_velocity());
    v_n.push_back(rig.normal_velocity());
  }
  const double mt = frequency_from_zero_crossings(V_s, dt), mn = frequency_from_zero_crossings(v_n, dt);
  std::printf(
      "[set J wall, dt = %.4g s] tangential: measured %.3f, discrete %.3f; normal: measured %.3f, discrete "
      "%.3f; measured w_t/w_n = %.6f (Verlet's map undone: %.6f), sqrt(3 k_s/k_n) = %.6f\n",
      dt, mt, verlet_frequency(w_t, dt), mn, verlet_frequency(w_n, dt), mt / mn,
      std::sin(0.5 * mt * dt) / std::sin(0.5 * mn * dt), std::sqrt(3.0 * p.k_s / p.k_n));
  EXPECT_NEAR(mt / verlet_frequency(w_t, dt), 1.0, 1e-5);
  EXPECT_NEAR(mn / verlet_frequency(w_n, dt), 1.0, 1e-5);
  // Undo Verlet's map w -> (2/dt) asin(w dt/2) before taking the ratio (the two corrections differ by ~1e-3).
  auto continuous = [dt](double w_verlet) { return (2.0 / dt) * std::sin(0.5 * w_verlet * dt); };
  const double ratio = continuous(mt) / continuous(mn);
  EXPECT_NEAR(ratio / std::sqrt(3.0 * p.k_s / p.k_n), 1.0, 1e-5) << "w_t/w_n = " << ratio;
}

// --- the Jiang rolling mode with the centres fixed -----------------------------------------------------

double jiang_ratio_formula(double rho, double delta) {
  if (std::isinf(rho)) return delta * std::sqrt(2.0 / 3.0);  // the limit rho -> inf (a wall)
  const double r4 = rho * rho * rho * rho;
  return delta * std::sqrt(2.0 * (1.0 + r4) / (3.0 * (1.0 + rho) * (1.0 + rho) * (1.0 + rho * rho)));
}

TEST(Frequencies, JiangRollingModeCentresFixedFormula) {
  EXPECT_NEAR(jiang_ratio_formula(1.0, 1.0), 0.408, 5e-4);
  EXPECT_NEAR(jiang_ratio_formula(INFINITY, 1.0), 0.816, 5e-4);
  EXPECT_NEAR(jiang_ratio_formula(1e6, 1.0), jiang_ratio_formula(INFINITY, 1.0), 1e-5);
}

class JiangRollingMode : public ::testing::TestWithParam<std::tuple<double, double>> {};

TEST_P(JiangRollingMode, LibraryStiffnessCodeEstimateAndMeasuredFrequency) {
  const auto [rho, delta] = GetParam();  // rho = inf: a wall
  const bool wall = std::isinf(rho);
  ContactParams p = set_S();
  p.delta = delta;
  const LawSelection laws = laws_with("none", "jiang_plastic");
  const double u0 = 1e-4 * kR;
  OneContactRig rig(laws, p, kR, wall ? INFINITY : rho * kR, u0, p.k_n * u0);
  DiscStore& D = rig.discs();

  // W from the library's Jiang geometry on the rig's own contact.
  const ContactBodies bodies = wall ? disc_wall_bodies(D.mass[0], D.inertia[0])
                                    : disc_disc_bodies(D.mass[0], D.mass[1], D.inertia[0], D.inertia[1]);
  const ContactKinematics k =
      wall ? disc_wall_kinematics(rig.n, kR - u0, kR, {}, {}, 0.0)
           : disc_disc_kinematics(D.position[1] - D.position[0], kR * (1.0 + rho) - u0, kR, rho * kR, {}, {}, 0.0, 0.0);
  const double K_m = jiang_geometry(ContactInput{p, bodies, k}).K_m;
  const double I_red = wall ? D.inertia[0] : D.inertia[0] * D.inertia[1] / (D.inertia[0] + D.inertia[1]);
  const double W = std::sqrt(K_m / I_red), w_n = std::sqrt(p.k_n / bodies.m_eff);
  EXPECT_NEAR(W / w_n, jiang_ratio_formula(rho, delta), 1e-12 * W / w_n);

  // The code's estimate without a tangential spring: the smaller of the normal and the rolling limits.
  std::string mode;
  const ContactBody A{D.mass[0], D.inertia[0], kR};
  const ContactBody B =
      wall ? ContactBody{INFINITY, INFINITY, INFINITY} : ContactBody{D.mass[1], D.inertia[1], rho * kR};
  const double dt_code = contact_critical_step(laws, p, A, B, &mode);
  EXPECT_NEAR(dt_code, std::min(2.0 / w_n, 2.0 / W), 1e-12 * dt_code);
  EXPECT_EQ(mode, W > w_n ? "rolling" : "normal");

  // Measured: spin disc 1 only. Without a tangential law the centres stay put (central forces only) and the
  // relative rotation rate oscillates at W (the common spin is a zero-frequency mode).
  const double dt = 0.5 * dt_code;
  D.omega[0] = 1e-4;
  rig.start(dt);
  std::vector<double> rate{rig.rotation_rate()};
  const auto steps = static_cast<int>(30.0 * 2.0 * M_PI / W / dt);
  for (int s = 0; s < steps; ++s) {
    rig.step();
    rate.push_back(rig.rotation_rate());
  }
  const double measured = frequency_from_zero_crossings(rate, dt);
  EXPECT_NEAR(measured / verlet_frequency(W, dt), 1.0, 1e-5)
      << "measured " << measured << ", W " << W << ", discrete " << verlet_frequency(W, dt);
  EXPECT_LT(std::fabs(D.position[0].x) + std::fabs(D.position[0].y - (wall ? kR - u0 : 0.0)), 1e-12)
      << "the centre moved";
}

INSTANTIATE_TEST_SUITE_P(RatiosAndDeltas, JiangRollingMode,
                         ::testing::Combine(::testing::Values(1.0, 2.0, 10.0, 100.0, INFINITY),
                                            ::testing::Values(0.3, 1.0, 3.0)));

}  // namespace
}  // namespace rondel
