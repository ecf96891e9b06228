#pragma once
// jiang_brittle: Jiang, Yu & Harris 2005 (J05) Model 2, Eq. 36; docs/physics.md section 3.
// As jiang_plastic (B, K_m, mu_m, cap M0 = F_n B/6) while |theta_r| <= theta_r0 = 2 F_n/(k_n B), which is
// where the spring alone reaches M0 (K_m theta_r0 = M0). Once |theta_r| passes theta_r0 the contact breaks:
// M = 0 until the contact opens (then the history is zeroed). The stored rolling energy K_m theta_r^2/2 of
// the breaking step is released (booked as dissipation by the ledger).
// History slots: "theta_r" [rad], "broken" (0 or 1).
#include <array>
#include <cmath>

#include "physics/RollingJiangPlastic.hpp"

namespace rondel {

struct RollingJiangBrittle {
  static constexpr const char* name = "jiang_brittle";
  static constexpr const LawBlock* block = &kJiangBlock;
  static RollingSpring spring(const ContactParams& p, const ContactBodies& b, const ContactKinematics& k) {
    return RollingJiangPlastic::spring(p, b, k);
  }
  static constexpr bool kActive = true;
  static constexpr bool kBreaks = true;  // books the stored energy released at a break (E_r_break)
  static constexpr std::array<const char*, 2> slots{"theta_r", "broken"};

  static RollingCouple moment(const ContactParams& p, const ContactBodies& b, const ContactKinematics& k, double F_n,
                              double dt, double, double, double* const* hist, std::size_t row) {
    double& theta_r = hist[0][row];
    double& broken = hist[1][row];
    if (broken != 0.0) return {};
    const JiangGeometry g = jiang_geometry(p, b, k);
    const double before = theta_r;
    theta_r += k.thetadot_r * dt;
    const double theta_r0 = g.B > 0.0 ? 2.0 * F_n / (p.k_n * g.B) : 0.0;
    if (std::fabs(theta_r) > theta_r0) {
      broken = 1.0;
      RollingCouple c;
      c.released = 0.5 * g.K_m * before * before;
      theta_r = 0.0;
      return c;
    }
    return jiang_spring_slider(g, F_n, k.thetadot_r, dt, theta_r);
  }
  static double stored(const ContactParams& p, const ContactBodies& b, const ContactKinematics& k, double,
                       double* const* hist, std::size_t row) {
    const double th = hist[0][row];
    return 0.5 * jiang_geometry(p, b, k).K_m * th * th;
  }
  static double cap(const ContactParams& p, const ContactKinematics& k, double F_n) {
    return RollingJiangPlastic::cap(p, k, F_n);
  }
};

}  // namespace rondel
