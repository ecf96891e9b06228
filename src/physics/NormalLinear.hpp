#pragma once
// Linear spring-dashpot normal law without tension (PHYSICS.md section 2):
//   F_n = max(0, k_n u_n - c_n v_n),  c_n = 2 zeta sqrt(m_eff k_n)  (or a user-given c_n) [N, per thickness]
// Damping ratio and restitution are related by VALIDATION.md section 4 (see Restitution.hpp).
#include <cmath>

#include "core/ContactParams.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawTypes.hpp"

namespace rondel {

struct NormalLinear {
  static constexpr const char* name = "linear";
  static double c_n(const ContactParams& p, const ContactBodies& b) {
    return p.c_n_fixed >= 0.0 ? p.c_n_fixed : 2.0 * p.zeta_n * std::sqrt(b.m_eff * p.k_n);
  }
  static double force(const ContactParams& p, const ContactBodies& b, const ContactKinematics& k) {
    const double f = p.k_n * k.u_n - c_n(p, b) * k.v_n;
    return f > 0.0 ? f : 0.0;
  }
};

}  // namespace rondel
