// Objectivity of the rolling laws, docs/validation.md section 1:
//  K7: an isolated pair (rho = 2) kept in contact by equal and opposite central forces, in rigid spin
//      Omega = 5 rad/s for 1 s: the total angular momentum is conserved (1e-10 relative) for every law but
//      force_proportional, whose couples M_i = -mu_r F_n a_i sign(omega_i) brake the pair at
//      dL/dt = -mu_r F_n (a1 + a2).
//  K8: K2 (centres fixed, omega1 = omega2, unequal radii) evaluated with the legacy iwashita_oda measure gives
//      dU_r = (R1 - R2) omega T/2, not 0 (the W15 measure V_r gives 0); in rigid rotation (K3) it gives 0.
//
// K7 is run with a velocity-Verlet loop of its own, built on the library pieces (disc_disc_kinematics,
// NormalLinear, TangentialCoulomb, the Rolling* moment functions), not with Simulation: the case needs two
// external central forces that hold the pair together (the contact has no tension and Simulation has no
// external forces besides gravity, which is uniform and cannot pull two discs towards each other), and it
// lets the test record F_n, a1, a2 and the couples of every step. The loop is the integrator of docs/design.md
// section 4: half kick, drift, forces from the new positions and the half-step velocities (which also
// increment the springs), half kick; the forces at t = 0 are those of the initial state with a zero
// increment (as Simulation does). Forces and torques follow docs/physics.md section 1: F_t on disc 1 along t,
// -F_n n on 1, torques a1 F_t + M1 on 1 and a2 F_t + M2 on 2.
//
// Why conservation is exact in this scheme: with f the force on 1 and -f on 2, sum x_i x f_i + tau_i =
// -(d x f) + (a1 + a2) F_t + M1 + M2 = M1 + M2 (d x (F_t t) = |d| F_t, a1 + a2 = |d|), and central forces
// contribute nothing. Velocity Verlet changes L by dt/2 of that sum at the old and at the new positions, so
// L_{n+1} - L_n = dt/2 [(M1 + M2)_n + (M1 + M2)_{n+1}] to rounding: zero for the objective laws (M2 = -M1),
// and the trapezoid of -mu_r F_n (a1 + a2) for force_proportional while both spins stay positive.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "core/ContactParams.hpp"
#include "core/Vec2.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawTypes.hpp"
#include "physics/NormalLinear.hpp"
#include "physics/RollingAlonsoMarroquin.hpp"
#include "physics/RollingConstantTorque.hpp"
#include "physics/RollingDisplacementDamping.hpp"
#include "physics/RollingForceProportional.hpp"
#include "physics/RollingIwashitaOda.hpp"
#include "physics/RollingJiangBrittle.hpp"
#include "physics/RollingJiangPlastic.hpp"
#include "physics/RollingNone.hpp"
#include "physics/RollingWang.hpp"
#include "physics/TangentialLaws.hpp"

namespace rondel {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDensity = 2650.0;
constexpr double kR1 = 0.01;

double disc_mass(double R) { return kDensity * kPi * R * R; }
double disc_inertia(double R) { return 0.5 * disc_mass(R) * R * R; }
Vec2 rotate(Vec2 a, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * a.x - s * a.y, s * a.x + c * a.y};
}

// ---------------------------------------------------------------------------------------------------------
// K7

// Parameters for every law at once (each law reads its own fields). k_n = 1e4 N/m with an overlap of 1e-5 m
// gives F_n = 0.1 N: force_proportional's braking mu_r F_n (a1 + a2) = 3e-4 N m then takes about 5 % of L in
// 1 s and both spins stay positive. The dashpots are on, so that velocities enter every couple.
ContactParams k7_params() {
  ContactParams p;
  p.k_n = 1e4;
  p.zeta_n = 0.2;
  p.k_s = 0.75e4;
  p.zeta_t = 0.2;
  p.mu = 0.5;
  p.delta = 0.3;  // jiang_*: B = 4e-3 m, K_m = 1.3e-2 N m/rad, M0 = 6.7e-5 N m
  p.k_r = 300.0;  // wang, alonso_marroquin: k_r R*^2 = 1.3e-2 N m/rad
  p.c_r = 2.0;
  p.mu_r = 0.1;    // wang, alonso_marroquin, force_proportional; constant_torque, displacement_damping
  p.K_r = 1.3e-2;  // iwashita_oda
  p.C_r = 1e-4;
  p.eta = 6.7e-4;
  p.f_lim = 0.08;  // constant_torque's limiter on (its default)
  p.theta_rmax = 0.035;
  p.nu = 0.3;  // displacement_damping viscous part on
  p.f_visc = 0.5;
  return p;
}

