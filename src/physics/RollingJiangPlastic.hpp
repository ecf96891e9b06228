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

// [jiang], shared by jiang_plastic and jiang_brittle.
inline constexpr ParamSpec kJiangParams[] = {
    {"delta", "-", Presence::required, 0.0, kPositive, "shape parameter: contact width B = delta r",
     &ContactParams::delta},
};
inline constexpr LawBlock kJiangBlock{"jiang", "Jiang, Yu & Harris 2005 (jiang_plastic, jiang_brittle)", kJiangParams};

struct JiangGeometry {
  double B, K_m, mu_m;
};

inline JiangGeometry jiang_geometry(const ContactParams& p, const ContactBodies& b, const ContactKinematics& k) {
  const double B = p.delta * harmonic_radius(k);
  return {B, p.k_n * B * B / 12.0, NormalLinear::c_n(p, b) * B * B / 12.0};
}

// The elastic-plastic spring-slider shared by both Jiang models; theta_r already incremented.
inline RollingCouple jiang_spring_slider(const JiangGeometry& g, double F_n, double thetadot_r, double dt,
                                         double& theta_r) {
  const double trial = -g.K_m * theta_r - g.mu_m * thetadot_r;
  const double before = theta_r;
  const CapResult m = cap_spring_slider(trial, F_n * g.B / 6.0, g.K_m, theta_r);
  RollingCouple c{m.value, -m.value};
  c.yielded = m.capped;
  if (m.capped)
    c.plastic = std::fabs(m.value * (before - theta_r));
  else
    c.dashpot = g.mu_m * thetadot_r * thetadot_r * dt;
  return c;
}

struct RollingJiangPlastic {
  static constexpr const char* name = "jiang_plastic";
  static constexpr const LawBlock* block = &kJiangBlock;
  // K_m = k_n B^2/12 and mu_m = c_n B^2/12 (shared with jiang_brittle, which breaks at the same spring).
  static RollingSpring spring(const ContactParams& p, const ContactBodies& b, const ContactKinematics& k) {
    const JiangGeometry g = jiang_geometry(p, b, k);
    return {g.K_m, g.mu_m};
  }
  static constexpr bool kActive = true;
  static constexpr std::array<const char*, 1> slots{"theta_r"};

  static RollingCouple moment(const ContactParams& p, const ContactBodies& b, const ContactKinematics& k, double F_n,
                              double dt, double, double, double* const* hist, std::size_t row) {
    double& theta_r = hist[0][row];
    theta_r += k.thetadot_r * dt;
    return jiang_spring_slider(jiang_geometry(p, b, k), F_n, k.thetadot_r, dt, theta_r);
  }
  static double stored(const ContactParams& p, const ContactBodies& b, const ContactKinematics& k, double,
                       double* const* hist, std::size_t row) {
    const double th = hist[0][row];
    return 0.5 * jiang_geometry(p, b, k).K_m * th * th;
  }
  // The ledger's split made exact (docs/physics.md section 5): the kernel integrates the couple's work with
  // the trapezoid of last and this step's couple, so the energy the rolling spring-slider takes from the
  // motion this step is -(M' + M)/2 thetadot_r dt; what the spring does not store, K_m (theta_r^2 -
  // theta_r'^2)/2, is dissipated: plastic work when the couple is at its cap, dashpot work otherwise. Booked
  // so, D_rolling_plastic + D_rolling_dashpot + the stored rolling energy equal -W_rolling to round-off.
  static void split(const ContactParams& p, const ContactBodies& b, const ContactKinematics& k, double M_prev,
                    double theta_before, double theta_after, double dt, RollingCouple& c) {
    const double K_m = jiang_geometry(p, b, k).K_m;
    const double taken = -0.5 * (M_prev + c.M1) * k.thetadot_r * dt;
    const double lost = taken - 0.5 * K_m * (theta_after * theta_after - theta_before * theta_before);
    c.plastic = c.yielded ? lost : 0.0;
    c.dashpot = c.yielded ? 0.0 : lost;
  }
  // The couple at yield, M0 = F_n B/6.
  static double cap(const ContactParams& p, const ContactKinematics& k, double F_n) {
    return F_n * p.delta * harmonic_radius(k) / 6.0;
  }
};

}  // namespace rondel
