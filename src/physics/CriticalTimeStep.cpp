#include "physics/CriticalTimeStep.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "physics/BondParallel.hpp"
#include "physics/NormalLinear.hpp"

namespace rondel {

double mode_limit(double omega, double zeta) {
  // sqrt(1 + zeta^2) - zeta = 1 / (sqrt(1 + zeta^2) + zeta): the second form for a huge damping (the first
  // cancels to 0, or overflows), the first below (the form docs/physics.md writes, rounded as it is).
  if (zeta > 1e3) return (2.0 / omega) / (std::hypot(1.0, zeta) + zeta);
  return (2.0 / omega) * (std::sqrt(1.0 + zeta * zeta) - zeta);
}

namespace {

struct Best {
  double dt = INFINITY;
  const char* mode = "";
  // A NaN limit (a parameter too large or too small for double precision) is kept: the set-up refuses it.
  void consider(double limit, const char* name) {
    if (!std::isnan(dt) && (std::isnan(limit) || limit < dt)) dt = limit, mode = name;
  }
};

}  // namespace

double contact_critical_step(const LawSelection& laws, const ContactParams& p_in, const ContactBody& a,
                             const ContactBody& b, std::string* mode, double max_overlap, double thickness) {
  const bool wall = std::isinf(b.m);
  const ContactBodies bodies = wall ? disc_wall_bodies(a.m, a.I) : disc_disc_bodies(a.m, b.m, a.I, b.I);
  const double m_eff = bodies.m_eff;
  // A contact that stiffens with overlap (hertz, mindlin) as the spring-dashpot it is at the largest overlap the
  // run allows (docs/physics.md section 6).
  ContactKinematics at_limit = contact_geometry(a.R, b.R, wall);
  if (normal_law(laws).stiffening) at_limit.u_n = max_overlap * (wall ? a.R : std::min(a.R, b.R));
  const ContactParams p = linearised(laws, ContactInput{p_in, bodies, at_limit});
  Best best;
  // A bond's springs beside the contact's (zero unbonded): normal kb_n A, shear kb_s A, rotation kb_n I.
  const bool bonded = !wall && thickness > 0.0 && p_in.kb_n > 0.0;
  const BondGeometry g = bonded ? BondGeometry::of(a.R, b.R, thickness, p_in.bond_lambda) : BondGeometry{};
  const double kb_n = p_in.kb_n * g.A, kb_s = p_in.kb_s * g.A, Kb = p_in.kb_n * g.I;
  // The normal mode with the law's stiffest spring (walton_braun: its unloading stiffness K2).
  const ContactParams q = stiffest_normal(laws, ContactInput{p_in, bodies, at_limit});
  const double k_n = q.k_n + kb_n;
  const double w_n = std::sqrt(k_n / m_eff);
  best.consider(mode_limit(w_n, NormalLinear::c_n(q, bodies) / (2.0 * std::sqrt(m_eff * k_n))),
                bonded ? "normal + bond" : "normal");

  // Tangential and rolling springs in the coordinates s (sliding) and theta_r (rolling): their modes are
  // the eigenvalues of diag(k_s, K) [[G, C], [C, H]] with G = 1/m_t = sum(1/m_i + R_i^2/I_i),
  // H = 1/I_red = sum(1/I_i) and C = R1/I1 - R2/I2 (a wall: R1/I1), in closed form below.
  double G = 1.0 / a.m + a.R * a.R / a.I, H = 1.0 / a.I, C = a.R / a.I;
  if (!wall) G += 1.0 / b.m + b.R * b.R / b.I, H += 1.0 / b.I, C -= b.R / b.I;
  double w2_t = 0.0, zeta_t = 0.0, k_s = kb_s;
  const auto spring = tangential_spring(laws, p);
  if (spring) k_s += spring->k, zeta_t = spring->zeta * std::sqrt(m_eff * G) * std::sqrt(spring->k / k_s);
  if (k_s > 0.0) {
    w2_t = k_s * G;
    best.consider(mode_limit(std::sqrt(w2_t), zeta_t), bonded ? "tangential + bond" : "tangential");
  }
  RollingSpring roll = rolling_spring(laws, p, bodies, at_limit).value_or(RollingSpring{});
  roll.K += Kb;
  if (roll.K > 0.0) {
    const double w2_r = roll.K * H;
    const double zeta_r = roll.C * std::sqrt(H / roll.K) / 2.0;
    if (w2_t > 0.0) {
      // Largest eigenvalue of the coupled pair. docs/physics.md's sum bound w2_t + w2_r is conservative but
      // falls to 0.77 of the limit for equal discs at delta = 3 (C = 0 decouples the modes there).
      const double half = 0.5 * (w2_t - w2_r);
      const double w2 = 0.5 * (w2_t + w2_r) + std::sqrt(half * half + k_s * roll.K * C * C);
      best.consider(mode_limit(std::sqrt(w2), std::max(zeta_t, zeta_r)),
                    bonded ? "tangential+rolling + bond" : "tangential+rolling");
    } else {
      best.consider(mode_limit(std::sqrt(w2_r), zeta_r), bonded ? "rolling + bond" : "rolling");
    }
  }
  if (mode) *mode = best.mode;
  return best.dt;
}

CriticalStep critical_time_step(const LawSelection& laws, const ContactParamTable& params,
                                const std::vector<MaterialInfo>& materials, bool has_walls,
                                const CriticalOptions& options) {
  CriticalStep best{INFINITY, "", ""};
  auto radii = [](const MaterialInfo& m) {
    std::vector<double> out{m.R_min};
    constexpr int kSamples = 8;
    for (int s = 1; s <= kSamples && m.R_max > m.R_min; ++s)
      out.push_back(m.R_min * std::pow(m.R_max / m.R_min, static_cast<double>(s) / kSamples));
    return out;
  };
  auto body = [](const MaterialInfo& mat, double R) {
    Material m;
    m.density = mat.density, m.thickness = mat.thickness, m.body = mat.body;
    const double mass = m.mass(R);
    return ContactBody{mass, m.inertia(mass, R), R};
  };
  auto label = [&materials](std::size_t index, double R) {
    std::ostringstream s;
    s << "material " << (materials[index].name.empty() ? std::to_string(index) : materials[index].name) << " R=" << R;
    return s.str();
  };
  const ContactBody wall{INFINITY, INFINITY, INFINITY};
  const double u = options.max_overlap;
  for (std::size_t a = 0; a < materials.size(); ++a) {
    if (materials[a].R_max <= 0.0) continue;  // no disc of this material in the scene
    for (double Ra : radii(materials[a])) {
      const ContactBody A = body(materials[a], Ra);
      std::string mode;
      for (int w : has_walls ? options.wall_materials : std::vector<int>{}) {
        const double dt = contact_critical_step(laws, params.wall(a, static_cast<std::size_t>(w)), A, wall, &mode, u);
        if (!std::isnan(best.dt) && !(dt >= best.dt)) best = {dt, mode, label(a, Ra) + " / wall", 0.0};
      }
      for (std::size_t b = 0; b < materials.size(); ++b) {
        if (materials[b].R_max <= 0.0) continue;
        for (double Rb : radii(materials[b])) {
          const double dt = contact_critical_step(laws, params.pair(a, b), A, body(materials[b], Rb), &mode, u,
                                                  materials[a].thickness);
          if (!std::isnan(best.dt) && !(dt >= best.dt)) best = {dt, mode, label(a, Ra) + " / " + label(b, Rb), 0.0};
        }
      }
    }
  }
  if (normal_law(laws).elastic) {
    // The Rayleigh step of the smallest disc, which the commercial codes and LIGGGHTS users quote.
    best.rayleigh = INFINITY;
    for (const MaterialInfo& m : materials) {
      if (m.R_max <= 0.0 || m.youngs_modulus <= 0.0) continue;
      const double G = m.youngs_modulus / (2.0 * (1.0 + m.poisson_ratio));
      best.rayleigh = std::min(
          best.rayleigh, std::numbers::pi * m.R_min * std::sqrt(m.density / G) / (0.1631 * m.poisson_ratio + 0.8766));
    }
    std::ostringstream s;
    s.precision(6);
    s << "; Hertz-Mindlin stiffness at u_n = " << u << " of the smaller radius (run.max_overlap); Rayleigh step "
      << best.rayleigh << " s";
    best.pair += s.str();
  }
  return best;
}

}  // namespace rondel