struct PairState {
  Vec2 x[2], v[2];
  double w[2] = {0.0, 0.0};
  double theta[2] = {0.0, 0.0};
};

struct K7Result {
  double L0 = 0.0;
  double max_dev = 0.0;  // max_n |L_n - L_0 - expected_n|
  double L_end = 0.0;
  double expected_end = 0.0;  // L_0 + the trapezoid of -mu_r F_n (a1 + a2) (force_proportional), else L_0
  double max_M = 0.0;         // max |M1| + |M2| over the run (the laws did act)
  double max_Vr = 0.0, max_Vs = 0.0;
  double min_w = INFINITY;  // smallest spin seen
  double min_Fn = INFINITY, max_Fn = 0.0;
  double max_P = 0.0;  // |total linear momentum| at the end
  bool in_contact = true;
};

double angular_momentum(const PairState& s, const double m[2], const double I[2]) {
  double L = 0.0;
  for (int i = 0; i < 2; ++i) L += I[i] * s.w[i] + m[i] * cross(s.x[i], s.v[i]);
  return L;
}

// Rigid spin Omega of the pair about its centre of mass (at the origin) with overlap u_n0; `dw1`, `dw2` are
// spins added on top (a perturbation that makes the rolling springs, caps and dashpots act).
template <class Rolling>
K7Result run_k7(double Omega, double dw1, double dw2, double T, double dt) {
  const ContactParams p = k7_params();
  const double rho = 2.0, u_n0 = 1e-5;
  const double R[2] = {kR1, rho * kR1};
  const double m[2] = {disc_mass(R[0]), disc_mass(R[1])};
  const double I[2] = {disc_inertia(R[0]), disc_inertia(R[1])};
  const double d0 = R[0] + R[1] - u_n0;
  const double m_eff = m[0] * m[1] / (m[0] + m[1]);
  // The external pull on each disc towards the other: balances the contact spring and supplies the
  // centripetal force of the rigid spin, so the initial state is an equilibrium in the rotating frame.
  const double F_ext = p.k_n * u_n0 + m_eff * Omega * Omega * d0;

  PairState s;
  const Vec2 e = rotate({1.0, 0.0}, 0.7);  // line of centres at an arbitrary angle
  s.x[0] = -(m[1] / (m[0] + m[1]) * d0) * e;
  s.x[1] = (m[0] / (m[0] + m[1]) * d0) * e;
  for (int i = 0; i < 2; ++i) s.v[i] = Omega * perp(s.x[i]);
  s.w[0] = Omega + dw1;
  s.w[1] = Omega + dw2;

  // History of the one contact row (row 0): the tangential slot and up to two rolling slots.
  double t_slots[1][1] = {{0.0}}, r_slots[2][1] = {{0.0}, {0.0}};
  double* t_ptr[1] = {t_slots[0]};
  double* r_ptr[2] = {r_slots[0], r_slots[1]};

  const ContactBodies bodies = disc_disc_bodies(m[0], m[1], I[0], I[1]);
  Vec2 f[2];
  double tq[2];
  K7Result out;
  double brake = 0.0;  // -mu_r F_n (a1 + a2) of the latest force evaluation (force_proportional's formula)
  auto forces = [&](double h) {
    const Vec2 d = s.x[1] - s.x[0];
    const double dist = std::sqrt(dot(d, d));
    const ContactKinematics k = disc_disc_kinematics(d, dist, R[0], R[1], s.v[0], s.v[1], s.w[0], s.w[1]);
    if (k.u_n <= 0.0) out.in_contact = false;
    const double F_n = NormalLinear::force(p, bodies, k);
    const TangentialForce Ft = TangentialCoulomb::force(p, bodies, k, F_n, h, t_ptr, 0);
    const RollingCouple M = Rolling::moment(p, bodies, k, F_n, h, s.w[0], s.w[1], r_ptr, 0);
    f[0] = Ft.F_t * k.t - F_n * k.n + F_ext * k.n;  // the external pull on 1 is along +n (towards 2)
    f[1] = -f[0];
    tq[0] = k.a1 * Ft.F_t + M.M1;
    tq[1] = k.a2 * Ft.F_t + M.M2;
    brake = -p.mu_r * F_n * (k.a1 + k.a2);
    out.max_M = std::max(out.max_M, std::fabs(M.M1) + std::fabs(M.M2));
    out.max_Vr = std::max(out.max_Vr, std::fabs(k.V_r));
    out.max_Vs = std::max(out.max_Vs, std::fabs(k.V_s));
    out.min_Fn = std::min(out.min_Fn, F_n);
    out.max_Fn = std::max(out.max_Fn, F_n);
  };

  forces(0.0);  // t = 0: the initial state, zero spring increment
  out.L0 = angular_momentum(s, m, I);
  double expected = out.L0;
  const bool fp = std::string(Rolling::name) == "force_proportional";
  const auto steps = std::lround(T / dt);
  for (long n = 0; n < steps; ++n) {
    const double brake_old = brake;
    for (int i = 0; i < 2; ++i) {
      s.v[i] += (0.5 * dt / m[i]) * f[i];
      s.w[i] += 0.5 * dt * tq[i] / I[i];
      s.x[i] += dt * s.v[i];
      s.theta[i] += dt * s.w[i];
    }
    for (int i = 0; i < 2; ++i) out.min_w = std::min(out.min_w, s.w[i]);
    forces(dt);
    for (int i = 0; i < 2; ++i) {
      s.v[i] += (0.5 * dt / m[i]) * f[i];
      s.w[i] += 0.5 * dt * tq[i] / I[i];
    }
    if (fp) expected += 0.5 * dt * (brake_old + brake);
    out.max_dev = std::max(out.max_dev, std::fabs(angular_momentum(s, m, I) - expected));
  }
  out.L_end = angular_momentum(s, m, I);
  out.expected_end = expected;
  const Vec2 P = m[0] * s.v[0] + m[1] * s.v[1];
  out.max_P = std::sqrt(dot(P, P));
  return out;
}

