#pragma once
// force_proportional: the commercial manual's force proportional method (CM Eq. 3275); docs/physics.md
// section 3. Each disc gets its own couple from its own spin:
//   M_i = -mu_r F_n a_i sign(omega_i)      [N m],  a_i = R_i - u_n/2 (a wall gets none)
// At a wall the disc's spin is taken relative to the wall, sign(omega1 - Omega) (Omega = 0 unless the wall
// rotates, docs/physics.md section 8), so a disc carried round by a rotating wall is not braked.
// Not objective: a pair in rigid rotation is braked, so the angular momentum of an isolated pair is not
// conserved (dL/dt = -mu_r F_n (a1 + a2) for a pair spinning together, docs/validation.md case K7).
// Parameter mu_r [-]. No history.
#include <array>
#include <cmath>

#include "core/ContactParams.hpp"
#include "core/LawSpec.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawTypes.hpp"

namespace rondel {

inline constexpr ParamSpec kForceProportionalParams[] = {
    {"mu_r", "-", Presence::required, 0.0, kNonNegative, "rolling friction", &ContactParams::mu_r, 0.1},
};
inline constexpr LawBlock kForceProportionalBlock{"force_proportional", "commercial manual Eq. 3275 (not objective)",
                                                  kForceProportionalParams};

struct RollingForceProportional {
  static constexpr const char* name = "force_proportional";
  static constexpr const LawBlock* block = &kForceProportionalBlock;
  static constexpr const char* no_spring = "a friction couple without a spring";
  static constexpr bool kActive = true;
  static constexpr const char* not_objective =
      "each disc's couple follows its own spin (a pair in rigid rotation is braked)";
  static constexpr const char* unsplit_work = "a friction couple without a spring: its work is left unsplit";
  static constexpr bool kOwnCouples = true;  // M2 is not -M1: the rows keep both couples
  static constexpr std::array<const char*, 0> slots{};
  struct History {};

  static RollingCouple moment(const ContactInput& in, History) {
    const ContactKinematics& k = in.k;
    const double f = in.p.mu_r * in.F_n;
    if (k.wall) return {-f * k.a1 * sign(k.thetadot_r), 0.0};  // the disc's spin relative to the wall
    return {-f * k.a1 * sign(in.w1), -f * k.a2 * sign(in.w2)};
  }
  static double stored(const ContactInput&, History) { return 0.0; }
  static double cap(const ContactInput& in) { return in.p.mu_r * in.F_n * in.k.a1; }
};

}  // namespace rondel
