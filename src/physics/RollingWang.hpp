#pragma once
// wang: Wang, Alonso-Marroquin, Xue & Xie 2015 (W15) Eq. 28, a spring-slider on the objective rolling
// displacement (W15 Eq. 11); docs/physics.md section 3.
//   x_r += V_r dt,  V_r = R* (w1 - w2), R* = R1 R2/(R1 + R2) (-> R1 at a wall)            [m]
//   trial T_r = -k_r x_r - c_r V_r, capped at mu_r F_n by the capping rule (x_r = -T_r/k_r)  [N]
//   M = R* T_r, +M on disc 1 and -M on disc 2                                                [N m]
// Parameters k_r [N/m], mu_r [-], c_r [N s/m] (default 0). History slot: "x_r" [m].
#include <array>
#include <cmath>

#include "core/ContactParams.hpp"
#include "core/LawSpec.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawTypes.hpp"

namespace rondel {

inline constexpr ParamSpec kWangParams[] = {
    {"k_r", "N/m", Presence::required, 0.0, kPositive, "rolling stiffness", &ContactParams::k_r},
    {"mu_r", "-", Presence::required, 0.0, kNonNegative, "rolling friction: cap mu_r F_n on T_r", &ContactParams::mu_r},
    {"c_r", "N s/m", Presence::defaulted, 0.0, kNonNegative, "rolling dashpot", &ContactParams::c_r},
};
// Shared with alonso_marroquin (RollingAlonsoMarroquin.hpp), the same spring-slider on W15's "model 2" velocity.
inline constexpr LawBlock kWangBlock{"wang", "Wang et al. 2015 rolling spring-slider (wang, alonso_marroquin)",
                                     kWangParams};

struct RollingWang {
  static constexpr const char* name = "wang";
  static constexpr const LawBlock* block = &kWangBlock;
  // The couple stiffness k_r R*^2 and dashpot c_r R*^2 (M = R* T_r with T_r on x_r = R* theta_r).
  static RollingSpring spring(const ContactParams& p, const ContactBodies&, const ContactKinematics& k) {
    return {p.k_r * k.R_star * k.R_star, p.c_r * k.R_star * k.R_star};
  }
  static constexpr bool kActive = true;
  static constexpr std::array<const char*, 1> slots{"x_r"};

  static RollingCouple moment(const ContactParams& p, const ContactBodies&, const ContactKinematics& k, double F_n,
                              double dt, double, double, double* const* hist, std::size_t row) {
    double& x_r = hist[0][row];
    x_r += k.V_r * dt;
    // Without a dashpot (c_r = 0, the default) the trial is the spring alone and nothing is damped.
    double trial = -p.k_r * x_r;
    if (p.c_r > 0.0) trial -= p.c_r * k.V_r;
    const double before = x_r;
    const CapResult T = cap_spring_slider(trial, p.mu_r * F_n, p.k_r, x_r);
    const double M = k.R_star * T.value;
    RollingCouple c{M, -M};
    if (T.capped)
      c.plastic = std::fabs(T.value * (before - x_r));
    else if (p.c_r > 0.0)
      c.dashpot = p.c_r * k.V_r * k.V_r * dt;
    return c;
  }
  static double stored(const ContactParams& p, const ContactBodies&, const ContactKinematics&, double,
                       double* const* hist, std::size_t row) {
    const double x = hist[0][row];
    return 0.5 * p.k_r * x * x;
  }
  static double cap(const ContactParams& p, const ContactKinematics& k, double F_n) { return k.R_star * p.mu_r * F_n; }
};

}  // namespace rondel
