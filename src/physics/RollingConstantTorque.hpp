#pragma once
// constant_torque: the commercial manual's constant torque method with its moment limiter (CM Eq. 3276);
// PHYSICS.md section 3.
//   M = -sign(omega1 - omega2) mu_r R_eq F_n,  R_eq = 2 R1 R2/(R1 + R2) (harmonic mean, -> 2 R1 at a wall)
//   limiter, read literally: |M| <= f_lim min(I1 |omega1|, I2 |omega2|)/dt (a wall contributes no term);
//   f_lim = 0 switches it off. +M on disc 1, -M on disc 2.
// With the limiter on, a disc rolling over a resting disc meets no resistance (min(...) = 0): this is the
// manual's rule, kept as written. Parameters mu_r [-], f_lim [-] (default 0.08). No history.
#include <algorithm>
#include <array>
#include <cmath>

#include "core/ContactParams.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawTypes.hpp"

namespace rondel {

struct RollingConstantTorque {
  static constexpr const char* name = "constant_torque";
  static constexpr bool kActive = true;
  static constexpr std::array<const char*, 0> slots{};

  static RollingCouple moment(const ContactParams& p, const ContactBodies& b, const ContactKinematics& k,
                              double F_n, double dt, double w1, double w2, double* const*, std::size_t) {
    const double R_eq = k.wall ? 2.0 * k.R1 : 2.0 * k.R1 * k.R2 / (k.R1 + k.R2);
    double M = -sign(w1 - w2) * p.mu_r * R_eq * F_n;
    if (p.f_lim > 0.0 && dt > 0.0) {
      double spin = b.I1 * std::fabs(w1);
      if (!k.wall) spin = std::min(spin, b.I2 * std::fabs(w2));
      const double limit = p.f_lim * spin / dt;
      if (std::fabs(M) > limit) M = limit * sign(M);
    }
    return {M, -M};
  }
  static double stored(const ContactParams&, const ContactBodies&, const ContactKinematics&, double,
                       double* const*, std::size_t) {
    return 0.0;
  }
  static double cap(const ContactParams& p, const ContactKinematics& k, double F_n) {
    return p.mu_r * (k.wall ? 2.0 * k.R1 : 2.0 * k.R1 * k.R2 / (k.R1 + k.R2)) * F_n;
  }
};

}  // namespace rondel
