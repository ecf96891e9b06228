#include "physics/CriticalTimeStep.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "physics/NormalLinear.hpp"

namespace rondel {

double mode_limit(double omega, double zeta) { return (2.0 / omega) * (std::sqrt(1.0 + zeta * zeta) - zeta); }

namespace {

struct Best {
  double dt = INFINITY;
  const char* mode = "";
  void consider(double limit, const char* name) {
    if (limit < dt) dt = limit, mode = name;
  }
};

}  // namespace

double contact_critical_step(const LawSelection& laws, const ContactParams& p, const ContactBody& a,
                             const ContactBody& b, std::string* mode) {
  const bool wall = std::isinf(b.m);
  const ContactBodies bodies = wall ? disc_wall_bodies(a.m, a.I) : disc_disc_bodies(a.m, b.m, a.I, b.I);
  const double m_eff = bodies.m_eff;
  Best best;
  const double w_n = std::sqrt(p.k_n / m_eff);
  best.consider(mode_limit(w_n, NormalLinear::c_n(p, bodies) / (2.0 * std::sqrt(m_eff * p.k_n))), "normal");

  // Tangential and rolling springs in the coordinates s (sliding) and theta_r (rolling): their modes are
  // the eigenvalues of diag(k_s, K) [[G, C], [C, H]] with G = 1/m_t = sum(1/m_i + R_i^2/I_i),
  // H = 1/I_red = sum(1/I_i) and C = R1/I1 - R2/I2 (a wall: R1/I1), in closed form below.
  double G = 1.0 / a.m + a.R * a.R / a.I, H = 1.0 / a.I, C = a.R / a.I;
  if (!wall) G += 1.0 / b.m + b.R * b.R / b.I, H += 1.0 / b.I, C -= b.R / b.I;
  double w2_t = 0.0, zeta_t = 0.0, k_s = 0.0;
  if (const auto spring = tangential_spring(laws, p)) {
    k_s = spring->k;
    w2_t = k_s * G;
    zeta_t = spring->zeta * std::sqrt(m_eff * G);
    best.consider(mode_limit(std::sqrt(w2_t), zeta_t), "tangential");
  }
  const RollingSpring roll =
      rolling_spring(laws, p, bodies, contact_geometry(a.R, b.R, wall)).value_or(RollingSpring{});
  if (roll.K > 0.0) {
    const double w2_r = roll.K * H;
    const double zeta_r = roll.C * std::sqrt(H / roll.K) / 2.0;
    if (w2_t > 0.0) {
      // Largest eigenvalue of the coupled pair. docs/physics.md's sum bound w2_t + w2_r is conservative but
      // falls to 0.77 of the limit for equal discs at delta = 3 (C = 0 decouples the modes there).
      const double half = 0.5 * (w2_t - w2_r);
      const double w2 = 0.5 * (w2_t + w2_r) + std::sqrt(half * half + k_s * roll.K * C * C);
      best.consider(mode_limit(std::sqrt(w2), std::max(zeta_t, zeta_r)), "tangential+rolling");
    } else {
      best.consider(mode_limit(std::sqrt(w2_r), zeta_r), "rolling");
    }
  }
  if (mode) *mode = best.mode;
  return best.dt;
}

CriticalStep critical_time_step(const LawSelection& laws, const ContactParamTable& params,
                                const std::vector<MaterialInfo>& materials, bool has_walls) {
  CriticalStep best{INFINITY, "", ""};
  auto radii = [](const MaterialInfo& m) {
    std::vector<double> out{m.R_min};
    constexpr int kSamples = 8;
    for (int s = 1; s <= kSamples && m.R_max > m.R_min; ++s)
      out.push_back(m.R_min * std::pow(m.R_max / m.R_min, static_cast<double>(s) / kSamples));
    return out;
  };
  auto body = [](const MaterialInfo& mat, double R) {
    const double m = mat.density * std::numbers::pi * R * R * mat.thickness;
    return ContactBody{m, 0.5 * m * R * R, R};
  };
  auto label = [](std::size_t index, double R) {
    std::ostringstream s;
    s << "material " << index << " R=" << R;
    return s.str();
  };
  const ContactBody wall{INFINITY, INFINITY, INFINITY};
  for (std::size_t a = 0; a < materials.size(); ++a) {
    if (materials[a].R_max <= 0.0) continue;  // no disc of this material in the scene
    for (double Ra : radii(materials[a])) {
      const ContactBody A = body(materials[a], Ra);
      std::string mode;
      if (has_walls) {
        const double dt = contact_critical_step(laws, params.wall(a), A, wall, &mode);
        if (dt < best.dt) best = {dt, mode, label(a, Ra) + " / wall"};
      }
      for (std::size_t b = 0; b < materials.size(); ++b) {
        if (materials[b].R_max <= 0.0) continue;
        for (double Rb : radii(materials[b])) {
          const double dt = contact_critical_step(laws, params.pair(a, b), A, body(materials[b], Rb), &mode);
          if (dt < best.dt) best = {dt, mode, label(a, Ra) + " / " + label(b, Rb)};
        }
      }
    }
  }
  return best;
}

}  // namespace rondel
