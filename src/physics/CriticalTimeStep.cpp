#include "physics/CriticalTimeStep.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "physics/NormalLinear.hpp"

namespace rondel {

double mode_limit(double omega, double zeta) {
  return (2.0 / omega) * (std::sqrt(1.0 + zeta * zeta) - zeta);
}

namespace {

struct Body {
  double m, I, R;  // a wall: m = I = R = inf
  std::string label;
};

Body disc_body(const MaterialInfo& mat, std::size_t index, double R) {
  const double m = mat.density * std::numbers::pi * R * R * mat.thickness;
  std::ostringstream s;
  s << "material " << index << " R=" << R;
  return {m, 0.5 * m * R * R, R, s.str()};
}

void consider(CriticalStep& best, double dt, const char* mode, const Body& a, const Body& b) {
  if (dt < best.dt) best = {dt, mode, a.label + " / " + b.label};
}

void pair_limits(CriticalStep& best, const LawSelection& laws, const ContactParams& p, const Body& a,
                 const Body& b) {
  const bool wall = std::isinf(b.m);
  const double m_eff = wall ? a.m : a.m * b.m / (a.m + b.m);
  const ContactBodies bodies = wall ? disc_wall_bodies(a.m, a.I) : disc_disc_bodies(a.m, b.m, a.I, b.I);
  const double w_n = std::sqrt(p.k_n / m_eff);
  const double zeta_n = NormalLinear::c_n(p, bodies) / (2.0 * std::sqrt(m_eff * p.k_n));
  consider(best, mode_limit(w_n, zeta_n), "normal", a, b);
  if (laws.tangential == TangentialLaw::coulomb) {
    double inv_mt = 1.0 / a.m + a.R * a.R / a.I;
    if (!wall) inv_mt += 1.0 / b.m + b.R * b.R / b.I;
    const double m_t = 1.0 / inv_mt;
    const double w_t = std::sqrt(p.k_s / m_t);
    const double zeta_t = p.zeta_t * std::sqrt(m_eff / m_t);
    consider(best, mode_limit(w_t, zeta_t), "tangential", a, b);
  }
}

}  // namespace

CriticalStep critical_time_step(const LawSelection& laws, const ContactParamTable& params,
                                const std::vector<MaterialInfo>& materials, bool has_walls) {
  CriticalStep best{INFINITY, "", ""};
  const Body wall{INFINITY, INFINITY, INFINITY, "wall"};
  for (std::size_t a = 0; a < materials.size(); ++a) {
    if (materials[a].R_max <= 0.0) continue;  // no disc of this material in the scene
    for (double Ra : {materials[a].R_min, materials[a].R_max}) {
      const Body A = disc_body(materials[a], a, Ra);
      if (has_walls) pair_limits(best, laws, params.wall(a), A, wall);
      for (std::size_t b = 0; b < materials.size(); ++b) {
        if (materials[b].R_max <= 0.0) continue;
        for (double Rb : {materials[b].R_min, materials[b].R_max})
          pair_limits(best, laws, params.pair(a, b), A, disc_body(materials[b], b, Rb));
      }
    }
  }
  return best;
}

}  // namespace rondel
