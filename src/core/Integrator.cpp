#include "core/Integrator.hpp"

#include <algorithm>
#include <cmath>

namespace rondel {

namespace {

template <bool kBounds>
Integrator::Drift drift_pass(DiscStore& discs, const Domain& domain, double dt, const BodyForce& body) {
  const double h = 0.5 * dt;
  const std::size_t n = discs.n_owned();
  // Local copies and plain pointers: a store to a disc cannot make the compiler reload them.
  const Domain box = domain;
  const Vec2 gravity = body.gravity;
  const std::uint32_t* const flags = discs.flags.data();
  const double *const mass = discs.mass.data(), *const inertia = discs.inertia.data();
  Vec2* const force = discs.force.data();
  double* const torque = discs.torque.data();
  Vec2 *const position = discs.position.data(), *const velocity = discs.velocity.data();
  double *const omega = discs.omega.data(), *const theta = discs.theta.data();
  double W_g = 0.0, step2 = 0.0, v2 = 0.0, a2 = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!(flags[i] & kFlagFixed)) {
      const double m = mass[i];
      if constexpr (kBounds) {
        const Vec2 a = (1.0 / m) * force[i];
        a2 = std::max(a2, dot(a, a));
      }
      Vec2& v = velocity[i];
      v.x += h * force[i].x / m;
      v.y += h * force[i].y / m;
      omega[i] += h * torque[i] / inertia[i];
      if constexpr (kBounds) v2 = std::max(v2, dot(v, v));
      const Vec2 dx = dt * v;
      step2 = std::max(step2, dot(dx, dx));
      position[i] += dx;
      theta[i] += dt * omega[i];
      box.wrap(position[i]);
      W_g += m * dot(gravity, dx);
      force[i] = body.on(m, flags[i]);
      torque[i] = 0.0;
    }
  }
  return {W_g, std::sqrt(step2), std::sqrt(v2), std::sqrt(a2)};
}

}  // namespace

Integrator::Drift Integrator::half_kick_drift(DiscStore& discs, const Domain& domain, double dt, const BodyForce& body,
                                              bool bounds) {
  return bounds ? drift_pass<true>(discs, domain, dt, body) : drift_pass<false>(discs, domain, dt, body);
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
