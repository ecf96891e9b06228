#pragma once
// wang: Wang, Alonso-Marroquin, Xue & Xie 2015 (W15) Eq. 28, a spring-slider on the objective rolling
// displacement (W15 Eq. 11); docs/physics.md section 3.
//   x_r += V_r dt,  V_r = R* (w1 - w2), R* = R1 R2/(R1 + R2) (-> R1 at a wall)            [m]
//   trial T_r = -k_r x_r - c_r V_r, capped at mu_r F_n by the capping rule (x_r = -T_r/k_r)  [N]
//   M = R* T_r, +M on disc 1 and -M on disc 2                                                [N m]
// Parameters k_r [N/m], mu_r [-], c_r [N s/m] (default 0). History slot: "x_r" [m].
// RollingWangT<false> is the same law without the dashpot's terms, for runs in which no pair or wall sets c_r
// (the default): with c_r = 0 it performs the same operations, so it gives the same bits, and saves the tests
// of c_r on every contact (docs/benchmarks.md, "The cost of the rolling law"). RollingWangT<false, true> is that
// law for tables in which every pair and wall has rolling resistance: the kernel skips its per-contact test of
// p.rolling. The law declares both as its Variant (LawSelection::rolling_lean, rolling_every_row).
#include <array>
#include <cmath>

#include "core/ContactParams.hpp"
#include "core/LawSpec.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawTypes.hpp"

namespace rondel {

inline constexpr ParamSpec kWangParams[] = {
    {"k_r", "N/m", Presence::required, 0.0, kPositive, "rolling stiffness", &ContactParams::k_r, 3e4},
    {"mu_r", "-", Presence::required, 0.0, kNonNegative, "rolling friction: cap mu_r F_n on T_r", &ContactParams::mu_r,
     0.1},
    {"c_r", "N s/m", Presence::defaulted, 0.0, kNonNegative, "rolling dashpot", &ContactParams::c_r, 2.0},
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
  static RollingSpring spring(const ContactInput& in) {
    const double R_star = in.k.R_star;
    return {in.p.k_r * R_star * R_star, in.p.c_r * R_star * R_star};
  }
  static constexpr bool kActive = true;
  static constexpr std::array<const char*, 1> slots{"x_r"};
  struct History {
    double& x_r;  // [m]
  };
  // The kernel's variants (LawRows.hpp, with_kernel_laws): `lean` where every pair and wall has no rolling dashpot
  // (the default), `every_row` where moreover every one has rolling resistance.
  static bool lean(const ContactParams& p) { return !(p.c_r > 0.0); }
  template <bool kLean, bool kEveryRowRolls>
  using Variant = RollingWangT<!kLean, kLean && kEveryRowRolls>;

  static RollingCouple moment(const ContactInput& in, History h) {
    // The parameters and the spring in locals, the spring stored once at the end: no store through the
    // history can make the compiler load a parameter again.
    const ContactParams& p = in.p;
    const double k_r = p.k_r, cap = p.mu_r * in.F_n, V_r = in.k.V_r;
    double x_r = h.x_r + V_r * in.dt;
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
      if (p.c_r > 0.0) c.dashpot = p.c_r * V_r * V_r * in.dt;
    }
    h.x_r = x_r;
    c.M1 = in.k.R_star * T;
    c.M2 = -c.M1;
    return c;
  }
  static double stored(const ContactInput& in, History h) { return 0.5 * in.p.k_r * h.x_r * h.x_r; }
  static double cap(const ContactInput& in) { return in.k.R_star * in.p.mu_r * in.F_n; }
};
// The law of the registry (contact.rolling = wang); the kernel selection takes its Variant: without the dashpot's
// terms when no pair or wall has a rolling dashpot, and then without the per-contact test of p.rolling when every
// one has rolling resistance (LawRows.hpp, with_kernel_laws).
using RollingWang = RollingWangT<true>;

}  // namespace rondel
