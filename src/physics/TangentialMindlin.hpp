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
    {"mu", "-", Presence::required, 0.0, kNonNegative, "friction coefficient", &ContactParams::mu},
};
inline constexpr LawBlock kMindlinBlock{
    "mindlin", "Mindlin tangential stiffness with Coulomb cap (G* of the materials)", kMindlinParams};

struct TangentialMindlin {
  static constexpr const char* name = "mindlin";
  static constexpr const LawBlock* block = &kMindlinBlock;
  static constexpr bool kElastic = true;  // G* from the materials' E and nu
  static constexpr const char* kNeedsNormal = NormalHertz::name;
  static constexpr const char* kNeedsWhy = "its damping and stiffness come from the Hertz contact";
  // The critical step linearises the law at its largest overlap (CriticalTimeStep.cpp sets k_s = S_t and
  // zeta_t = sqrt(5/6) |beta| there), so the spring is read as the coulomb one.
  static TangentialSpring spring(const ContactParams& p) { return {p.k_s, p.zeta_t}; }
  static constexpr bool kFriction = true;
  static constexpr std::array<const char*, 1> slots{"xi"};

  static double stiffness(const ContactParams& p, const ContactKinematics& k) {
    return 8.0 * p.G_star * std::sqrt(k.R_star * k.u_n);
  }
  static TangentialForce force(const ContactParams& p, const ContactBodies& b, const ContactKinematics& k, double F_n,
                               double dt, double* const* hist, std::size_t row) {
    double& xi = hist[0][row];
    xi += k.V_s * dt;
    const double S_t = stiffness(p, k);
    const double trial = -S_t * xi + NormalHertz::kDashpot * p.beta * std::sqrt(S_t * b.m_eff) * k.V_s;
    const double before = xi;
    const CapResult F = cap_spring_slider(trial, p.mu * F_n, S_t, xi);
    return {F.value, F.capped ? std::fabs(F.value * (before - xi)) : 0.0};
  }
  static double stored(const ContactParams& p, const ContactKinematics& k, double* const* hist, std::size_t row) {
    const double xi = hist[0][row];
    return 0.5 * stiffness(p, k) * xi * xi;
  }
};

}  // namespace rondel