template <class Rolling>
void check_k7(bool perturbed) {
  const std::string name = Rolling::name;
  SCOPED_TRACE(name + (perturbed ? " (rigid spin + relative spin)" : " (rigid spin)"));
  const double Omega = 5.0, T = 1.0, dt = 1e-4;
  // The perturbation: +2 rad/s on disc 1, -1 rad/s on disc 2 (both spins stay positive).
  const K7Result r = perturbed ? run_k7<Rolling>(Omega, 2.0, -1.0, T, dt) : run_k7<Rolling>(Omega, 0.0, 0.0, T, dt);
  std::printf(
      "K7 %-21s %-9s L0 %.9e  L_end %.12e  expected %.12e  max dev/L0 %.1e  max|M| %.2e  "
      "F_n [%.4f, %.4f]  min w %.3f\n",
      name.c_str(), perturbed ? "perturbed" : "rigid", r.L0, r.L_end, r.expected_end, r.max_dev / r.L0, r.max_M,
      r.min_Fn, r.max_Fn, r.min_w);
  EXPECT_TRUE(r.in_contact);
  EXPECT_GT(r.min_Fn, 0.0);
  EXPECT_LT(r.max_P, 1e-12 * r.L0 / kR1);  // the pair's momentum stays zero: only internal forces act
  // Conservation (objective laws) or the braking law (force_proportional), at every step, 1e-10 relative.
  EXPECT_LE(r.max_dev, 1e-10 * std::fabs(r.L0));
  if (name == "force_proportional") {
    // The braking is real: max_dev above checked it against the trapezoid of -mu_r F_n (a1 + a2) step by step;
    // here its size is bracketed by the extremes of F_n (which grows from 0.1 N as the slowing orbit needs
    // less of the constant external pull).
    EXPECT_GT(r.min_w, 0.0);  // both spins positive throughout: sign(omega_i) = 1
    const double mu_r = k7_params().mu_r, lever_sum = 3.0 * kR1;
    EXPECT_LE(r.L_end - r.L0, -mu_r * r.min_Fn * (lever_sum - 2e-5) * T);
    EXPECT_GE(r.L_end - r.L0, -mu_r * r.max_Fn * lever_sum * T);
    EXPECT_LT(r.L_end, 0.99 * r.L0);
  } else {
    EXPECT_NEAR(r.L_end, r.L0, 1e-10 * std::fabs(r.L0));
  }
  if (perturbed && name != "none") {
    EXPECT_GT(r.max_M, 0.0);  // the couple did act
  }
}

