#pragma once
// wang: Wang, Alonso-Marroquin, Xue & Xie 2015 (W15) Eq. 28, a spring-slider on the objective rolling
// displacement (W15 Eq. 11); docs/physics.md section 3.
//   x_r += V_r dt,  V_r = R* (w1 - w2), R* = R1 R2/(R1 + R2) (-> R1 at a wall)            [m]
//   trial T_r = -k_r x_r - c_r V_r, capped at mu_r F_n by the capping rule (x_r = -T_r/k_r)  [N]
//   M = R* T_r, +M on disc 1 and -M on disc 2                                                [N m]
// Parameters k_r [N/m], mu_r [-], c_r [N s/m] (default 0). History slot: "x_r" [m].
// RollingWangT<false> is the same law without the dashpot's terms, for runs in which no pair or wall sets c_r
// (the default): with c_r = 0 it performs the same operations, so it gives the same bits, and saves the tests
// of c_r on every contact (LawSelection::rolling_dashpot; docs/benchmarks.md, "The cost of the rolling law").
// RollingWangT<false, true> is that law for tables in which every pair and wall has rolling resistance: the kernel
// skips its per-contact test of p.rolling (LawSelection::rolling_every_row).
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

template <bool kDashpot, bool kAllRoll = false>
struct RollingWangT {
  static constexpr const char* name = "wang";
  static constexpr bool kEveryRow = kAllRoll;
  static constexpr bool kSparseLoss = !kDashpot;  // without a dashpot, only a capped contact dissipates
  static constexpr const LawBlock* block = &kWangBlock;
  // The couple stiffness k_r R*^2 and dashpot c_r R*^2 (M = R* T_r with T_r on x_r = R* theta_r).
  static RollingSpring spring(const ContactParams& p, const ContactBodies&, const ContactKinematics& k) {
    return {p.k_r * k.R_star * k.R_star, p.c_r * k.R_star * k.R_star};
  }
  static constexpr bool kActive = true;
  static constexpr std::array<const char*, 1> slots{"x_r"};

  static RollingCouple moment(const ContactParams& p, const ContactBodies&, const ContactKinematics& k, double F_n,
                              double dt, double, double, double* const* hist, std::size_t row) {
    // The parameters and the spring in locals, the spring stored once at the end: no store through the
    // history can make the compiler load a parameter again.
    double* const spring = hist[0] + row;
    const double k_r = p.k_r, cap = p.mu_r * F_n, V_r = k.V_r;
    double x_r = *spring + V_r * dt;
    // Without a dashpot (c_r = 0, the default) the trial is the spring alone and nothing is damped.
    double T = -k_r * x_r;
    if constexpr (kDashpot)
      if (p.c_r > 0.0) T -= p.c_r * V_r;
    RollingCouple c;
    // The capping rule (cap_spring_slider): T at the cap, the spring reset to it.
    if (std::fabs(T) > cap) [[unlikely]] {
      T = cap * sign(T);
      const double before = x_r;
      x_r = -T / k_r;
      c.plastic = std::fabs(T * (before - x_r));
    } else if constexpr (kDashpot) {
      if (p.c_r > 0.0) c.dashpot = p.c_r * V_r * V_r * dt;
    }
    *spring = x_r;
    c.M1 = k.R_star * T;
    c.M2 = -c.M1;
    return c;
  }
  static double stored(const ContactParams& p, const ContactBodies&, const ContactKinematics&, double,
                       double* const* hist, std::size_t row) {
    const double x = hist[0][row];
    return 0.5 * p.k_r * x * x;
  }
  static double cap(const ContactParams& p, const ContactKinematics& k, double F_n) { return k.R_star * p.mu_r * F_n; }
};
// The law of the registry (contact.rolling = wang); the kernel selection swaps in RollingWangT<false> when no
// pair or wall has a rolling dashpot, RollingWangT<false, true> when moreover every one has rolling resistance
// (LawRows.hpp, with_kernel_laws).
using RollingWang = RollingWangT<true>;
using RollingWangUndamped = RollingWangT<false>;
// RollingWangUndamped where every pair and wall has rolling resistance (LawSelection::rolling_every_row).
using RollingWangUndampedEveryRow = RollingWangT<false, true>;

}  // namespace rondel
