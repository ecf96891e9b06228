// Objectivity of the rolling laws that are not objective, and of the legacy measure, docs/validation.md section 1
// (every objective law's angular momentum is checked by the conformance tests, test_law_conformance.cpp):
//  K7: an isolated pair (rho = 2) kept in contact by equal and opposite central forces, in rigid spin
//      Omega = 5 rad/s for 1 s: force_proportional's couples M_i = -mu_r F_n a_i sign(omega_i) brake the pair at
//      dL/dt = -mu_r F_n (a1 + a2) (K7Pair.hpp: the rig).
//  K8: K2 (centres fixed, omega1 = omega2, unequal radii) evaluated with the legacy iwashita_oda measure gives
//      dU_r = (R1 - R2) omega T/2, not 0 (the W15 measure V_r gives 0); in rigid rotation (K3) it gives 0.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "K7Pair.hpp"
#include "core/ContactParams.hpp"
#include "core/Vec2.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawTypes.hpp"
#include "physics/RollingForceProportional.hpp"
#include "physics/RollingIwashitaOda.hpp"

namespace rondel {
namespace {

using namespace testing_rig;
using namespace testing_rig::k7;

// force_proportional in K7, rigid spin alone and with a relative spin on top: the pair is braked by the trapezoid
// of -mu_r F_n (a1 + a2) step by step (1e-10 relative), and by an amount bracketed by the extremes of F_n.
TEST(RollingObjectivity, K7_ForceProportionalBrakesARigidlySpinningPair) {
  for (const bool perturbed : {false, true}) {
    SCOPED_TRACE(perturbed ? "rigid spin + relative spin" : "rigid spin");
    const double Omega = 5.0, T = 1.0, dt = 1e-4;
    // The perturbation: +2 rad/s on disc 1, -1 rad/s on disc 2 (both spins stay positive).
    const K7Result r =
        run_k7<RollingForceProportional>(k7_params(), Omega, perturbed ? 2.0 : 0.0, perturbed ? -1.0 : 0.0, T, dt);
    std::printf("K7 force_proportional %-9s L0 %.9e  L_end %.12e  expected %.12e  max dev/L0 %.1e\n",
                perturbed ? "perturbed" : "rigid", r.L0, r.L_end, r.expected_end, r.max_dev / r.L0);
    EXPECT_TRUE(r.in_contact);
    EXPECT_LT(r.max_P, 1e-12 * r.L0 / kR1);  // the pair's momentum stays zero: only internal forces act
    EXPECT_LE(r.max_dev, 1e-10 * std::fabs(r.L0));
    // The braking is real: max_dev above checked it against the trapezoid of -mu_r F_n (a1 + a2) step by step;
    // here its size is bracketed by the extremes of F_n (which grows from 0.1 N as the slowing orbit needs less
    // of the constant external pull).
    EXPECT_GT(r.min_w, 0.0);  // both spins positive throughout: sign(omega_i) = 1
    const double mu_r = k7_params().mu_r, lever_sum = 3.0 * kR1;
    EXPECT_LE(r.L_end - r.L0, -mu_r * r.min_Fn * (lever_sum - 2e-5) * T);
    EXPECT_GE(r.L_end - r.L0, -mu_r * r.max_Fn * lever_sum * T);
    EXPECT_LT(r.L_end, 0.99 * r.L0);
  }
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
    RollingCouple M;
    const Pair s = fixed_pair(R2, u_n, w);
    const ContactKinematics k = kinematics(s);
    const ContactBodies b = disc_disc_bodies(disc_mass(kR1), disc_mass(R2), disc_inertia(kR1), disc_inertia(R2));
    for (int n = 0; n < steps; ++n)
      M = RollingIwashitaOda::moment(ContactInput{p, b, k, 1.0, dt, s.w1, s.w2}, {slot[0]});
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
