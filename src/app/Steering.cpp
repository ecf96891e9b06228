#include "app/Steering.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "app/CellControl.hpp"
#include "app/Simulation.hpp"
#include "core/Errors.hpp"
#include "core/Format.hpp"

namespace rondel::steering {

namespace {

constexpr const char* kFixedRefusal = "is fixed: it stays at rest (free it first: set_fixed(gids, False))";

void check_finite(const char* what, std::size_t k, double v) {
  if (!std::isfinite(v))
    throw InputError(std::string(what) + "[" + std::to_string(k) + "] = " + fmt(v) +
                     " is not a finite number; a disc's value must be finite");
}

// The local index of each gid on this rank (or -1), after checking on every rank that each gid is owned by exactly
// one rank and given once (collective).
std::vector<std::ptrdiff_t> owned_indices(const Simulation& sim, const std::vector<std::int64_t>& gids) {
  std::vector<std::int64_t> sorted = gids;
  std::sort(sorted.begin(), sorted.end());
  const auto twice = std::adjacent_find(sorted.begin(), sorted.end());
  if (twice != sorted.end())
    throw InputError("gid " + std::to_string(*twice) + " is given twice; each disc at most once per call");
  const DiscStore& d = sim.discs();
  const auto first = d.gid.begin(), last = d.gid.begin() + static_cast<std::ptrdiff_t>(d.n_owned());
  const bool in_order = std::is_sorted(first, last);  // the owned discs are kept in gid order (Simulation::rebuild)
  std::vector<std::ptrdiff_t> index(gids.size(), -1);
  std::int64_t found = 0;
  for (std::size_t k = 0; k < gids.size(); ++k) {
    const auto at = in_order ? std::lower_bound(first, last, gids[k]) : std::find(first, last, gids[k]);
    if (at != last && *at == gids[k]) index[k] = at - first, ++found;
  }
  const Communicator& comm = sim.comm();
  if (comm.sum(found) == static_cast<std::int64_t>(gids.size())) return index;
  // Name the first gid that no rank owns: each rank's smallest position of a gid it owns is not enough, so every rank
  // marks what it owns and the lowest unmarked position is agreed.
  std::int64_t missing = static_cast<std::int64_t>(gids.size());
  for (std::size_t k = 0; k < gids.size(); ++k) {
    const std::int64_t owned = comm.sum(static_cast<std::int64_t>(index[k] >= 0));
    if (owned == 0) {
      missing = static_cast<std::int64_t>(k);
      break;
    }
  }
  throw InputError("gid " + std::to_string(gids[static_cast<std::size_t>(missing)]) +
                   " is not a disc of the simulation (no rank owns it); the gids are those of final.csv and of the "
                   "views' gid column");
}

void check_sizes(std::size_t gids, std::size_t values, const char* what) {
  if (gids != values)
    throw InputError(std::string(what) + ": " + std::to_string(values) + " values for " + std::to_string(gids) +
                     " gids; one value per gid");
}

// Refused on every rank alike when a disc of the list on any rank has the flag `flag`.
void refuse_flagged(const Simulation& sim, const std::vector<std::int64_t>& gids,
                    const std::vector<std::ptrdiff_t>& index, std::uint32_t flag, const std::string& message) {
  std::int64_t first = -1;
  for (std::size_t k = 0; k < gids.size() && first < 0; ++k)
    if (index[k] >= 0 && (sim.discs().flags[static_cast<std::size_t>(index[k])] & flag)) first = gids[k];
  first = sim.comm().max(first);
  if (first >= 0) throw InputError("disc " + std::to_string(first) + " " + message);
}

void check_value(const char* what, std::size_t k, double v) { check_finite(what, k, v); }
void check_value(const char* what, std::size_t k, Vec2 v) { check_finite(what, k, v.x), check_finite(what, k, v.y); }

// The checks of a write of one value per disc, on every rank alike: as many values as gids, finite numbers, each gid
// owned by one rank and given once, no fixed disc. Returns the local index of each gid on this rank (or -1).
template <class Value>
std::vector<std::ptrdiff_t> checked_free_discs(const Simulation& sim, const std::vector<std::int64_t>& gids,
                                               const std::vector<Value>& values, const char* what) {
  check_sizes(gids.size(), values.size(), what);
  for (std::size_t k = 0; k < values.size(); ++k) check_value(what, k, values[k]);
  std::vector<std::ptrdiff_t> index = owned_indices(sim, gids);
  refuse_flagged(sim, gids, index, kFlagFixed, kFixedRefusal);
  return index;
}

// write(i, k) on each owned disc i of the list (k its place in the list); the sum of what the writes return (the
// kinetic energy they added on this rank).
template <class Write>
double each_owned(const std::vector<std::ptrdiff_t>& index, Write&& write) {
  double sum = 0.0;
  for (std::size_t k = 0; k < index.size(); ++k)
    if (index[k] >= 0) sum += write(static_cast<std::size_t>(index[k]), k);
  return sum;
}

const Wall& checked_wall(const Simulation& sim, std::size_t wall) {
  if (wall >= sim.walls().size())
    throw InputError("wall " + std::to_string(wall) + " does not exist; the walls are 0 to " +
                     std::to_string(static_cast<std::int64_t>(sim.walls().size()) - 1));
  return sim.walls()[wall];
}

}  // namespace

void set_velocity(Simulation& sim, const std::vector<std::int64_t>& gids, const std::vector<Vec2>& v) {
  const std::vector<std::ptrdiff_t> index = checked_free_discs(sim, gids, v, "velocity");
  sim.edit_discs([&](DiscStore& d) {
    return each_owned(index, [&](std::size_t i, std::size_t k) {
      const double added = 0.5 * d.mass[i] * (dot(v[k], v[k]) - dot(d.velocity[i], d.velocity[i]));
      d.velocity[i] = v[k];
      return added;
    });
  });
}

void set_omega(Simulation& sim, const std::vector<std::int64_t>& gids, const std::vector<double>& omega) {
  const std::vector<std::ptrdiff_t> index = checked_free_discs(sim, gids, omega, "omega");
  sim.edit_discs([&](DiscStore& d) {
    return each_owned(index, [&](std::size_t i, std::size_t k) {
      const double added = 0.5 * d.inertia[i] * (omega[k] * omega[k] - d.omega[i] * d.omega[i]);
      d.omega[i] = omega[k];
      return added;
    });
  });
}

void set_fixed(Simulation& sim, const std::vector<std::int64_t>& gids, bool fixed) {
  const std::vector<std::ptrdiff_t> index = owned_indices(sim, gids);
  refuse_flagged(sim, gids, index, kFlagAttached,
                 "is glued to a rough wall (walls.rough): it moves with its wall and cannot be fixed or freed");
  sim.edit_discs([&](DiscStore& d) {
    return each_owned(index, [&](std::size_t i, std::size_t) {
      double added = 0.0;
      if (fixed && !(d.flags[i] & kFlagFixed)) {
        added = -(0.5 * d.mass[i] * dot(d.velocity[i], d.velocity[i]) + 0.5 * d.inertia[i] * d.omega[i] * d.omega[i]);
        d.velocity[i] = {};
        d.omega[i] = 0.0;
      }
      d.flags[i] = fixed ? (d.flags[i] | kFlagFixed) : (d.flags[i] & ~static_cast<std::uint32_t>(kFlagFixed));
      return added;
    });
  });
}

void set_body_force(Simulation& sim, const std::vector<std::int64_t>& gids, const std::vector<Vec2>& forces) {
  checked_free_discs(sim, gids, forces, "force");
  sim.set_driver_forces(gids, forces);
}

void set_cell_rates(Simulation& sim, double xx, double yy, double xy) {
  if (!sim.config().cell_deforms())
    throw InputError(
        "the cell does not deform in this run: its rates are set by a scene with [cell] rates or "
        "stresses (a standing box stays one)");
  Domain& cell = sim.steered_cell();
  const double given[3] = {xx, yy, xy};
  const char* names[3] = {"xx", "yy", "xy"};
  for (int k = 0; k < 3; ++k) {
    if (std::isnan(given[k])) continue;
    if (!std::isfinite(given[k]))
      throw InputError(std::string("cell rate ") + names[k] + " = " + fmt(given[k]) + " must be finite [1/s]");
    if (k < 2 && sim.steered_cell_control().target(k) > 0.0)
      throw InputError(std::string("cell rate ") + names[k] + ": the component is stress-controlled (cell.stress_" +
                       names[k] + "); set its target stress instead");
  }
  if (!std::isnan(xx)) cell.L.xx = xx;
  if (!std::isnan(yy)) cell.L.yy = yy;
  if (!std::isnan(xy)) cell.L.xy = xy;
  cell.rates();
  sim.motion_changed();  // the motion bound changes: the next step reduces
}

void set_cell_stress(Simulation& sim, double xx, double yy) {
  const double given[2] = {xx, yy};
  const char* names[2] = {"xx", "yy"};
  CellControl& control = sim.steered_cell_control();
  for (int k = 0; k < 2; ++k) {
    if (std::isnan(given[k])) continue;
    if (control.target(k) <= 0.0)
      throw InputError(std::string("cell stress ") + names[k] +
                       ": the component is not stress-controlled in this run "
                       "(cell.stress_" +
                       names[k] + " not set); set its rate instead");
    if (!(std::isfinite(given[k]) && given[k] > 0.0))
      throw InputError(std::string("cell stress ") + names[k] + " = " + fmt(given[k]) +
                       " must be a finite number > 0 [Pa]");
  }
  for (int k = 0; k < 2; ++k)
    if (!std::isnan(given[k])) control.set_target(k, given[k]);
}

void set_wall_velocity(Simulation& sim, std::size_t wall, Vec2 v) {
  check_finite("wall velocity", 0, v.x), check_finite("wall velocity", 1, v.y);
  const Wall& w = checked_wall(sim, wall);
  if (w.control != Wall::Control::velocity || w.rotates())
    throw InputError("wall " + std::to_string(wall) +
                     " is not a translating wall of prescribed velocity (it is servo- or strain-rate-controlled, or "
                     "it rotates): its velocity cannot be set");
  sim.steered_walls()[wall].velocity = v;
}

void set_wall_stress(Simulation& sim, std::size_t wall, double stress) {
  const Wall& w = checked_wall(sim, wall);
  if (w.control != Wall::Control::servo)
    throw InputError("wall " + std::to_string(wall) +
                     " is not a servo wall (walls.servo): its target stress cannot be set");
  if (!(std::isfinite(stress) && stress > 0.0))
    throw InputError("target stress " + fmt(stress) + " of wall " + std::to_string(wall) +
                     " must be a finite number > 0 [Pa]");
  sim.steered_walls()[wall].target_stress = stress;
}

void set_wall_strain_rate(Simulation& sim, std::size_t wall, double rate) {
  const Wall& w = checked_wall(sim, wall);
  if (w.control != Wall::Control::strain_rate)
    throw InputError("wall " + std::to_string(wall) +
                     " is not a strain-rate wall (walls.control WALL:strain_rate:RATE): its rate cannot be set");
  if (!std::isfinite(rate))
    throw InputError("strain rate " + fmt(rate) + " of wall " + std::to_string(wall) + " must be finite [1/s]");
  sim.steered_walls()[wall].strain_rate = rate;
}

}  // namespace rondel::steering
