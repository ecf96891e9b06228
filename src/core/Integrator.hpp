#pragma once
#include "core/BodyForce.hpp"
#include "core/DiscStore.hpp"
#include "core/Domain.hpp"
#include "core/Vec2.hpp"

namespace rondel {

// Velocity Verlet for translation and rotation (docs/design.md section 4, steps 1 and 7). The drift uses the
// half-step velocities, which are also the velocities the springs and the ledger see.
struct Integrator {
  struct Drift {
    double W_g = 0.0;        // work of gravity over the drift
    double max_step = 0.0;   // largest displacement |x_new - x_old| of a free disc in this drift
    double max_speed = 0.0;  // with `bounds`: largest |v| of a free disc after the half kick
    double max_accel = 0.0;  // with `bounds`: largest |F/m| of a free disc, of the force it used
  };
  // One pass over the owned discs, the first half of the step:
  //  - the half kick and drift of every free disc: v += F/m dt/2; omega += T/I dt/2; x += v dt;
  //    theta += omega dt; wrap (fixed discs do not move here);
  //  - the work of gravity over the drift, sum m g.(x_new - x_old) (exact: gravity is constant; booked here
  //    because the drift alone knows each disc's displacement before migration reorders the discs);
  //  - the largest displacement of a free disc in this drift, |v| dt (NeighbourList::displacement bounds the
  //    displacement since the last build with it);
  //  - with `bounds`, the largest speed and acceleration of the free discs (the motion bound of the spaced
  //    displacement checks, docs/scaling.md);
  //  - the start of each free disc's next force sum, the body force (ForceAssembly::begin does the same for
  //    every disc; the fixed discs and ghosts are left to ForceAssembly::begin_fixed_and_ghosts), once the
  //    kick has used the force.
  static Drift half_kick_drift(DiscStore& discs, const Domain& domain, double dt, const BodyForce& body, bool bounds);
  // v += F/m dt/2; omega += T/I dt/2.
  static void half_kick(DiscStore& discs, double dt);
};

}  // namespace rondel
