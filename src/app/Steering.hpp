#pragma once
// A script's writes into a running simulation (the Python module, docs/python.md), between steps. Each is
// collective: every rank passes the same arguments and changes the discs it owns, so a script gives the same bits
// on any rank count. Bad values are refused before anything changes, on every rank alike, naming the value: a
// number that is NaN or infinite, a gid that no rank owns or that is given twice, a wall index out of range or a
// wall whose control does not take the value.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/Vec2.hpp"

namespace rondel {

class Simulation;

namespace steering {

// Velocities [m/s] and spins [rad/s] of the discs `gids` (of a free disc; a fixed disc stays at rest). The change of
// kinetic energy is booked as the work W_driver.
void set_velocity(Simulation& sim, const std::vector<std::int64_t>& gids, const std::vector<Vec2>& v);
void set_omega(Simulation& sim, const std::vector<std::int64_t>& gids, const std::vector<double>& omega);
// Fixes the discs (at rest, not integrated; their kinetic energy is booked as W_driver) or frees them (from rest).
// A disc glued to a wall is refused: it moves with its wall.
void set_fixed(Simulation& sim, const std::vector<std::int64_t>& gids, bool fixed);
// Body forces [N] on the discs `gids` beside gravity, from the next step on (a zero force removes one); their work is
// booked as W_driver (app/DriverForces.hpp). A fixed disc is refused.
void set_body_force(Simulation& sim, const std::vector<std::int64_t>& gids, const std::vector<Vec2>& forces);
// A deforming cell's rates [1/s] (the components given: 0 xx, 1 yy, 2 xy; NaN: unchanged), for components that are
// not stress-controlled; a stress-controlled component's target stress [Pa] (> 0; NaN: unchanged).
void set_cell_rates(Simulation& sim, double xx, double yy, double xy);
void set_cell_stress(Simulation& sim, double xx, double yy);
// A velocity-controlled, translating wall's velocity [m/s]; a servo wall's target stress [Pa] (> 0).
void set_wall_velocity(Simulation& sim, std::size_t wall, Vec2 v);
void set_wall_stress(Simulation& sim, std::size_t wall, double stress);
// A strain-rate wall's rate [1/s] (> 0 compresses, < 0 unloads, 0 holds the wall).
void set_wall_strain_rate(Simulation& sim, std::size_t wall, double rate);

}  // namespace steering
}  // namespace rondel
