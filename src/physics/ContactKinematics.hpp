#pragma once
// Objective contact kinematics of Wang et al. 2015 (W15 Eqs. 11-13), written in the canonical frame of
// docs/physics.md section 1: disc 1 is the lower gid, n points from 1 to 2, t = z x n.
//   u_n = R1 + R2 - |d|,  a_i = R_i - u_n/2 (contact-point levers, a1 + a2 = |d|)
//   v_n = (v2 - v1).n,  V_t = (v1 - v2).t,  V_s = V_t + a1 w1 + a2 w2,
//   V_r = R* (w1 - w2), R* = R1 R2/(R1 + R2),  thetadot_r = w1 - w2.
// At a wall (disc 2, R2 -> inf): u_n = R1 - dist, R* -> R1, v2 is the velocity v_w of the wall's surface at the
// contact point p = x1 + a1 n and w2 its angular velocity Omega (0 unless it rotates, docs/physics.md section 8):
// V_t = (v1 - v_w).t, V_s = V_t + a1 w1 (the wall's a2 w2 term is its surface velocity, already in v_w) and
// thetadot_r = w1 - Omega. Velocities are the half-step ones of velocity Verlet (docs/physics.md section 1).
#include <cmath>

#include "core/Vec2.hpp"

namespace rondel {

struct ContactKinematics {
  Vec2 n, t;
  double dist = 0.0, u_n = 0.0;
  double R1 = 0.0, R2 = 0.0;  // R2 = +inf at a wall
  double a1 = 0.0, a2 = 0.0;  // a2 = +inf at a wall
  double R_star = 0.0;
  double v_n = 0.0, V_t = 0.0, V_s = 0.0, V_r = 0.0, thetadot_r = 0.0;
  bool wall = false;
};

// R* = R1 R2/(R1 + R2), the reduced radius of two discs (a wall: R1, set by disc_wall_kinematics).
inline double reduced_radius(double R1, double R2) { return R1 * R2 / (R1 + R2); }

// r = 2 R1 R2/(R1 + R2), the harmonic-mean radius of the rolling laws (-> 2 R1 at a wall, J05 Eq. 11).
// 2 R1 R2/(R1 + R2) and 2 R* round to the same bits (a factor 2 is exact), so either form may be used.
inline double harmonic_radius(const ContactKinematics& k) {
  return k.wall ? 2.0 * k.R1 : 2.0 * k.R1 * k.R2 / (k.R1 + k.R2);
}

// The geometry of a contact that has not moved yet (the critical step): radii, R* and the wall flag;
// R2 = inf at a wall. Velocities and overlap are zero.
inline ContactKinematics contact_geometry(double R1, double R2, bool wall) {
  ContactKinematics k;
  k.wall = wall;
  k.R1 = R1;
  k.R2 = wall ? INFINITY : R2;
  k.R_star = wall ? R1 : reduced_radius(R1, R2);
  return k;
}

// d = x2 - x1 (minimum image), dist = |d| > 0.
inline ContactKinematics disc_disc_kinematics(Vec2 d, double dist, double R1, double R2, Vec2 v1, Vec2 v2, double w1,
                                              double w2) {
  ContactKinematics k;
  k.dist = dist;
  k.n = (1.0 / dist) * d;
  k.t = perp(k.n);
  k.R1 = R1;
  k.R2 = R2;
  k.u_n = R1 + R2 - dist;
  k.a1 = R1 - 0.5 * k.u_n;
  k.a2 = R2 - 0.5 * k.u_n;
  k.R_star = reduced_radius(R1, R2);
  const Vec2 dv = v2 - v1;
  k.v_n = dot(dv, k.n);
  k.V_t = -dot(dv, k.t);
  k.V_s = k.V_t + k.a1 * w1 + k.a2 * w2;
  k.thetadot_r = w1 - w2;
  k.V_r = k.R_star * k.thetadot_r;
  return k;
}

// The lever a1 = R1 - u_n/2 of a disc at the distance dist from a wall (u_n = R1 - dist), as the kinematics
// form it: the contact point is x1 + a1 n.
inline double wall_lever(double R1, double dist) { return R1 - 0.5 * (R1 - dist); }

// n: unit vector from the disc centre towards the wall; dist: centre-to-wall distance; v_wall: the wall's
// surface velocity at the contact point; w_wall: the wall's angular velocity (0: a wall that does not rotate).
inline ContactKinematics disc_wall_kinematics(Vec2 n, double dist, double R1, Vec2 v1, Vec2 v_wall, double w1,
                                              double w_wall = 0.0) {
  ContactKinematics k;
  k.wall = true;
  k.dist = dist;
  k.n = n;
  k.t = perp(n);
  k.R1 = R1;
  k.R2 = INFINITY;
  k.u_n = R1 - dist;
  k.a1 = R1 - 0.5 * k.u_n;
  k.a2 = INFINITY;
  k.R_star = R1;
  const Vec2 dv = v_wall - v1;
  k.v_n = dot(dv, k.n);
  k.V_t = -dot(dv, k.t);
  k.V_s = k.V_t + k.a1 * w1;
  k.thetadot_r = w1 - w_wall;
  k.V_r = k.R_star * k.thetadot_r;
  return k;
}

}  // namespace rondel
