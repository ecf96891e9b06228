#pragma once
// Hertz normal law with the Tsuji-type dashpot (docs/physics.md section 6; Hertz 1882, Tsuji, Tanaka & Ishida
// 1992, Di Renzo & Di Maio 2004), the quasi-3D model of LIGGGHTS, EDEM and Lethe:
//   S_n = 2 E* sqrt(R* u_n)                                        (the current normal stiffness) [N/m]
//   F_n = max(0, 4/3 E* sqrt(R*) u_n^(3/2) + 2 sqrt(5/6) beta sqrt(S_n m_eff) v_n)   [N, per thickness]
//       = max(0, 2/3 S_n u_n - c_n v_n),  c_n = -2 sqrt(5/6) beta sqrt(S_n m_eff) >= 0 (beta <= 0)
//   stored energy 8/15 E* sqrt(R*) u_n^(5/2) = 4/15 S_n u_n^2
// E*, G* and beta = ln e/sqrt(ln^2 e + pi^2) are the pair's constants (PairConstants.hpp). The rolling
// laws that use k_n and c_n (jiang_*: K_m = k_n B^2/12, mu_m = c_n B^2/12) see this contact's S_n and c_n
// (linearised()); the critical step takes S_n at the largest overlap the run allows (run.max_overlap).
#include <array>
#include <cmath>

#include "core/ContactParams.hpp"
#include "core/LawSpec.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawTypes.hpp"

namespace rondel {

inline constexpr ParamSpec kHertzParams[] = {
    {"e", "-", Presence::required, 0.0, kRestitution,
     "restitution coefficient of the pair (Tsuji dashpot; 1 = undamped)", &ContactParams::e_n, 0.8},
};
inline constexpr LawBlock kHertzBlock{"hertz", "Hertz normal force with the Tsuji dashpot (E, nu of the materials)",
                                      kHertzParams};

struct NormalHertz {
  static constexpr const char* name = "hertz";
  static constexpr const LawBlock* block = &kHertzBlock;
  static constexpr bool kStiffening = true;
  static constexpr bool kElastic = true;                // E* from the materials' E and nu
  static constexpr std::array<const char*, 0> slots{};  // no history
  struct History {};
  // 2 sqrt(5/6): the Tsuji dashpot's factor.
  static constexpr double kDashpot = 1.8257418583505538;

  static double stiffness(const ContactParams& p, double R_star, double u_n) {
    return 2.0 * p.E_star * std::sqrt(R_star * u_n);
  }
  static double dashpot(const ContactParams& p, const ContactBodies& b, double S_n) {
    return -kDashpot * p.beta * std::sqrt(S_n * b.m_eff);
  }
  static NormalForce force(const ContactInput& in, History = {}) {
    const ContactKinematics& k = in.k;
    const double S_n = stiffness(in.p, k.R_star, k.u_n);
    const double f = (2.0 / 3.0) * S_n * k.u_n - dashpot(in.p, in.b, S_n) * k.v_n;
    return {f > 0.0 ? f : 0.0};
  }
  static double stored(const ContactInput& in, History = {}) {
    return (4.0 / 15.0) * stiffness(in.p, in.k.R_star, in.k.u_n) * in.k.u_n * in.k.u_n;
  }
  // The parameters with k_n and c_n of this contact now (for the rolling laws that use them, the critical step).
  static ContactParams linearised(const ContactInput& in) {
    ContactParams q = in.p;
    q.k_n = stiffness(in.p, in.k.R_star, in.k.u_n);
    q.c_n_fixed = dashpot(in.p, in.b, q.k_n);
    return q;
  }
};

}  // namespace rondel
