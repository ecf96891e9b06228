#include "core/Integrator.hpp"

#include <algorithm>
#include <cmath>

namespace rondel {

namespace {

// A component of a force (or a torque) under local damping: f - alpha |f| sign(v), sign(0) = 0.
inline double damped(double f, double v, double alpha) {
  return v > 0.0 ? f - alpha * std::fabs(f) : (v < 0.0 ? f + alpha * std::fabs(f) : f);
}

// A damped half kick of one velocity component v by the force component f on the mass (or inertia) m, as the
// undamped kick v += h f / m with f damped: returns the work the damping took, h (f - f_damped) (v + v')/2.
inline double damped_kick(double& v, double f, double m, double h, double alpha) {
  const double fd = damped(f, v, alpha);
  const double before = v;
  v += h * fd / m;
  return h * (f - fd) * (0.5 * (before + v));
}

template <bool kBounds, bool kDamp>
Integrator::Drift drift_pass(DiscStore& discs, const Domain& domain, double dt, const BodyForce& body, double alpha) {
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
  double W_g = 0.0, step2 = 0.0, v2 = 0.0, a2 = 0.0, D = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!(flags[i] & kFlagFixed)) {
      const double m = mass[i];
      Vec2& v = velocity[i];
      if constexpr (kDamp) {
        if constexpr (kBounds) {
          const Vec2 a = (1.0 / m) * Vec2{damped(force[i].x, v.x, alpha), damped(force[i].y, v.y, alpha)};
          a2 = std::max(a2, dot(a, a));
        }
        D += damped_kick(v.x, force[i].x, m, h, alpha);
        D += damped_kick(v.y, force[i].y, m, h, alpha);
        D += damped_kick(omega[i], torque[i], inertia[i], h, alpha);
      } else {
        if constexpr (kBounds) {
          const Vec2 a = (1.0 / m) * force[i];
          a2 = std::max(a2, dot(a, a));
        }
        v.x += h * force[i].x / m;
        v.y += h * force[i].y / m;
        omega[i] += h * torque[i] / inertia[i];
      }
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
  return {W_g, std::sqrt(step2), std::sqrt(v2), std::sqrt(a2), D};
}

}  // namespace

Integrator::Drift Integrator::half_kick_drift(DiscStore& discs, const Domain& domain, double dt, const BodyForce& body,
                                              bool bounds, double damping) {
  if (damping > 0.0)
    return bounds ? drift_pass<true, true>(discs, domain, dt, body, damping)
                  : drift_pass<false, true>(discs, domain, dt, body, damping);
  return bounds ? drift_pass<true, false>(discs, domain, dt, body, 0.0)
                : drift_pass<false, false>(discs, domain, dt, body, 0.0);
}

double Integrator::half_kick(DiscStore& discs, double dt, double damping) {
  const double h = 0.5 * dt;
  if (damping > 0.0) {
    double D = 0.0;
    for (std::size_t i = 0; i < discs.n_owned(); ++i) {
      if (discs.flags[i] & kFlagFixed) continue;
      const double m = discs.mass[i];
      D += damped_kick(discs.velocity[i].x, discs.force[i].x, m, h, damping);
      D += damped_kick(discs.velocity[i].y, discs.force[i].y, m, h, damping);
      D += damped_kick(discs.omega[i], discs.torque[i], discs.inertia[i], h, damping);
    }
    return D;
  }
  for (std::size_t i = 0; i < discs.n_owned(); ++i) {
    if (discs.flags[i] & kFlagFixed) continue;
    const double m = discs.mass[i];
    discs.velocity[i].x += h * discs.force[i].x / m;
    discs.velocity[i].y += h * discs.force[i].y / m;
    discs.omega[i] += h * discs.torque[i] / discs.inertia[i];
  }
  return 0.0;
}

}  // namespace rondel
