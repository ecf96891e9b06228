#pragma once
// alonso_marroquin: "model 2" of Wang, Alonso-Marroquin, Xue & Xie 2015 (W15), the rolling velocity taken from
// the contact-point velocities of Alonso-Marroquin et al. 2006 (W15 Eqs. 23-24), kept for comparison studies
// (W15 Figs. 5-6: in biaxial tests it gave less macroscopic friction than W15's Eq. 11, the `wang` law, once
// mu_r > 0.2, and about 4 % less dilatancy); docs/physics.md section 3, docs/validation.md section 10.
//   betadot = -V_t/|d|, the turning rate of the line of centres                               [rad/s]
//   s1 =  R1 (w1 - betadot) =  R1 w1 + R1/|d| V_t   (the contact point on disc 1, W15 Eq. 23)   [m/s]
//   s2 = -R2 (w2 - betadot) = -R2 w2 - R2/|d| V_t   (the contact point on disc 2, W15 Eq. 24)   [m/s]
//   at a wall (R2 -> inf): s1 = R1 w1, s2 = -V_t; a wall rotating at Omega (w2): the same in its frame,
//   s1 = R1 (w1 - Omega), s2 = -(V_t + a1 Omega) (both vanish in rigid co-rotation)
//   V_r2 = sign(s1) min(|s1|, |s2|) when s1 s2 > 0, else 0 (pure rolling is s1 = s2)          [m/s]
//   then `wang`'s spring-slider on V_r2 (W15 Eq. 28):
//   x_r += V_r2 dt; trial T_r = -k_r x_r - c_r V_r2, capped at mu_r F_n by the capping rule    [N]
//   M = R* T_r, +M on disc 1 and -M on disc 2, R* = R1 R2/(R1 + R2) (-> R1 at a wall)          [N m]
// Signs: W15 prints Eqs. 23-24 with its tangent n x z (= -t here) and in the sign assignment of Alonso-Marroquin
// et al.; read with counter-clockwise spins they would give s1 = 2 R1 Omega in rigid rotation, and they vanish
// there with clockwise-positive spins. Written for the counter-clockwise spins of this frame, with the sign that
// makes V_r2 = V_r in pure rolling, they are s1 and s2 above: zero in rigid rotation, and W15's relations to the
// contact-point arcs, da = s1 dt and db = -s2 dt, hold (`iwashita_oda`'s arcs; their average is that law's
// measure). W15 writes them for touching rigid discs, |d| = R1 + R2; |d| = a1 + a2 keeps s1 and s2 exactly
// objective when the discs overlap (a superposed spin adds Omega to w_i and -Omega |d| to V_t).
// Zero in rigid rotation, in pure sliding and whenever s1 and s2 have different signs (no spring increment and
// no dashpot then); equal to `wang`'s V_r = R* (w1 - w2) in pure rolling. Unlike `wang`'s, the spring does not
// follow the relative rotation: the couple does work M (w1 - w2) dt while the spring moves by V_r2 dt, and the
// difference, of either sign, is left in the ledger's D_other (docs/physics.md section 5). At a wall a disc
// rolling without slip has V_t = -a1 w1, so V_r2 = a1 w1, u_n/(2 R1) below `wang`'s R1 w1.
// Parameters: `wang`'s block [wang], k_r [N/m], mu_r [-], c_r [N s/m] (default 0). History slot: "x_r" [m].
#include <algorithm>
#include <array>
#include <cmath>

#include "core/ContactParams.hpp"
#include "core/LawSpec.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawTypes.hpp"
#include "physics/RollingWang.hpp"

namespace rondel {

// The contact-point velocities s1, s2 and the rolling velocity V_r2 they share.
struct AlonsoMarroquinRates {
  double s1 = 0.0, s2 = 0.0, V_r2 = 0.0;
};

inline AlonsoMarroquinRates alonso_marroquin_rates(const ContactKinematics& k, double w1, double w2) {
  AlonsoMarroquinRates r;
  if (k.wall) {  // in the wall's frame (a rotating wall: w2 = Omega, and V_t + a1 Omega is V_t seen from it)
    r.s1 = k.R1 * (w1 - w2);
    r.s2 = -(k.V_t + k.a1 * w2);
  } else {
    const double betadot = -k.V_t / k.dist;
    r.s1 = k.R1 * (w1 - betadot);
    r.s2 = -k.R2 * (w2 - betadot);
  }
  if (r.s1 * r.s2 > 0.0) r.V_r2 = sign(r.s1) * std::min(std::fabs(r.s1), std::fabs(r.s2));
  return r;
}

struct RollingAlonsoMarroquin {
  static constexpr const char* name = "alonso_marroquin";
  static constexpr const LawBlock* block = &kWangBlock;
  // wang's couple stiffness k_r R*^2 and dashpot c_r R*^2: in pure rolling V_r2 = V_r = R* thetadot_r.
  static RollingSpring spring(const ContactInput& in) { return RollingWang::spring(in); }
  static constexpr bool kActive = true;
  static constexpr const char* unsplit_work =
      "the spring moves with V_r2 while the couple works on w1 - w2: the difference is left in D_other";
  static constexpr std::array<const char*, 1> slots{"x_r"};
  struct History {
    double& x_r;  // [m]
  };

  static RollingCouple moment(const ContactInput& in, History h) {
    const ContactParams& p = in.p;
    double& x_r = h.x_r;
    const double V_r2 = alonso_marroquin_rates(in.k, in.w1, in.w2).V_r2;
    x_r += V_r2 * in.dt;
    const double trial = -p.k_r * x_r - p.c_r * V_r2;
    const double before = x_r;
    const CapResult T = cap_spring_slider(trial, p.mu_r * in.F_n, p.k_r, x_r);
    const double M = in.k.R_star * T.value;
    RollingCouple c{M, -M};
    if (T.capped)
      c.plastic = std::fabs(T.value * (before - x_r));
    else
      c.dashpot = p.c_r * V_r2 * V_r2 * in.dt;
    return c;
  }
  static double stored(const ContactInput& in, History h) { return RollingWang::stored(in, {h.x_r}); }
  static double cap(const ContactInput& in) { return RollingWang::cap(in); }
};

}  // namespace rondel
