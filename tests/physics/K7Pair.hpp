#pragma once
// Case K7 of docs/validation.md section 1 as a rig: an isolated pair (rho = 2) kept in contact by equal and opposite
// central forces, in rigid spin, integrated with a velocity-Verlet loop of its own built on the library's law
// functions (disc_disc_kinematics, NormalLinear, TangentialCoulomb and the rolling law), recording what the
// conformance tests (angular momentum of every objective law) and the force_proportional test (its braking)
// check.
//
// It is not Simulation: the case needs two external central forces that hold the pair together (the contact has
// no tension and Simulation has no external forces besides gravity), and it records F_n, a1, a2 and the couples of
// every step. The loop is the integrator of docs/design.md section 4: half kick, drift, forces from the new
// positions and the half-step velocities (which also increment the springs), half kick; the forces at t = 0 are
// those of the initial state with a zero increment. Forces and torques follow docs/physics.md section 1.
//
// Why conservation is exact in this scheme: with f the force on 1 and -f on 2, sum x_i x f_i + tau_i =
// -(d x f) + (a1 + a2) F_t + M1 + M2 = M1 + M2 (d x (F_t t) = |d| F_t, a1 + a2 = |d|), and central forces
// contribute nothing. Velocity Verlet changes L by dt/2 of that sum at the old and at the new positions, so
// L_{n+1} - L_n = dt/2 [(M1 + M2)_n + (M1 + M2)_{n+1}] to rounding: zero for the objective laws (M2 = -M1),
// and the trapezoid of -mu_r F_n (a1 + a2) for force_proportional while both spins stay positive.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "core/ContactParams.hpp"
#include "core/Vec2.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawConcepts.hpp"
#include "physics/LawTypes.hpp"
#include "physics/NormalLinear.hpp"
#include "physics/TangentialLaws.hpp"

namespace rondel::testing_rig {

namespace k7 {
constexpr double kPi = std::numbers::pi;
constexpr double kDensity = 2650.0;
constexpr double kR1 = 0.01;
inline double disc_mass(double R) { return kDensity * kPi * R * R; }
inline double disc_inertia(double R) { return 0.5 * disc_mass(R) * R * R; }
inline Vec2 rotate(Vec2 a, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * a.x - s * a.y, s * a.x + c * a.y};
}
}  // namespace k7

// Parameters for every law of the seeds at once (each law reads its own fields). k_n = 1e4 N/m with an overlap of
// 1e-5 m gives F_n = 0.1 N: force_proportional's braking mu_r F_n (a1 + a2) = 3e-4 N m then takes about 5 % of L
// in 1 s and both spins stay positive. The dashpots are on, so that velocities enter every couple.
inline ContactParams k7_params() {
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

inline double angular_momentum(const PairState& s, const double m[2], const double I[2]) {
  double L = 0.0;
  for (int i = 0; i < 2; ++i) L += I[i] * s.w[i] + m[i] * cross(s.x[i], s.v[i]);
  return L;
}

// Rigid spin Omega of the pair about its centre of mass (at the origin) with overlap u_n0; `dw1`, `dw2` are
// spins added on top (a perturbation that makes the rolling springs, caps and dashpots act). `p`: the contact's
// parameters (k7_params(), or a law's example values over it).
template <class Rolling>
K7Result run_k7(const ContactParams& p, double Omega, double dw1, double dw2, double T, double dt) {
  using namespace k7;
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

  // History of the one contact row: the tangential slot and up to two rolling slots.
  double t_slot[1] = {0.0}, r_slots[2][1] = {{0.0}, {0.0}};
  double* t_ptr[1] = {t_slot};
  double* r_ptr[2] = {r_slots[0], r_slots[1]};
  const auto t_hist = history_row<TangentialCoulomb::History, 1>(t_ptr, 0);
  const auto r_hist = history_row<typename Rolling::History, Rolling::slots.size()>(r_ptr, 0);

  const ContactBodies bodies = disc_disc_bodies(m[0], m[1], I[0], I[1]);
  Vec2 f[2];
  double tq[2];
  K7Result out;
  double brake = 0.0;  // -mu_r F_n (a1 + a2) of the latest force evaluation (force_proportional's formula)
  double M1_prev = 0.0;
  auto forces = [&](double h) {
    const Vec2 d = s.x[1] - s.x[0];
    const double dist = std::sqrt(dot(d, d));
    const ContactKinematics k = disc_disc_kinematics(d, dist, R[0], R[1], s.v[0], s.v[1], s.w[0], s.w[1]);
    if (k.u_n <= 0.0) out.in_contact = false;
    const double F_n = NormalLinear::force(ContactInput{p, bodies, k}).F_n;
    const ContactInput in{p, bodies, k, F_n, h, s.w[0], s.w[1], M1_prev};
    const TangentialForce Ft = TangentialCoulomb::force(in, t_hist);
    const RollingCouple M = Rolling::moment(in, r_hist);
    M1_prev = M.M1;
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
  const bool fp = own_couples<Rolling>();  // force_proportional: each disc brakes by its own couple
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

}  // namespace rondel::testing_rig