template <class... Laws>
void check_all_k7(bool perturbed) {
  (check_k7<Laws>(perturbed), ...);
}

TEST(RollingObjectivity, K7_RigidSpinConservesAngularMomentumExceptForceProportional) {
  check_all_k7<RollingNone, RollingJiangPlastic, RollingJiangBrittle, RollingWang, RollingAlonsoMarroquin,
               RollingIwashitaOda, RollingConstantTorque, RollingDisplacementDamping, RollingForceProportional>(false);
}

// The same with a relative spin on top of the rigid spin, so that every law's couple acts (springs load, caps
// are reached, constant_torque switches on, jiang_brittle breaks): M2 = -M1 keeps L exact regardless.
TEST(RollingObjectivity, K7_PerturbedSpinConservesAngularMomentumExceptForceProportional) {
  check_all_k7<RollingNone, RollingJiangPlastic, RollingJiangBrittle, RollingWang, RollingAlonsoMarroquin,
               RollingIwashitaOda, RollingConstantTorque, RollingDisplacementDamping, RollingForceProportional>(true);
}

// ---------------------------------------------------------------------------------------------------------
// K8

// A pair touching with overlap u_n along the direction `angle`, centres fixed, spins w1, w2; or, with
// Omega != 0, the same pair in rigid rotation about c at time t.
struct Pair {
  Vec2 x1, x2, v1, v2;
  double R1, R2, dist, w1, w2;
};
Pair fixed_pair(double R2, double u_n, double w) {
  Pair s;
  s.R1 = kR1;
  s.R2 = R2;
  s.dist = kR1 + R2 - u_n;
  const Vec2 n = rotate({1.0, 0.0}, 2.1);
  s.x1 = {-0.003, 0.004};
  s.x2 = s.x1 + s.dist * n;
  s.v1 = s.v2 = {0.0, 0.0};
  s.w1 = s.w2 = w;
  return s;
}
Pair rigid_pair(double R2, double u_n, double Omega, double t) {
  Pair s = fixed_pair(R2, u_n, Omega);
  const Vec2 c{0.031, -0.017};
  for (auto [x, v] : {std::pair{&s.x1, &s.v1}, std::pair{&s.x2, &s.v2}}) {
    *x = c + rotate(*x - c, Omega * t);
    *v = Omega * perp(*x - c);
  }
  return s;
}
ContactKinematics kinematics(const Pair& s) {
  return disc_disc_kinematics(s.x2 - s.x1, s.dist, s.R1, s.R2, s.v1, s.v2, s.w1, s.w2);
}

