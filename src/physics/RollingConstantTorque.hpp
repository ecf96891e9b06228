#pragma once
// constant_torque: the commercial manual's constant torque method with its moment limiter (CM Eq. 3276);
// docs/physics.md section 3.
//   M = -sign(omega1 - omega2) mu_r R_eq F_n,  R_eq = 2 R1 R2/(R1 + R2) (harmonic mean, -> 2 R1 at a wall)
//   limiter, read literally: |M| <= f_lim min(I1 |omega1|, I2 |omega2|)/dt (a wall contributes no term);
//   f_lim = 0 switches it off. +M on disc 1, -M on disc 2.
// With the limiter on, a disc rolling over a resting disc meets no resistance (min(...) = 0): this is the
// manual's rule, kept as written. Parameters mu_r [-], f_lim [-] (default 0.08). No history.
#include <algorithm>
#include <array>
#include <cmath>

#include "core/ContactParams.hpp"
#include "core/LawSpec.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawTypes.hpp"

namespace rondel {

inline constexpr ParamSpec kConstantTorqueParams[] = {
    {"mu_r", "-", Presence::required, 0.0, kNonNegative, "rolling friction", &ContactParams::mu_r, 0.05},
    {"f_lim", "-", Presence::defaulted, 0.08, kNonNegative, "moment limiter fraction; 0 switches the limiter off",
     &ContactParams::f_lim},
};
inline constexpr LawBlock kConstantTorqueBlock{"constant_torque", "commercial manual Eq. 3276 with moment limiter",
                                               kConstantTorqueParams};

struct RollingConstantTorque {
  static constexpr const char* name = "constant_torque";
  static constexpr const LawBlock* block = &kConstantTorqueBlock;
  static constexpr const char* no_spring = "a constant couple without a spring";
  static constexpr bool kActive = true;
  static constexpr const char* not_objective = "its moment limiter reads each disc's own spin (f_lim > 0)";
  static constexpr const char* unsplit_work = "a constant couple without a spring: its work is left unsplit";
  static constexpr std::array<const char*, 0> slots{};
  struct History {};

  static RollingCouple moment(const ContactInput& in, History) {
    const ContactParams& p = in.p;
    const double R_eq = harmonic_radius(in.k);
    double M = -sign(in.w1 - in.w2) * p.mu_r * R_eq * in.F_n;
    if (p.f_lim > 0.0 && in.dt > 0.0) {
      double spin = in.b.I1 * std::fabs(in.w1);
      if (!in.k.wall) spin = std::min(spin, in.b.I2 * std::fabs(in.w2));
      const double limit = p.f_lim * spin / in.dt;
      if (std::fabs(M) > limit) M = limit * sign(M);
    }
    return {M, -M};
  }
  static double stored(const ContactInput&, History) { return 0.0; }
  static double cap(const ContactInput& in) { return in.p.mu_r * harmonic_radius(in.k) * in.F_n; }
};

}  // namespace rondel
