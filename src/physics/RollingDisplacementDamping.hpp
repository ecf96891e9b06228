#pragma once
// displacement_damping: the commercial manual's displacement damping method (CM Eqs. 3277-3278);
// docs/physics.md section 3.
//   R_eq = 2 R1 R2/(R1 + R2) (-> 2 R1 at a wall),  k_r = mu_r R_eq F_n/theta_rmax      [N m/rad]
//   trial = M_k - k_r (omega1 - omega2) dt; |trial| > mu_r R_eq F_n: "at the limit", M_k clamped to it;
//   otherwise "elastic", M_k = trial.
//   viscous part (only when nu > 0): -nu C_crit (omega1 - omega2) elastic, -f nu C_crit (omega1 - omega2)
//   at the limit (regime from the trial value); C_crit = 2 sqrt(I_r k_r),
//   I_r = [(I1 + m1 R1^2)^-1 + (I2 + m2 R2^2)^-1]^-1 (a wall: I1 + m1 R1^2).
//   M = M_k + M_d, +M on disc 1 and -M on disc 2.
// Parameters mu_r, theta_rmax (0.035), nu (0), f (1). History slot: "M_k" [N m].
#include <array>
#include <cmath>

#include "core/ContactParams.hpp"
#include "core/LawSpec.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawTypes.hpp"

namespace rondel {

inline constexpr ParamSpec kDisplacementDampingParams[] = {
    {"mu_r", "-", Presence::required, 0.0, kNonNegative, "rolling friction", &ContactParams::mu_r, 0.05},
    {"theta_rmax", "rad", Presence::defaulted, 0.035, kPositive, "rotation at which the couple reaches its cap",
     &ContactParams::theta_rmax},
    {"nu", "-", Presence::defaulted, 0.0, kNonNegative, "viscous damping factor (0 = off)", &ContactParams::nu},
    {"f", "-", Presence::defaulted, 1.0, kNonNegative, "viscous damping multiplier at the limit",
     &ContactParams::f_visc},
};
inline constexpr LawBlock kDisplacementDampingBlock{"displacement_damping", "commercial manual Eqs. 3277-3278",
                                                    kDisplacementDampingParams};

struct RollingDisplacementDamping {
  static constexpr const char* name = "displacement_damping";
  static constexpr const LawBlock* block = &kDisplacementDampingBlock;
  static constexpr const char* no_spring = "k_r = mu_r R_eq F_n/theta_rmax grows with F_n: not known in advance";
  static constexpr bool kActive = true;
  static constexpr std::array<const char*, 1> slots{"M_k"};
  struct History {
    double& M_k;  // [N m]
  };

  static double R_eq(const ContactKinematics& k) { return harmonic_radius(k); }

  static RollingCouple moment(const ContactInput& in, History h) {
    const ContactParams& p = in.p;
    const ContactKinematics& k = in.k;
    double& M_k = h.M_k;
    const double cap = p.mu_r * R_eq(k) * in.F_n;
    const double k_r = cap / p.theta_rmax;
    const double rel = k.thetadot_r;
    const double trial = M_k - k_r * rel * in.dt;
    const bool at_limit = std::fabs(trial) > cap;
    RollingCouple c;
    if (at_limit) {
      const double clamped = cap * sign(trial);
      c.plastic = k_r > 0.0 ? std::fabs(clamped * (trial - clamped)) / k_r : 0.0;  // cap x slip angle
      M_k = clamped;
    } else {
      M_k = trial;
    }
    double M_d = 0.0;
    if (p.nu > 0.0) {
      const ContactBodies& b = in.b;
      const double I_r = k.wall ? b.I1 + b.m1 * k.R1 * k.R1
                                : 1.0 / (1.0 / (b.I1 + b.m1 * k.R1 * k.R1) + 1.0 / (b.I2 + b.m2 * k.R2 * k.R2));
      const double C_crit = 2.0 * std::sqrt(I_r * k_r);
      M_d = -(at_limit ? p.f_visc : 1.0) * p.nu * C_crit * rel;
      c.dashpot = -M_d * rel * in.dt;
    }
    c.M1 = M_k + M_d;
    c.M2 = -c.M1;
    return c;
  }
  static double stored(const ContactInput& in, History h) {
    const double k_r = in.p.mu_r * R_eq(in.k) * in.F_n / in.p.theta_rmax;
    const double M = h.M_k;
    return k_r > 0.0 ? 0.5 * M * M / k_r : 0.0;
  }
  static double cap(const ContactInput& in) { return in.p.mu_r * R_eq(in.k) * in.F_n; }
};

}  // namespace rondel
