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

// One half kick of a free disc (the arithmetic of both kicks of the step); adds the work the damping took to
// D, component by component.
template <bool kDamp>
inline void kick(Vec2& v, double& omega, Vec2 force, double torque, double m, double inertia, double h, double alpha,
                 double& D) {
  if constexpr (kDamp) {
    D += damped_kick(v.x, force.x, m, h, alpha);
    D += damped_kick(v.y, force.y, m, h, alpha);
    D += damped_kick(omega, torque, inertia, h, alpha);
  } else {
    v.x += h * force.x / m;
    v.y += h * force.y / m;
    omega += h * torque / inertia;
  }
}

// kMoving: a moving cell (its wrap shifts velocities; the motion bounds are apart from the mean flow). The
// standing box's pass is compiled without it.
template <bool kBounds, bool kDamp, bool kClose, bool kMoving>
Integrator::Drift drift_pass(DiscStore& discs, const Domain& domain, double dt, const BodyForce& body, double alpha) {
  const double h = 0.5 * dt;
  const std::size_t n = discs.n_owned();
  // Local copies and plain pointers: a store to a disc cannot make the compiler reload them.
  const Domain box = domain;
  const bool standing = box.standing();  // the plain wrap, decided once for the pass
  const Vec2 gravity = body.gravity;
  const std::uint32_t* const flags = discs.flags.data();
  const double *const mass = discs.mass.data(), *const inertia = discs.inertia.data();
  Vec2* const force = discs.force.data();
  double* const torque = discs.torque.data();
  Vec2 *const position = discs.position.data(), *const velocity = discs.velocity.data();
  double *const omega = discs.omega.data(), *const theta = discs.theta.data();
  double W_g = 0.0, step2 = 0.0, v2 = 0.0, a2 = 0.0, D = 0.0, D_close = 0.0, W_cell = 0.0, u2 = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!(flags[i] & kFlagFixed)) {
      const double m = mass[i];
      Vec2& v = velocity[i];
      // The last step's closing kick, deferred to this pass (the same arithmetic as half_kick; its damping
      // work summed apart, in disc order, as half_kick sums it).
      if constexpr (kClose) kick<kDamp>(v, omega[i], force[i], torque[i], m, inertia[i], h, alpha, D_close);
      if constexpr (kBounds) {
        const Vec2 a = kDamp ? (1.0 / m) * Vec2{damped(force[i].x, v.x, alpha), damped(force[i].y, v.y, alpha)}
                             : (1.0 / m) * force[i];
        a2 = std::max(a2, dot(a, a));
      }
      kick<kDamp>(v, omega[i], force[i], torque[i], m, inertia[i], h, alpha, D);
      const Vec2 dx = dt * v;
      if constexpr (kMoving) {  // a deforming cell: the speed apart from the mean flow's (NeighbourList)
        const Vec2 u = v - box.flow(position[i]);
        u2 = std::max(u2, dot(u, u));
      } else {
        if constexpr (kBounds) v2 = std::max(v2, dot(v, v));
        step2 = std::max(step2, dot(dx, dx));
      }
      position[i] += dx;
      theta[i] += dt * omega[i];
      if constexpr (kMoving) {
        // A moving cell shifts the velocity too (Lees-Edwards): the kinetic energy that changes is the cell's work.
        box.wrap_moving(position[i], v, m, W_cell);
      } else if (standing) {
        box.wrap_standing(position[i]);
      } else {
        box.wrap(position[i]);  // a tilted cell that stands still: no velocity to shift
      }
      W_g += m * dot(gravity, dx);
      force[i] = body.on(m, flags[i]);
      torque[i] = 0.0;
    }
  }
  if constexpr (kMoving) {  // the step and speed bounds from the largest speed apart from the flow
    step2 = dt * dt * u2;
    if constexpr (kBounds) v2 = u2;
  }
  return {W_g, std::sqrt(step2), std::sqrt(v2), std::sqrt(a2), D, D_close, W_cell};
}

template <bool kClose, bool kMoving>
Integrator::Drift drift_of(DiscStore& discs, const Domain& domain, double dt, const BodyForce& body, bool bounds,
                           double damping) {
  if (damping > 0.0)
    return bounds ? drift_pass<true, true, kClose, kMoving>(discs, domain, dt, body, damping)
                  : drift_pass<false, true, kClose, kMoving>(discs, domain, dt, body, damping);
  return bounds ? drift_pass<true, false, kClose, kMoving>(discs, domain, dt, body, 0.0)
                : drift_pass<false, false, kClose, kMoving>(discs, domain, dt, body, 0.0);
}

}  // namespace

Integrator::Drift Integrator::half_kick_drift(DiscStore& discs, const Domain& domain, double dt, const BodyForce& body,
                                              bool bounds, double damping, bool close_last) {
  if (domain.moving)
    return close_last ? drift_of<true, true>(discs, domain, dt, body, bounds, damping)
                      : drift_of<false, true>(discs, domain, dt, body, bounds, damping);
  return close_last ? drift_of<true, false>(discs, domain, dt, body, bounds, damping)
                    : drift_of<false, false>(discs, domain, dt, body, bounds, damping);
}

double Integrator::half_kick(DiscStore& discs, double dt, double damping) {
  const double h = 0.5 * dt;
  const std::uint32_t* const flags = discs.flags.data();
  const double *const mass = discs.mass.data(), *const inertia = discs.inertia.data();
  const Vec2* const force = discs.force.data();
  const double* const torque = discs.torque.data();
  Vec2* const velocity = discs.velocity.data();
  double* const omega = discs.omega.data();
  double D = 0.0;
  const std::size_t n = discs.n_owned();
  if (damping > 0.0) {
    for (std::size_t i = 0; i < n; ++i)
      if (!(flags[i] & kFlagFixed))
        kick<true>(velocity[i], omega[i], force[i], torque[i], mass[i], inertia[i], h, damping, D);
    return D;
  }
  for (std::size_t i = 0; i < n; ++i)
    if (!(flags[i] & kFlagFixed))
      kick<false>(velocity[i], omega[i], force[i], torque[i], mass[i], inertia[i], h, 0.0, D);
  return 0.0;
}

}  // namespace rondel
