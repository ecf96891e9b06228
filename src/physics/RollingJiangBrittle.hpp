#pragma once
// jiang_brittle: Jiang, Yu & Harris 2005 (J05) Model 2, Eq. 36; docs/physics.md section 3.
// As jiang_plastic (B, K_m, mu_m, cap M0 = F_n B/6) while |theta_r| <= theta_r0 = 2 F_n/(k_n B), which is
// where the spring alone reaches M0 (K_m theta_r0 = M0). Once |theta_r| passes theta_r0 the contact breaks:
// M = 0 that step, and the energy the spring held is released (booked as dissipation by the ledger): the stored
// K_m theta_r^2/2 as the step found it, and what the couple took from the discs in the step's first half (the
// trapezoid's -M_prev thetadot_r dt/2, with M_prev the last step's couple), so that the ledger closes at every
// break, which reform repeats. Then jiang.after_break: reform (the default) restarts the spring from
// theta_r = 0 the next step, so a contact that keeps rolling breaks again and again (a sawtooth between 0 and
// M0: the crushed contact width re-forms); open keeps M = 0 until the contact opens (then the history is
// zeroed), the reading of earlier versions, kept for comparison (docs/biaxial.md: it gives no strength over
// none in the J05 test). History slots: "theta_r" [rad], "broken" (0 or 1; open only).
#include <array>
#include <cmath>

#include "physics/RollingJiangPlastic.hpp"

namespace rondel {

struct RollingJiangBrittle {
  static constexpr const char* name = "jiang_brittle";
  static constexpr const LawBlock* block = &kJiangBlock;
  static RollingSpring spring(const ContactInput& in) { return RollingJiangPlastic::spring(in); }
  static constexpr bool kActive = true;
  static constexpr bool kBreaks = true;  // books the stored energy released at a break (E_r_break)
  static constexpr std::array<const char*, 2> slots{"theta_r", "broken"};
  struct History {
    double& theta_r;  // [rad]
    double& broken;   // 0 or 1
  };

  static RollingCouple moment(const ContactInput& in, History h) {
    if (h.broken != 0.0) return {};
    const JiangGeometry g = jiang_geometry(in);
    const double before = h.theta_r;
    const double theta_r0 = g.B > 0.0 ? 2.0 * in.F_n / (in.p.k_n * g.B) : 0.0;
    if (std::fabs(before + in.k.thetadot_r * in.dt) > theta_r0) {
      if (in.p.after_break == kAfterBreakOpen) h.broken = 1.0;
      RollingCouple c;
      c.released = 0.5 * g.K_m * before * before - 0.5 * in.M1_prev * in.k.thetadot_r * in.dt;
      h.theta_r = 0.0;
      return c;
    }
    return jiang_step(in, g, h.theta_r);  // Model 1's step, with its exact ledger split
  }
  static double stored(const ContactInput& in, History h) {
    return 0.5 * jiang_geometry(in).K_m * h.theta_r * h.theta_r;
  }
  static double cap(const ContactInput& in) { return RollingJiangPlastic::cap(in); }
};

}  // namespace rondel
