#pragma once
// Tangential laws (docs/physics.md section 2), in the canonical frame: F_t acts on disc 1 along t.
//  - none: frictionless, no history.
//  - coulomb (Cundall & Strack 1979): xi += V_s dt; trial F_t = -k_s xi - c_t V_s,
//    c_t = 2 zeta_t sqrt(m_eff k_s); cap mu F_n by the capping rule (F_t = mu F_n sign(trial), xi = -F_t/k_s).
//    Units: xi [m], k_s [N/m], F_t [N] (per thickness). History slot: "xi".
#include <array>
#include <cmath>

#include "core/ContactParams.hpp"
#include "core/LawSpec.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawTypes.hpp"

namespace rondel {

struct TangentialNone {
  static constexpr const char* name = "none";
  static constexpr const LawBlock* block = nullptr;
  static constexpr const char* no_spring = "frictionless: no tangential spring";
  static constexpr bool kFriction = false;
  static constexpr std::array<const char*, 0> slots{};
  struct History {};
  static TangentialForce force(const ContactInput&, History) { return {}; }
  static double stored(const ContactInput&, History) { return 0.0; }
};

inline constexpr ParamSpec kCoulombParams[] = {
    {"k_s", "N/m", Presence::required, 0.0, kPositive, "tangential stiffness", &ContactParams::k_s, 0.75e6},
    {"mu", "-", Presence::required, 0.0, kNonNegative, "friction coefficient", &ContactParams::mu, 0.5},
    {"zeta_t", "-", Presence::defaulted, 0.0, kNonNegative, "tangential damping ratio", &ContactParams::zeta_t, 0.1},
};
inline constexpr LawBlock kCoulombBlock{"coulomb", "Cundall-Strack tangential spring with Coulomb cap", kCoulombParams};

struct TangentialCoulomb {
  static constexpr const char* name = "coulomb";
  static constexpr const LawBlock* block = &kCoulombBlock;
  static TangentialSpring spring(const ContactParams& p) { return {p.k_s, p.zeta_t}; }
  static constexpr bool kFriction = true;
  static constexpr std::array<const char*, 1> slots{"xi"};
  struct History {
    double& xi;  // [m]
  };
  static TangentialForce force(const ContactInput& in, History h) {
    const ContactParams& p = in.p;
    double& xi = h.xi;
    xi += in.k.V_s * in.dt;
    // Without a dashpot (zeta_t = 0, the usual case) the trial is the spring alone: the same value as
    // -k_s xi - 0 V_s but for the sign of a zero.
    double trial = -p.k_s * xi;
    if (p.zeta_t > 0.0) trial -= 2.0 * p.zeta_t * std::sqrt(in.b.m_eff * p.k_s) * in.k.V_s;
    const double before = xi;
    const CapResult F = cap_spring_slider(trial, p.mu * in.F_n, p.k_s, xi);
    return {F.value, F.capped ? std::fabs(F.value * (before - xi)) : 0.0};
  }
  static double stored(const ContactInput& in, History h) { return 0.5 * in.p.k_s * h.xi * h.xi; }
};

}  // namespace rondel
