#pragma once
// jiang_plastic: Jiang, Yu & Harris 2005 (J05) Model 1, Eqs. 24, 29, 33, 35, 49c; docs/physics.md section 3.
//   contact width B = delta r, r = 2 R1 R2/(R1 + R2) (-> 2 R1 at a wall, J05 Eq. 11)      [m]
//   K_m = k_n B^2/12 [N m/rad],  mu_m = c_n B^2/12 [N m s/rad]
//   theta_r += thetadot_r dt;  trial M = -K_m theta_r - mu_m thetadot_r  [N m, per thickness]
//   capped at M0 = F_n B/6 by the capping rule (theta_r reset to -M/K_m).
// The couple acts +M on disc 1 and -M on disc 2. History slot: "theta_r" [rad]. Parameter: delta.
#include <array>
#include <cmath>

#include "core/ContactParams.hpp"
#include "core/LawSpec.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawTypes.hpp"
#include "physics/NormalLinear.hpp"

namespace rondel {

// [jiang], shared by jiang_plastic and jiang_brittle. after_break (jiang_brittle, its words' indices in
// ContactParams::after_break): what a broken contact does next (RollingJiangBrittle).
inline constexpr const char* kAfterBreakWords[] = {"reform", "open"};
inline constexpr double kAfterBreakReform = 0.0, kAfterBreakOpen = 1.0;
inline constexpr ParamSpec kJiangParams[] = {
    {"delta", "-", Presence::required, 0.0, kPositive, "shape parameter: contact width B = delta r",
     &ContactParams::delta, 0.3},
    {"after_break", "-", Presence::defaulted, kAfterBreakReform, Range{0.0, 1.0, false, false},
     "jiang_brittle after a break: reform (the spring restarts from theta_r = 0 the next step) or open (no couple "
     "until the contact opens)",
     &ContactParams::after_break, NAN, kAfterBreakWords},
};
inline constexpr LawBlock kJiangBlock{"jiang", "Jiang, Yu & Harris 2005 (jiang_plastic, jiang_brittle)", kJiangParams};

struct JiangGeometry {
  double B, K_m, mu_m;
};

inline JiangGeometry jiang_geometry(const ContactInput& in) {
  const double B = in.p.delta * harmonic_radius(in.k);
  return {B, in.p.k_n * B * B / 12.0, NormalLinear::c_n(in.p, in.b) * B * B / 12.0};
}

// Model 1's step, shared by both Jiang models (jiang_brittle between its breaks), with the contact's geometry g:
// theta_r += thetadot_r dt, the elastic-plastic spring-slider, and the ledger's split made exact (docs/physics.md
// section 5): the kernel integrates the couple's work with the trapezoid of last and this step's couple, so the
// energy the rolling spring-slider takes from the motion this step is -(M' + M)/2 thetadot_r dt; what the spring
// does not store, K_m (theta_r^2 - theta_r'^2)/2, is dissipated: plastic work when the couple is at its cap, dashpot
// work otherwise. Booked so, D_rolling_plastic + D_rolling_dashpot + the stored rolling energy equal -W_rolling to
// round-off.
inline RollingCouple jiang_step(const ContactInput& in, const JiangGeometry& g, double& theta_r) {
  const double before = theta_r;
  theta_r += in.k.thetadot_r * in.dt;
  const double trial = -g.K_m * theta_r - g.mu_m * in.k.thetadot_r;
  const CapResult m = cap_spring_slider(trial, in.F_n * g.B / 6.0, g.K_m, theta_r);
  RollingCouple c{m.value, -m.value};
  c.yielded = m.capped;
  const double taken = -0.5 * (in.M1_prev + c.M1) * in.k.thetadot_r * in.dt;
  const double lost = taken - 0.5 * g.K_m * (theta_r * theta_r - before * before);
  c.plastic = c.yielded ? lost : 0.0;
  c.dashpot = c.yielded ? 0.0 : lost;
  return c;
}

struct RollingJiangPlastic {
  static constexpr const char* name = "jiang_plastic";
  static constexpr const LawBlock* block = &kJiangBlock;
  // K_m = k_n B^2/12 and mu_m = c_n B^2/12 (shared with jiang_brittle, which breaks at the same spring).
  static RollingSpring spring(const ContactInput& in) {
    const JiangGeometry g = jiang_geometry(in);
    return {g.K_m, g.mu_m};
  }
  static constexpr bool kActive = true;
  static constexpr std::array<const char*, 1> slots{"theta_r"};
  struct History {
    double& theta_r;  // [rad]
  };

  static RollingCouple moment(const ContactInput& in, History h) {
    return jiang_step(in, jiang_geometry(in), h.theta_r);
  }
  static double stored(const ContactInput& in, History h) {
    return 0.5 * jiang_geometry(in).K_m * h.theta_r * h.theta_r;
  }
  // The couple at yield, M0 = F_n B/6.
  static double cap(const ContactInput& in) { return in.F_n * in.p.delta * harmonic_radius(in.k) / 6.0; }
};

}  // namespace rondel
