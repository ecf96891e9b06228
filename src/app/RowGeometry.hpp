#pragma once
// The geometry of a contact row (overlap u_n, levers a1, a2, normal n) from the discs' present state,
// through the kernel's own kinematics (physics/ContactKinematics.hpp, formed as ContactKernel forms them),
// so that the set-up check, the diagnostics and the measures hold no second formula.
#include <cmath>
#include <cstddef>

#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/Domain.hpp"
#include "core/Wall.hpp"
#include "physics/ContactKinematics.hpp"

namespace rondel {

struct RowGeometry {
  // Discs i (the row's disc 1) and j, d = x_j - x_i by the minimum image.
  static ContactKinematics pair(const DiscStore& discs, const Domain& domain, std::size_t i, std::size_t j) {
    const Vec2 d = domain.separation(discs.position[i], discs.position[j]);
    return disc_disc_kinematics(d, std::sqrt(dot(d, d)), discs.radius[i], discs.radius[j], discs.velocity[i],
                                discs.velocity[j], discs.omega[i], discs.omega[j]);
  }
  // The force of pair row r's last evaluation on its disc 1, f1 = F_t t - F_n n (disc 2 gets -f1), formed
  // as the kernel forms it: the same bits while the discs stay where the kernel saw them (the kernel keeps
  // only F_n and F_t of a pair row).
  static Vec2 pair_force(const DiscStore& discs, const Domain& domain, const ContactTable& pairs, std::size_t r) {
    const ContactKinematics k =
        pair(discs, domain, static_cast<std::size_t>(pairs.i1[r]), static_cast<std::size_t>(pairs.i2[r]));
    return pairs.F_t[r] * k.t - pairs.F_n[r] * k.n;
  }
  // Disc i against a wall (a rotating wall: its surface velocity at the contact point and its spin, as the
  // kernel forms them).
  static ContactKinematics wall(const DiscStore& discs, const Wall& w, std::size_t i) {
    const Wall::Proximity prox = w.proximity(discs.position[i]);
    if (!w.rotates())
      return disc_wall_kinematics(prox.n, prox.dist, discs.radius[i], discs.velocity[i], w.velocity, discs.omega[i]);
    const Vec2 v_wall = w.surface_velocity(discs.position[i] + wall_lever(discs.radius[i], prox.dist) * prox.n);
    return disc_wall_kinematics(prox.n, prox.dist, discs.radius[i], discs.velocity[i], v_wall, discs.omega[i], w.omega);
  }
};

}  // namespace rondel