// K2 with unequal radii (centres fixed, omega1 = omega2 = 10 rad/s for 1e-3 s, overlap 1e-5 m), sampled at the
// midpoints of 10 steps: the iwashita_oda rolling displacement r' theta_r = (R1 - R2) omega T/2, where the
// objective W15 measure V_r T = R* (omega1 - omega2) T = 0.
TEST(IwashitaOdaMeasure, K8_EqualSpinsOfUnequalDiscsRollInTheLegacyMeasure) {
  const double w = 10.0, T = 1e-3, u_n = 1e-5;
  const int steps = 10;
  const double dt = T / steps;
  for (double rho : {1.0, 2.0, 10.0, 100.0}) {
    SCOPED_TRACE("rho = " + std::to_string(rho));
    const double R2 = rho * kR1, r_prime = 0.5 * (kR1 + R2);
    double theta_io = 0.0, U_w15 = 0.0, U_s = 0.0;
    for (int n = 0; n < steps; ++n) {
      const Pair s = fixed_pair(R2, u_n, w);
      const ContactKinematics k = kinematics(s);
      theta_io += iwashita_oda_rate(k, s.w1, s.w2) * dt;
      U_w15 += k.V_r * dt;
      U_s += k.V_s * dt;
    }
    const double expected = 0.5 * (kR1 - R2) * w * T;
    const double a_sum = kR1 + R2 - u_n;
    std::printf("K8 rho %5.0f: iwashita_oda r' theta_r = %+.12e (expected %+.12e), W15 V_r T = %g, dU_s = %.6e\n", rho,
                r_prime * theta_io, expected, U_w15, U_s);
    EXPECT_NEAR(r_prime * theta_io, expected, 1e-10 * std::max(std::fabs(expected), kR1 * w * T));
    if (rho != 1.0) {
      EXPECT_GT(std::fabs(r_prime * theta_io), 1e-3 * kR1 * w * T);  // not 0
    }
    EXPECT_EQ(U_w15, 0.0);                                   // W15: no rolling
    EXPECT_NEAR(U_s, a_sum * w * T, 1e-10 * a_sum * w * T);  // K2: it slides by (a1 + a2) omega T

    // The same through the law: its history slot accumulates theta_r, and the couple follows it.
    ContactParams p;
    p.K_r = 0.75;
    p.C_r = 0.0;
    p.eta = 1.0;  // no cap
    double slot[1] = {0.0};
    double* hist[1] = {slot};
    RollingCouple M;
    const Pair s = fixed_pair(R2, u_n, w);
    const ContactKinematics k = kinematics(s);
    const ContactBodies b = disc_disc_bodies(disc_mass(kR1), disc_mass(R2), disc_inertia(kR1), disc_inertia(R2));
    for (int n = 0; n < steps; ++n) M = RollingIwashitaOda::moment(p, b, k, 1.0, dt, s.w1, s.w2, hist, 0);
    EXPECT_NEAR(r_prime * slot[0], expected, 1e-10 * std::max(std::fabs(expected), kR1 * w * T));
    EXPECT_NEAR(M.M1, -p.K_r * slot[0], 1e-12 * p.K_r * std::fabs(slot[0]) + 1e-300);
    EXPECT_EQ(M.M2, -M.M1);
  }
}

// K3 with the legacy measure: the pair (rho = 10, overlap 1e-5 m) in rigid rotation Omega = 5 rad/s for 1 rad
// does not roll (the turn of the contact direction dbeta = Omega dt is subtracted from both spins).
TEST(IwashitaOdaMeasure, K3_RigidRotationDoesNotRoll) {
  const double Omega = 5.0, turn = 1.0, u_n = 1e-5, T = turn / Omega;
  const int steps = 200;
  const double dt = T / steps;
  const double R2 = 10.0 * kR1, r_prime = 0.5 * (kR1 + R2);
  double theta_io = 0.0, scale = 0.0;
  for (int n = 0; n < steps; ++n) {
    const Pair s = rigid_pair(R2, u_n, Omega, (n + 0.5) * dt);
    const ContactKinematics k = kinematics(s);
    theta_io += iwashita_oda_rate(k, s.w1, s.w2) * dt;
    scale += (kR1 + R2) * Omega * dt;  // the size of the terms that cancel
  }
  std::printf("K3 iwashita_oda: r' theta_r = %.3e (terms of size %.3e)\n", r_prime * theta_io, scale);
  EXPECT_LE(std::fabs(r_prime * theta_io), 1e-10 * scale);
}

}  // namespace
}  // namespace rondel
