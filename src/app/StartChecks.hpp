#pragma once
// Derived quantities checked at set-up, before any file is written (docs/design.md section 8): the values
// of the keys are each in range (core/Config), but together they may still give a mass that underflows, a
// critical step of 0 or infinity, more cells than the memory holds, or a kinetic energy that overflows.
// Each check throws ConfigError naming the keys that made the quantity.
#include <string>
#include <vector>

#include "core/Config.hpp"
#include "core/DiscStore.hpp"
#include "physics/CriticalTimeStep.hpp"

namespace rondel::start_checks {

// The keys that place the scene's discs (by scene.type; the domain's too), for the messages of the checks of
// the initial state: a disc outside the domain, behind a wall, or overlapping another.
std::string scene_keys(const Config& c);
// The keys that set the critical step, with their values: the selected laws' parameters (the defaults, then
// [wall_contact] and the pair blocks where they differ), the materials' density and thickness (hertz: E and
// nu, run.max_overlap) and the scene's radius keys.
std::string critical_keys(const Config& c);
// The mass and inertia of the smallest and largest disc of every material: finite and normal (>= 2^-1022).
void check_masses(const Config& c, const std::vector<MaterialInfo>& materials);
// The critical step and the time step: finite and normal, the run's end time run.steps x dt finite, and the
// fall of a disc at rest under gravity in one step below run.max_overlap x the smallest radius `R_min`.
void check_time_step(const Config& c, const CriticalStep& critical, double dt, double R_min);
// The cell grid (cells of side >= `range`, as CellGrid makes them) against the machine's memory (the disc
// count is checked where the scene is built).
void check_cells(const Config& c, double range);
// A deforming cell (cell.rate_*, cell.stress_*) with the time step dt: the tilt changes by less than half the cell a
// step (a flip a step at most), no length shrinks by half in a step, and each length is at least twice the
// interaction range `range`: a rate's over the run (`sizing`, Simulation::cell_sizing), a stress target's now.
void check_cell(const Config& c, const Domain& sizing, double range, double dt);
// Every disc: a finite kinetic energy and a surface speed |v| + |omega| R below the speed of light.
void check_initial_motion(const Config& c, const DiscStore& discs);

}  // namespace rondel::start_checks
