#include "core/Integrator.hpp"

namespace rondel {

double Integrator::half_kick_drift(DiscStore& discs, const Domain& domain, double dt, Vec2 gravity) {
  const double h = 0.5 * dt;
  double W_g = 0.0;
  for (std::size_t i = 0; i < discs.n_owned(); ++i) {
    if (discs.flags[i] & kFlagFixed) continue;
    const double m = discs.mass[i];
    Vec2& v = discs.velocity[i];
    v.x += h * discs.force[i].x / m;
    v.y += h * discs.force[i].y / m;
    discs.omega[i] += h * discs.torque[i] / discs.inertia[i];
    const Vec2 dx = dt * v;
    discs.position[i] += dx;
    discs.theta[i] += dt * discs.omega[i];
    domain.wrap(discs.position[i]);
    W_g += m * dot(gravity, dx);
  }
  return W_g;
}

void Integrator::half_kick(DiscStore& discs, double dt) {
  const double h = 0.5 * dt;
  for (std::size_t i = 0; i < discs.n_owned(); ++i) {
    if (discs.flags[i] & kFlagFixed) continue;
    const double m = discs.mass[i];
    discs.velocity[i].x += h * discs.force[i].x / m;
    discs.velocity[i].y += h * discs.force[i].y / m;
    discs.omega[i] += h * discs.torque[i] / discs.inertia[i];
  }
}

}  // namespace rondel
