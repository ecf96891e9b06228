// The time step of Simulation (docs/design.md section 4) and its one reduction (docs/scaling.md): step(),
// rebuild(), and the fused reduction with its motion bound, pending errors and stop requests. The set-up and
// the outputs are in Simulation.cpp.
#include <algorithm>
#include <cmath>

#include "app/Simulation.hpp"
#include "core/Errors.hpp"
#include "core/Format.hpp"
#include "core/Integrator.hpp"
#include "parallel/Agreement.hpp"
#include "parallel/FusedReduction.hpp"

namespace rondel {

void Simulation::rebuild() {
  // Discs go to their cell owners with their contact rows; the rows (local and received) then serve as
  // the history source of the new neighbour list.
  const DiscExchange::Counts moved = exchange_.migrate(discs_, pairs_, wall_rows_, *decomposition_, comm_);
  decomposition_->migrated();
  // Received discs come last: back into gid order, the kernel's order (the arithmetic does not depend on it).
  discs_.sort_owned_by_gid();
  migrated_ += moved.sent;
  exchange_.build_ghosts(discs_, *decomposition_, comm_);
  phases_.lap(PhaseTimes::communication);
  neighbours_.build(discs_, config_.domain, walls_, config_.params, pairs_, wall_rows_);
  assembly_.build(discs_);
  rebalance_due_ = false;
  base_disp_ = predicted_ = 0.0;
  phases_.lap(PhaseTimes::neighbour);
}

void Simulation::close_step() {
  if (!kick_pending_) return;
  phases_.restart();
  const double D_kick = Integrator::half_kick(discs_, dt_, config_.local_damping);
  ledger_.add(pending_work_, pending_W_g_, pending_D_open_ + D_kick);
  kick_pending_ = false;
  phases_.lap(PhaseTimes::integrate);
}

void Simulation::advance_step(bool close) {
  phases_.restart();
  const CommStats before = comm_.stats();
  stop_agreed_ = 0;
  // 1. Half kick and drift of owned discs (wrapping into the periodic box); the drift books gravity's work.
  //    The same pass measures the largest step of a disc, which bounds the displacement since the last
  //    neighbour build (NeighbourList::displacement).
  //    It also starts each free disc's force sum with its body force (step 4), and measures the motion
  //    bound when the displacement checks are spaced by it.
  const bool bounds = comm_.size() > 1 && !controlled_walls_ && config_.check_every > 1;
  //    With run.local_damping the kick is damped (docs/physics.md section 9) and books what it took.
  //    A closing kick the last step deferred (advance) comes first, in the same pass, and books that step.
  const Integrator::Drift drift = Integrator::half_kick_drift(discs_, config_.domain, dt_, BodyForce{config_.gravity},
                                                              bounds, config_.local_damping, kick_pending_);
  if (kick_pending_) ledger_.add(pending_work_, pending_W_g_, pending_D_open_ + drift.D_close);
  kick_pending_ = false;
  drift_speed_ = drift.max_speed, drift_accel_ = drift.max_accel;
  const double W_g = drift.W_g;
  double moved = neighbours_.displacement(drift.max_step, discs_, config_.domain, walls_);
  phases_.lap(PhaseTimes::integrate);
  // A position gone NaN or inf is this rank's error, agreed at the next reduction (always before a rebuild
  // could migrate the disc); the reduction sees it as an infinite displacement.
  if (!std::isfinite(moved) && !pending_error_) pending_error_ = motion_error(moved);
  phases_.lap(PhaseTimes::neighbour);
  // 2. The step's one reduction (docs/scaling.md), when due: with controlled walls every step, before they
  //    steer from the last step's exact loads; otherwise when the motion bound, a balance check or the
  //    interval asks for it, or when the walls' motion alone could call for a new neighbour list.
  bool reduced = false;
  double disp = moved;
  if (controlled_walls_ || reduction_due()) disp = reduce(moved), reduced = true;
  phases_.lap(PhaseTimes::communication);
  if (controlled_walls_) boundaries_.steer(walls_, config_.domain, config_.thickness, dt_);
  for (auto& w : walls_) w.move(dt_);
  if (rough_walls_) {
    // Glued discs move after the displacement was measured: this step's wall motion is added (the same on
    // every rank), as the old order (measure after moving them) had it.
    Boundaries::move_glued(discs_, walls_, config_.domain, dt_);
    double v_wall = 0.0;
    for (const Wall& w : walls_) v_wall = std::max(v_wall, std::sqrt(dot(w.velocity, w.velocity)));
    disp += v_wall * dt_, moved += v_wall * dt_;
  }
  phases_.lap(PhaseTimes::integrate);
  if (!reduced && neighbours_.needs_rebuild(predicted_ / 0.9, walls_)) disp = reduce(moved), reduced = true;
  // Without a reduction, this rank's own discs (with the walls' motion) must not need a new list: if the
  // motion bound was wrong, that is an error rather than a missed contact.
  if (!reduced && !pending_error_ && neighbours_.needs_rebuild(moved, walls_)) pending_error_ = motion_error(moved);
  phases_.lap(PhaseTimes::communication);
  // 3. Rebuild the neighbour list when a disc (global max) has moved more than half the skin.
  const bool repartitioned = rebalance_due_;
  if (rebalance_due_ || (reduced && neighbours_.needs_rebuild(disp, walls_))) {
    rebuild();
  } else {
    exchange_.update_ghosts(discs_, comm_);
    phases_.lap(PhaseTimes::communication);
  }
  // The wall's work on the glued discs with the last step's reaction forces, taken before the sums start anew
  // (booked after the kernel's terms, as in step 6).
  const double W_glued_last = rough_walls_ ? Boundaries::glued_work_half(discs_, dt_) : 0.0;
  // 4. Body forces (gravity): the first term of each disc's sum (the drift started the free discs' sums).
  assembly_.begin_fixed_and_ghosts(discs_);
  LedgerStep work;
  // 5. Contact kernel over every row, adding each row's terms to its discs' sums in ascending partner gid
  //    (step 6). An overlap beyond run.max_overlap is this rank's error until the next reduction (or
  //    output) agrees on it; on one rank it stops the step at once.
  kernel_.run(KernelContext{discs_, config_.domain, walls_, config_.params, dt_, config_.max_overlap}, pairs_,
              wall_rows_, ForceSums::of(discs_), work);
  phases_.lap(PhaseTimes::force);
  if (work.worst_overlap > 0.0 && !pending_error_) pending_error_ = overlap_error(work);
  if (pending_error_ && comm_.size() == 1) std::rethrow_exception(pending_error_);
  // 6. The per-disc sums are complete (the kernel added the terms in ascending partner gid, walls last);
  //    fixed discs are finished.
  assembly_.finish(discs_);
  if (rough_walls_) {
    work.W_w += W_glued_last;
    work.W_w += Boundaries::glued_work_half(discs_, dt_);  // this step's reaction forces
  }
  if (controlled_walls_) loads_ = Boundaries::local_loads(walls_, discs_, config_.domain, pairs_, wall_rows_);
  phases_.lap(PhaseTimes::force);
  // 7. Second half kick (diagnostics and output on their schedules: Runner), damped with run.local_damping
  //    by the half-step velocities; deferred to the next step's drift when nothing looks in between.
  if (close) {
    const double D_kick = Integrator::half_kick(discs_, dt_, config_.local_damping);
    ledger_.add(work, W_g, drift.D_damping + D_kick);
  } else {
    kick_pending_ = true;
    pending_work_ = work, pending_W_g_ = W_g, pending_D_open_ = drift.D_damping;
  }
  phases_.lap(PhaseTimes::integrate);
  ++step_;
  time_ += dt_;
  // A balance check every balance_every steps, and once more after a repartition (the imbalance then
  // reported is the new map's; that measurement repartitions nothing). Both are agreed in the next step's
  // reduction.
  const bool check = config_.balance_every > 0 && step_ % config_.balance_every == 0;
  if (check || repartitioned) {
    remeasure_ = !check;
    balance_work_ = Decomposition::rank_work(discs_, pairs_);
    balance_pending_ = true;
  }
  ++steps_taken_;
  step_comm_.collectives += comm_.stats().collectives - before.collectives;
  step_comm_.messages += comm_.stats().messages - before.messages;
  step_comm_.bytes += comm_.stats().bytes - before.bytes;
  phases_.lap(PhaseTimes::other);
}

bool Simulation::reduction_due() {
  // One rank needs no agreement: its "reduction" is free and exact every step.
  if (comm_.size() == 1 || config_.check_every == 1 || balance_pending_ || !bounds_known_) return true;
  ++since_reduction_;
  const double j = static_cast<double>(since_reduction_);
  // The largest displacement since the last build can grow per step by at most the speed times dt plus
  // the acceleration's share; both are bounded with a factor two over their values at the last reduction.
  predicted_ = base_disp_ + 2.0 * j * v_step_ + 2.0 * j * (j + 1.0) * a_step_;
  return since_reduction_ >= config_.check_every;
}

double Simulation::reduce(double moved) {
  FusedReduction r;
  const bool bounds = comm_.size() > 1 && !controlled_walls_ && config_.check_every > 1;
  const auto [v, a] = bounds ? motion_bounds() : std::pair<double, double>{0.0, 0.0};
  const std::size_t s_disp = r.max(moved), s_v = r.max(v), s_a = r.max(a);
  const std::size_t s_err = r.max(static_cast<std::int64_t>(pending_error_ ? comm_.size() - comm_.rank() : 0));
  const std::size_t s_stop = r.max(stop_request_);
  const auto wall_slots = controlled_walls_ ? loads_.add_to(r) : std::vector<std::array<std::size_t, 4>>{};
  std::size_t s_work_max = 0, s_work_sum = 0;
  if (balance_pending_) s_work_max = r.max(balance_work_), s_work_sum = r.sum(balance_work_);
  r.reduce(comm_);
  if (r.max_int(s_err) > 0) raise_from(comm_, comm_.size() - static_cast<int>(r.max_int(s_err)), pending_error_);
  stop_agreed_ = r.max_int(s_stop);
  if (controlled_walls_) Boundaries::apply(walls_, r, wall_slots);
  if (balance_pending_) {
    balance_pending_ = false;
    const double mean = static_cast<double>(r.sum_int(s_work_sum)) / comm_.size();
    imbalance_ = mean > 0.0 ? static_cast<double>(r.max_int(s_work_max)) / mean : 1.0;
    if (!remeasure_ && comm_.size() > 1 && (config_.force_balance || imbalance_ > config_.balance_threshold) &&
        decomposition_->repartition(discs_, pairs_))
      rebalance_due_ = true;
    remeasure_ = false;
  }
  since_reduction_ = 0;
  base_disp_ = r.max_double(s_disp);
  predicted_ = base_disp_;
  v_step_ = r.max_double(s_v);
  a_step_ = r.max_double(s_a);
  bounds_known_ = bounds;
  return base_disp_;
}

std::pair<double, double> Simulation::motion_bounds() const {
  // Measured by this step's drift over the free discs (the fixed ones are moved by their walls: the walls'
  // term): the speed after the half kick and the acceleration of the force it used.
  return {drift_speed_ * dt_, drift_accel_ * dt_ * dt_};
}

void Simulation::settle_errors() {
  // Before any output: every rank's pending error is agreed (one small collective), and with controlled
  // walls their loads are those of this step, as a checkpoint or a measure expects.
  if (comm_.size() > 1) settle(comm_, pending_error_);
  if (controlled_walls_) boundaries_.measure(walls_, discs_, config_.domain, pairs_, wall_rows_, comm_);
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
