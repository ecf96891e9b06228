#pragma once
// Mindlin tangential law (docs/physics.md section 6; Mindlin & Deresiewicz 1953 in the no-slip form of
// LIGGGHTS and Lethe, Tsuji dashpot), with contact.normal = hertz (its beta):
//   S_t = 8 G* sqrt(R* u_n)                                      [N/m]
//   xi += V_s dt;  trial F_t = -S_t xi + 2 sqrt(5/6) beta sqrt(S_t m_eff) V_s   [N, per thickness]
//   capped at mu F_n by the capping rule of section 1 (F_t = mu F_n sign(trial), xi = -F_t/S_t).
//   stored energy F_t^2/(2 S_t) of the spring part = S_t xi^2/2. History slot: "xi" [m].
// S_t changes with the overlap: the stored energy then changes without contact work, and the ledger books
// that change with the dashpots and the integration error (D_other).
#include <array>
#include <cmath>

#include "core/ContactParams.hpp"
#include "core/LawSpec.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawTypes.hpp"
#include "physics/NormalHertz.hpp"

namespace rondel {

inline constexpr ParamSpec kMindlinParams[] = {
    {"mu", "-", Presence::required, 0.0, kNonNegative, "friction coefficient", &ContactParams::mu, 0.5},
};
inline constexpr LawBlock kMindlinBlock{
    "mindlin", "Mindlin tangential stiffness with Coulomb cap (G* of the materials)", kMindlinParams};

struct TangentialMindlin {
  static constexpr const char* name = "mindlin";
  static constexpr const LawBlock* block = &kMindlinBlock;
  static constexpr bool kElastic = true;  // G* from the materials' E and nu
  static constexpr const char* kNeedsNormal = NormalHertz::name;
  static constexpr const char* kNeedsWhy = "its damping and stiffness come from the Hertz contact";
  // The critical step linearises the law at its largest overlap (linearised() below: k_s = S_t and zeta_t =
  // sqrt(5/6) |beta| there), so the spring is read as the coulomb one.
  static TangentialSpring spring(const ContactParams& p) { return {p.k_s, p.zeta_t}; }
  static constexpr bool kFriction = true;
  static constexpr std::array<const char*, 1> slots{"xi"};
  struct History {
    double& xi;  // [m]
  };

  static double stiffness(const ContactParams& p, const ContactKinematics& k) {
    return 8.0 * p.G_star * std::sqrt(k.R_star * k.u_n);
  }
  // The law as the coulomb spring-dashpot it is at this overlap: k_s = S_t, and the dashpot
  // 2 sqrt(5/6)|beta| sqrt(S_t m_eff) in the coulomb form 2 zeta_t sqrt(m_eff k_s), zeta_t = sqrt(5/6)|beta|.
  static ContactParams linearised(const ContactInput& in) {
    ContactParams q = in.p;
    q.k_s = stiffness(in.p, in.k);
    q.zeta_t = -0.5 * NormalHertz::kDashpot * in.p.beta;
    return q;
  }
  static TangentialForce force(const ContactInput& in, History h) {
    const ContactParams& p = in.p;
    const ContactKinematics& k = in.k;
    double& xi = h.xi;
    xi += k.V_s * in.dt;
    const double S_t = stiffness(p, k);
    const double trial = -S_t * xi + NormalHertz::kDashpot * p.beta * std::sqrt(S_t * in.b.m_eff) * k.V_s;
    const double before = xi;
    const CapResult F = cap_spring_slider(trial, p.mu * in.F_n, S_t, xi);
    return {F.value, F.capped ? std::fabs(F.value * (before - xi)) : 0.0};
  }
  static double stored(const ContactInput& in, History h) { return 0.5 * stiffness(in.p, in.k) * h.xi * h.xi; }
};

}  // namespace rondel
