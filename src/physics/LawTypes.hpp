#pragma once
// What a contact law sees (ContactInput: its parameters, the two bodies, the kinematics, the normal force, the time
// step and the spins) and what it returns. Laws are stateless functions of a ContactInput and of their History, a
// struct of references to the row's history slots, one member per name of the law's `slots`, in that order.
#include <cmath>
#include <cstddef>
#include <utility>

#include "core/ContactParams.hpp"
#include "physics/ContactKinematics.hpp"

namespace rondel {

struct ContactBodies {
  double m1 = 0.0, m2 = 0.0, I1 = 0.0, I2 = 0.0;
  double m_eff = 0.0;  // m1 m2/(m1 + m2), = m1 at a wall
};

inline ContactBodies disc_disc_bodies(double m1, double m2, double I1, double I2) {
  return {m1, m2, I1, I2, m1 * m2 / (m1 + m2)};
}
inline ContactBodies disc_wall_bodies(double m1, double I1) { return {m1, INFINITY, I1, INFINITY, m1}; }

// One contact as a law sees it this step. The normal law reads p, b and k; the tangential and rolling laws also the
// normal force of this step; the rolling laws the spins and the last step's couple on disc 1 (a law that books its
// dissipation from the kernel's trapezoid work needs it: jiang_plastic).
struct ContactInput {
  const ContactParams& p;
  const ContactBodies& b;
  const ContactKinematics& k;
  double F_n = 0.0;      // [N]
  double dt = 0.0;       // [s]; 0 for the forces of the initial state
  double w1 = 0.0;       // [rad/s]
  double w2 = 0.0;       // [rad/s]; a wall: its angular velocity Omega
  double M1_prev = 0.0;  // [N m]
};

// The History of one row from the law's N history columns: H{columns[0][row], ..., columns[N-1][row]}. A History
// with another number of members than the law's `slots` does not compile.
template <class H, std::size_t N>
H history_row(double* const* columns, std::size_t row) {
  return [&]<std::size_t... I>(std::index_sequence<I...>) { return H{columns[I][row]...}; }
  (std::make_index_sequence<N>{});
}

inline double sign(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }  // sign(0) = 0

// The capping rule of docs/physics.md section 1 for a spring-slider: given the trial value (spring + dashpot),
// returns the force (or couple) and resets the spring so that the spring alone equals it when capped.
// `spring` is the displacement-like state, `stiffness` its stiffness (value = -stiffness * spring + ...).
struct CapResult {
  double value;
  bool capped;
};
inline CapResult cap_spring_slider(double trial, double cap, double stiffness, double& spring) {
  if (std::fabs(trial) > cap) {
    const double value = cap * sign(trial);
    spring = -value / stiffness;
    return {value, true};
  }
  return {trial, false};
}

// Rolling couples on disc 1 and disc 2 (objective laws give M2 = -M1; force_proportional gives each disc
// its own couple from its own spin), with this step's energy terms for the ledger [J per thickness]:
// plastic work of a capped spring-slider, rolling dashpot work, stored energy released by a brittle break.
struct RollingCouple {
  double M1 = 0.0;
  double M2 = 0.0;
  double plastic = 0.0;
  double dashpot = 0.0;
  double released = 0.0;
  bool yielded = false;  // a spring-slider at its cap this step
};

// The normal force of a contact [N, >= 0], with the work its hysteresis dissipated this step (a law whose unloading
// is stiffer than its loading: walton_braun; 0 for the others).
struct NormalForce {
  double F_n = 0.0;
  double hysteresis = 0.0;
};

// Tangential force on disc 1 along t, with the work dissipated by Coulomb slip this step.
struct TangentialForce {
  double F_t = 0.0;
  double slip = 0.0;
};

// The springs a law contributes to the critical step (docs/physics.md section 4), for one contact before it
// moves. A law without an a-priori spring says so with a `no_spring` reason instead (see LawConcepts.hpp).
struct TangentialSpring {
  double k = 0.0;     // [N/m]
  double zeta = 0.0;  // damping ratio [-]
};
struct RollingSpring {
  double K = 0.0;  // rolling stiffness [N m/rad]
  double C = 0.0;  // rolling dashpot [N m s/rad]
};

}  // namespace rondel
