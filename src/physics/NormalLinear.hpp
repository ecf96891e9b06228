#pragma once
// Linear spring-dashpot normal law without tension (docs/physics.md section 2):
//   F_n = max(0, k_n u_n - c_n v_n),  c_n = 2 zeta sqrt(m_eff k_n)  (or a user-given c_n) [N, per thickness]
// Damping ratio and restitution are related by docs/validation.md section 4 (see Restitution.hpp).
#include <array>
#include <cmath>

#include "core/ContactParams.hpp"
#include "core/LawSpec.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawTypes.hpp"

namespace rondel {

// [linear]: at most one of zeta, c_n, e may be given (the block's one_of).
inline constexpr ParamSpec kLinearParams[] = {
    {"k_n", "N/m", Presence::required, 0.0, kPositive, "normal stiffness", &ContactParams::k_n, 1e6},
    {"zeta", "-", Presence::optional, 0.0, kNonNegative, "normal damping ratio (default 0; give one of zeta, c_n, e)",
     &ContactParams::zeta_n, 0.1},
    {"c_n", "N s/m", Presence::optional, -1.0, kNonNegative, "normal dashpot coefficient", &ContactParams::c_n_fixed},
    {"e", "-", Presence::optional, -1.0, kRestitution, "restitution coefficient", &ContactParams::e_n},
};
inline constexpr const char* kLinearDamping[] = {"zeta", "c_n", "e"};
inline constexpr LawBlock kLinearBlock{"linear", "normal spring-dashpot, no tension", kLinearParams, kLinearDamping};

struct NormalLinear {
  static constexpr const char* name = "linear";
  static constexpr const LawBlock* block = &kLinearBlock;
  static constexpr bool kStiffening = false;
  static constexpr std::array<const char*, 0> slots{};  // no history
  struct History {};
  // The normal dashpot [N s/m]: its one owner (the kernel, the Jiang laws and the critical step call it).
  static double c_n(const ContactParams& p, const ContactBodies& b) {
    return p.c_n_fixed >= 0.0 ? p.c_n_fixed : 2.0 * p.zeta_n * std::sqrt(b.m_eff * p.k_n);
  }
  static NormalForce force(const ContactInput& in, History = {}) {
    const double f = in.p.k_n * in.k.u_n - c_n(in.p, in.b) * in.k.v_n;
    return {f > 0.0 ? f : 0.0};
  }
  static double stored(const ContactInput& in, History = {}) { return 0.5 * in.p.k_n * in.k.u_n * in.k.u_n; }
  static ContactParams linearised(const ContactInput& in) { return in.p; }
};

}  // namespace rondel
