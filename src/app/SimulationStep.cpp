// The time step of Simulation (docs/design.md section 4): the serial core (physics/StepCore.hpp: steps 1 and 4 to
// 7) with the run's parts between them, steps 2 and 3 (the step's one reduction, StepReduction.hpp; the walls,
// Boundaries; the neighbour list or the ghosts) and the checks and loads of step 6. The set-up and the outputs are
// in Simulation.cpp.
#include <algorithm>
#include <cmath>

#include "app/Simulation.hpp"
#include "core/Errors.hpp"
#include "core/Format.hpp"

namespace rondel {

StepInputs Simulation::step_inputs(bool bounds) {
  return StepInputs{discs_,
                    pairs_,
                    wall_rows_,
                    assembly_,
                    kernel_,
                    config_.domain,
                    walls_,
                    config_.params,
                    BodyForce{config_.gravity},
                    dt_,
                    config_.local_damping,
                    config_.max_overlap,
                    bounds,
                    bond_rows(),
                    &breaks_,
                    config_.thickness,
                    step_ + 1};
}

void Simulation::rebuild(bool on_owners) {
  // Discs go to their cell owners with their contact rows; the rows (local and received) then serve as
  // the history source of the new neighbour list. A deforming cell's decomposition grid takes its shape now.
  if (!config_.domain.standing()) follow_cell();
  cell_rebuild_ = false;
  neighbours_.set_cell_bound(dt_, neighbours_.range(R_max_));
  // Discs already on their owners (and no rank holding a row yet): the migration's pass over every disc and its
  // round of messages are skipped, on every rank alike.
  const DiscExchange::Counts moved =
      on_owners ? DiscExchange::Counts{}
                : exchange_.migrate(discs_, pairs_, wall_rows_, *decomposition_, comm_, false, bond_rows());
  decomposition_->migrated();
  // Received discs come last: back into gid order, the kernel's order (the arithmetic does not depend on it).
  discs_.sort_owned_by_gid();
  migrated_ += moved.sent;
  exchange_.build_ghosts(discs_, *decomposition_, comm_);
  if (config_.bonds) relink_bonds();
  phases_.lap(PhaseTimes::communication);
  neighbours_.build(discs_, config_.domain, walls_, config_.params, pairs_, wall_rows_);
  assembly_.build(discs_);
  if (!driver_forces_.empty()) driver_forces_.locate(discs_);
  reduction_.rebuilt();
  phases_.lap(PhaseTimes::neighbour);
}

void Simulation::relink_bonds() {
  // A bond whose other disc is neither owned nor a ghost here has stretched beyond the ghosts' reach: this rank's
  // error, agreed at the next reduction (it cannot act on the bond any more).
  ContactKey lost;
  if (bonds::relink(discs_, bonds_, lost) || reduction_.failed()) return;
  reduction_.keep(std::make_exception_ptr(
      InstabilityError("step " + std::to_string(step_) + ": the bond between discs " + std::to_string(lost.lo) +
                       " and " + std::to_string(lost.hi) + " has stretched beyond the interaction range and skin (" +
                       fmt(neighbours_.range(R_max_)) +
                       " m) without breaking: its strengths (bonds.sigma_c, bonds.tau_c) are too "
                       "high for its stiffness, or neighbour.skin is too small")));
}

void Simulation::edit_discs(const std::function<double(DiscStore&)>& edit) {
  core_.ledger().W_driver += edit(discs_);
  assembly_.build(discs_);
  motion_changed();
}

void Simulation::close_step() {
  phases_.restart();
  core_.close(step_inputs(false));
  phases_.lap(PhaseTimes::integrate);
}

// The run's parts of a step around the serial core (StepCore::advance).
struct Simulation::StepHooks {
  Simulation& sim;
  void lap(StepPhase phase) { sim.phases_.lap(phase == StepPhase::force ? PhaseTimes::force : PhaseTimes::integrate); }
  void between(const Integrator::Drift& drift) { sim.walls_and_neighbours(drift); }
  void after(LedgerStep& work) { sim.after_kernel(work); }
};

void Simulation::advance_step(bool close) {
  phases_.restart();
  const CommStats before = comm_.stats();
  if (config_.domain.moving) deform_cell();
  core_.advance(step_inputs(reduction_.measures_bounds()), close, StepHooks{*this});
  ++step_;
  time_ += dt_;
  // A balance check every balance_every steps, and once more after a repartition (the imbalance then reported is
  // the new map's; that measurement repartitions nothing). Both are agreed in the next step's reduction.
  const bool check = config_.balance_every > 0 && step_ % config_.balance_every == 0;
  if (check || repartitioned_) reduction_.check_balance(Decomposition::rank_work(discs_, pairs_), !check);
  ++steps_taken_;
  step_comm_.collectives += comm_.stats().collectives - before.collectives;
  step_comm_.messages += comm_.stats().messages - before.messages;
  step_comm_.bytes += comm_.stats().bytes - before.bytes;
  phases_.lap(PhaseTimes::other);
}

void Simulation::deform_cell() {
  // The cell's h(t + dt) before the drift, which wraps into it. Past |tilt| = L_x / 2 the cell flips: every disc
  // is wrapped into the new cell (its image relabelled, the same lattice) and this step builds a new list.
  Domain& cell = config_.domain;
  cell.deform(dt_);
  // The growth per step of the displacement bound's cell terms (NeighbourList::displacement and strain_term:
  // |L| dt (skin / 2 + |F| range / 2), |F| <= 2 before a rebuild).
  cell_step_ = cell.L.norm() * dt_ * (0.5 * neighbours_.skin() + neighbours_.range(R_max_));
  const int flipped = cell.flip();
  if (flipped == 0) return;
  flips_ += flipped;
  double W_cell = 0.0;  // the kinetic energy of the discs moved by -a (their velocity by -da/dt)
  for (std::size_t i = 0; i < discs_.n_owned(); ++i)
    W_cell += cell.wrap_work(discs_.position[i], discs_.velocity[i], discs_.mass[i]);
  core_.ledger().W_cell += W_cell;
  cell_rebuild_ = true;
}

void Simulation::follow_cell() {
  const Domain& cell = config_.domain;
  const double range = neighbours_.range(R_max_);
  if (!(cell.length_x() >= 2.0 * range && cell.length_y() >= 2.0 * range))
    throw InstabilityError("step " + std::to_string(step_) + ": the cell (L_x = " + fmt(cell.length_x()) +
                           ", L_y = " + fmt(cell.length_y()) + ") has become too small for the interaction range " +
                           fmt(range) + " (a length below twice the range: a disc would meet two images of another)" +
                           ": a larger cell, a lower cell.stress_* target or a lower rate");
  // A new grid when this one's cells have fallen below the range, or when the cell has grown so that twice as
  // many cells fit a side (the counts a start now would take): the same on every rank, decided on the shape.
  const CellGrid& grid = decomposition_->grid();
  const CellGrid fresh(cell, range, cell_sizing());
  if (grid.column_width(cell) < range || grid.row_height(cell) < range || fresh.nx() >= 2 * grid.nx() ||
      fresh.ny() >= 2 * grid.ny())
    regrid();
  else
    decomposition_->follow(cell);
}

void Simulation::regrid() {
  // As a restart: the discs (with their rows) to an equal-cell cut of the new grid on any rank, then to the
  // weighted cut. Collective, and rare: once per halving or doubling of a length.
  route_to_owners();
  ++regrids_;
}

void Simulation::walls_and_neighbours(const Integrator::Drift& drift) {
  reduction_.start_step(drift, dt_, cell_step_);
  // The drift's largest step bounds the displacement since the last neighbour build (NeighbourList::displacement).
  // A position gone NaN or inf is this rank's error, agreed at the next reduction (always before a rebuild could
  // migrate the disc); the reduction sees it as an infinite displacement.
  double moved = neighbours_.displacement(drift.max_step, discs_, config_.domain, walls_);
  if (!std::isfinite(moved)) reduction_.keep(motion_error(moved));
  phases_.lap(PhaseTimes::neighbour);
  // 2. The step's one reduction when due: with controlled walls every step, before they steer from the last
  //    step's exact loads; otherwise when the motion bound, a balance check or the interval asks for it, or when
  //    the walls' motion alone could call for a new neighbour list. Then the walls move.
  bool reduced = false;
  double disp = moved;
  const auto reduce = [&] {
    disp = reduction_.reduce(moved, walls_, loads_, *decomposition_, discs_, pairs_, config_.domain, cell_control_,
                             cell_sums_),
    reduced = true;
  };
  if (reduction_.due_before_walls()) reduce();
  phases_.lap(PhaseTimes::communication);
  // Glued discs move after the displacement was measured: this step's wall motion is added to it (the same on
  // every rank), so that the neighbour list's bound covers them.
  const double glued = boundaries_.move_walls(walls_, discs_, config_.domain, config_.thickness, dt_);
  if (boundaries_.rough()) disp += glued, moved += glued;
  phases_.lap(PhaseTimes::integrate);
  if (!reduced && neighbours_.needs_rebuild(reduction_.predicted() / 0.9, walls_)) reduce();
  // Without a reduction, this rank's own discs (with the walls' motion) must not need a new list: if the motion
  // bound was wrong, that is an error rather than a missed contact. A flip of the cell builds a new list anyway.
  if (!reduced && !reduction_.failed() && !cell_rebuild_ && neighbours_.needs_rebuild(moved, walls_))
    reduction_.keep(motion_error(moved));
  phases_.lap(PhaseTimes::communication);
  // 3. A new neighbour list when a disc (global max) has moved more than half the skin, or a repartition is due;
  //    otherwise the ghosts' update.
  repartitioned_ = reduction_.rebalance_due();
  if (repartitioned_ || cell_rebuild_ || (reduced && neighbours_.needs_rebuild(disp, walls_))) {
    rebuild();
  } else {
    exchange_.update_ghosts(discs_, comm_);
    phases_.lap(PhaseTimes::communication);
  }
  // The walls' work on the glued discs with the last step's reaction forces, before the sums start anew.
  boundaries_.glued_work_before(discs_, dt_);
}

void Simulation::after_kernel(LedgerStep& work) {
  // A script's body forces after the contacts (the same sum on any rank count), their work booked now.
  if (!driver_forces_.empty()) core_.ledger().W_driver += driver_forces_.apply(discs_, dt_);
  // An overlap beyond run.max_overlap is this rank's error until the next reduction (or output) agrees on it; on
  // one rank it stops the step at once.
  if (work.worst_overlap > 0.0 && !reduction_.failed()) reduction_.keep(overlap_error(work));
  if (reduction_.failed() && comm_.size() == 1) std::rethrow_exception(reduction_.error());
  boundaries_.add_glued_work(discs_, dt_, work.W_w);  // the last step's reaction forces and this step's
  if (boundaries_.controlled()) loads_ = Boundaries::local_loads(walls_, discs_, config_.domain, pairs_, wall_rows_);
  if (cell_control_.active()) cell_sums_ = CellControl::local_sums(discs_, config_.domain, pairs_);
}

void Simulation::settle_errors() {
  // Before any output: every rank's pending error is agreed (one small collective), and with controlled
  // walls their loads are those of this step, as a checkpoint or a measure expects.
  reduction_.settle();
  if (boundaries_.controlled()) boundaries_.measure(walls_, discs_, config_.domain, pairs_, wall_rows_, comm_);
}

std::exception_ptr Simulation::overlap_error(const LedgerStep& work) const {
  std::string where =
      work.worst_at_wall
          ? "disc " + std::to_string(work.worst_key.lo) + " and wall " + std::to_string(work.worst_key.hi)
          : "discs " + std::to_string(work.worst_key.lo) + " and " + std::to_string(work.worst_key.hi);
  where += std::isinf(work.worst_overlap) ? " have coincident centres"
                                          : " overlap by " + fmt(work.worst_overlap) + " of the smaller radius";
  return std::make_exception_ptr(
      InstabilityError("step " + std::to_string(step_ + 1) + " (t = " + fmt(time_ + dt_) + " s): " + where +
                       ", above run.max_overlap = " + fmt(config_.max_overlap) +
                       ". The contact law is not valid there: stiffen the contacts (linear.k_n, or the "
                       "materials' youngs_modulus with hertz), slow the impact, or lower run.dt if the run "
                       "became unstable"));
}

std::exception_ptr Simulation::motion_error(double moved) const {
  return std::make_exception_ptr(InstabilityError(
      "step " + std::to_string(step_ + 1) + ": a disc moved " + fmt(moved) +
      " m since the last neighbour build, more than half the skin (" + fmt(0.5 * neighbours_.skin()) +
      " m, or with the walls' motion more than the skin), between two displacement checks, or its position is "
      "not finite: its motion outgrew the bound the checks are spaced by. Set "
      "parallel.check_every = 1 (a check every step), or lower run.dt if the run became unstable"));
}

}  // namespace rondel
