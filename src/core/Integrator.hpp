#pragma once
#include "core/BodyForce.hpp"
#include "core/DiscStore.hpp"
#include "core/Domain.hpp"
#include "core/Vec2.hpp"

namespace rondel {

// Velocity Verlet for translation and rotation (docs/design.md section 4, steps 1 and 7). The drift uses the
// half-step velocities, which are also the velocities the springs and the ledger see.
//
// Local damping (run.local_damping = alpha > 0; docs/physics.md section 9): in each half kick every
// component of a free disc's force and its torque is replaced by F_i - alpha |F_i| sign(v_i) (T - alpha |T|
// sign(omega)), with the velocity at the start of that kick: the full-step velocity in the first kick (the
// drift's), the half-step velocity in the second. sign(0) = 0: a component at rest is not damped. The stored
// forces stay the undamped sums (the checkpoint, the snapshots and the wall loads see those). Each kick
// returns the work the damping took, sum h (F_i - F_i,damped) (v_i + v_i')/2 (v' after the kick): the kick's
// kinetic energy change is exactly h F_damped (v + v')/2, so this booking leaves the ledger's balance as it
// is without damping. With alpha = 0 the kicks are the undamped ones, operation for operation.
struct Integrator {
  struct Drift {
    double W_g = 0.0;        // work of gravity over the drift
    double max_step = 0.0;   // largest displacement |x_new - x_old| of a free disc in this drift (in a deforming
                             // cell apart from the mean flow's: |v - L (x_old - x0)| dt)
    double max_speed = 0.0;  // with `bounds`: largest |v| of a free disc after the half kick (|v - L (x - x0)|)
    double max_accel = 0.0;  // with `bounds`: largest |F/m| of a free disc, of the (damped) force it used
    double D_damping = 0.0;  // work the local damping took in the half kick (0 without damping)
    double D_close = 0.0;    // with `close_last`: the same for the last step's closing kick
    double W_cell = 0.0;     // a moving cell: the kinetic energy its wraps changed (a velocity shifted by da/dt, db/dt)
  };
  // One pass over the owned discs, the first half of the step:
  //  - the half kick and drift of every free disc: v += F/m dt/2; omega += T/I dt/2; x += v dt;
  //    theta += omega dt; wrap (fixed discs do not move here); the kick damped when `damping` > 0;
  //  - the work of gravity over the drift, sum m g.(x_new - x_old) (exact: gravity is constant; booked here
  //    because the drift alone knows each disc's displacement before migration reorders the discs);
  //  - the largest displacement of a free disc in this drift, |v| dt (NeighbourList::displacement bounds the
  //    displacement since the last build with it);
  //  - with `bounds`, the largest speed and acceleration of the free discs (the motion bound of the spaced
  //    displacement checks, docs/scaling.md);
  //  - the start of each free disc's next force sum, the body force (ForceAssembly::begin does the same for
  //    every disc; the fixed discs and ghosts are left to ForceAssembly::begin_fixed_and_ghosts), once the
  //    kick has used the force.
  // With `close_last`, the pass first gives each free disc the last step's closing kick (half_kick, which was
  // deferred: nothing read the full-step velocities in between), then the kick above: the same operations, in
  // the same order, as half_kick followed by this pass, in one pass over the discs instead of two.
  static Drift half_kick_drift(DiscStore& discs, const Domain& domain, double dt, const BodyForce& body, bool bounds,
                               double damping = 0.0, bool close_last = false);
  // v += F/m dt/2; omega += T/I dt/2 (damped when `damping` > 0). Returns the work the damping took.
  static double half_kick(DiscStore& discs, double dt, double damping = 0.0);
};

}  // namespace rondel
