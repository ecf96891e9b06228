#pragma once
// iwashita_oda: Iwashita & Oda 1998 (IO98) as summarised in J05 Table 1; docs/physics.md section 3. Legacy
// rolling measure kept on purpose for comparison studies: it is zero in rigid rotation but not in pure
// sliding of unequal discs (it gives (R1 - R2) omega T/2 where W15 gives 0, docs/validation.md case K8).
//   r' = (R1 + R2)/2;  dbeta = turn of the contact direction = -V_t dt/|d| (W15 Eqs. 17, 19a)
//   da = R1 (dtheta1 - dbeta),  db = R2 (dtheta2 - dbeta),  dU_r = (da - db)/2,  theta_r += dU_r/r'
//   at a wall (no wall limit exists, J05 section 2.2): theta_r += (omega1 - omega_wall) dt
//   trial M = -K_r theta_r - C_r dtheta_r/dt, capped at eta F_n by the capping rule.
// Parameters K_r [N m/rad], C_r [N m s/rad], eta [m]. History slot: "theta_r" [rad].
#include <array>
#include <cmath>

#include "core/ContactParams.hpp"
#include "core/LawSpec.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawTypes.hpp"

namespace rondel {

// Rate of the legacy rolling angle, dtheta_r/dt.
inline double iwashita_oda_rate(const ContactKinematics& k, double w1, double w2) {
  if (k.wall) return k.thetadot_r;  // w1 - omega_wall
  const double dbeta = -k.V_t / k.dist;
  const double da = k.R1 * (w1 - dbeta), db = k.R2 * (w2 - dbeta);
  return 0.5 * (da - db) / (0.5 * (k.R1 + k.R2));
}

inline constexpr ParamSpec kIwashitaOdaParams[] = {
    {"K_r", "N m/rad", Presence::required, 0.0, kPositive, "rolling stiffness", &ContactParams::K_r, 0.75},
    {"C_r", "N m s/rad", Presence::required, 0.0, kNonNegative, "rolling dashpot", &ContactParams::C_r, 1e-4},
    {"eta", "m", Presence::required, 0.0, kNonNegative, "couple cap eta F_n", &ContactParams::eta, 5e-4},
};
inline constexpr LawBlock kIwashitaOdaBlock{
    "iwashita_oda", "Iwashita & Oda 1998 (legacy rolling measure, for comparison)", kIwashitaOdaParams};

struct RollingIwashitaOda {
  static constexpr const char* name = "iwashita_oda";
  static constexpr const LawBlock* block = &kIwashitaOdaBlock;
  static RollingSpring spring(const ContactInput& in) { return {in.p.K_r, in.p.C_r}; }
  static constexpr bool kActive = true;
  static constexpr const char* unsplit_work = "its legacy measure books no dissipation: the work is left unsplit";
  static constexpr std::array<const char*, 1> slots{"theta_r"};
  struct History {
    double& theta_r;  // [rad]
  };

  static RollingCouple moment(const ContactInput& in, History h) {
    const ContactParams& p = in.p;
    double& theta_r = h.theta_r;
    const double rate = iwashita_oda_rate(in.k, in.w1, in.w2);
    theta_r += rate * in.dt;
    const double trial = -p.K_r * theta_r - p.C_r * rate;
    const CapResult M = cap_spring_slider(trial, p.eta * in.F_n, p.K_r, theta_r);
    return {M.value, -M.value};
  }
  static double stored(const ContactInput& in, History h) { return 0.5 * in.p.K_r * h.theta_r * h.theta_r; }
  static double cap(const ContactInput& in) { return in.p.eta * in.F_n; }
};

}  // namespace rondel
