#pragma once
// The geometry of a contact row (overlap u_n, levers a1, a2, normal n) from the discs' present state,
// through the kernel's own kinematics (physics/ContactKinematics.hpp, formed as ContactKernel forms them),
// so that the set-up check, the diagnostics and the measures hold no second formula.
#include <cmath>
#include <cstddef>

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
  // Disc i against a wall.
  static ContactKinematics wall(const DiscStore& discs, const Wall& w, std::size_t i) {
    const Wall::Proximity prox = w.proximity(discs.position[i]);
    return disc_wall_kinematics(prox.n, prox.dist, discs.radius[i], discs.velocity[i], w.velocity, discs.omega[i]);
  }
};

}  // namespace rondel
