#pragma once
#include "core/DiscStore.hpp"
#include "core/Domain.hpp"
#include "core/Vec2.hpp"

namespace rondel {

// Velocity Verlet for translation and rotation (docs/design.md section 4, steps 1 and 7). The drift uses the
// half-step velocities, which are also the velocities the springs and the ledger see.
struct Integrator {
  // v += F/m dt/2; omega += T/I dt/2; x += v dt; theta += omega dt; wrap. Returns the work of gravity
  // over the drift, sum m g.(x_new - x_old) (exact: gravity is constant); it is booked here because the
  // drift alone knows each disc's displacement before migration reorders the discs.
  static double half_kick_drift(DiscStore& discs, const Domain& domain, double dt, Vec2 gravity);
  // v += F/m dt/2; omega += T/I dt/2.
  static void half_kick(DiscStore& discs, double dt);
};

}  // namespace rondel
