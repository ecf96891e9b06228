#pragma once
#include <vector>

#include "core/DiscStore.hpp"
#include "core/Domain.hpp"
#include "core/Vec2.hpp"

namespace rondel {

// Velocity Verlet for translation and rotation (docs/design.md section 4, steps 1 and 7). The drift uses the
// half-step velocities, which are also the velocities the springs and the ledger see.
struct Integrator {
  struct Drift {
    double W_g = 0.0;               // work of gravity over the drift
    double max_displacement = 0.0;  // largest displacement of an owned disc since the reference positions
  };
  // v += F/m dt/2; omega += T/I dt/2; x += v dt; theta += omega dt; wrap (fixed discs do not move here).
  // Returns the work of gravity over the drift, sum m g.(x_new - x_old) (exact: gravity is constant; it is
  // booked here because the drift alone knows each disc's displacement before migration reorders the
  // discs), and, in the same pass, the largest minimum-image displacement of an owned disc (fixed ones
  // included) from `since`, the positions at the last neighbour build (NeighbourList::max_displacement's
  // value; infinite when `since` does not hold one position per owned disc).
  static Drift half_kick_drift(DiscStore& discs, const Domain& domain, double dt, Vec2 gravity,
                               const std::vector<Vec2>& since);
  // v += F/m dt/2; omega += T/I dt/2.
  static void half_kick(DiscStore& discs, double dt);
};

}  // namespace rondel
