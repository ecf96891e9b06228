#include "app/StepReduction.hpp"

#include <utility>

#include "parallel/Agreement.hpp"
#include "parallel/FusedReduction.hpp"

namespace rondel {

StepReduction::StepReduction(const Communicator& comm, const Config& config, bool controlled_walls)
    : comm_(comm),
      config_(config),
      controlled_walls_(controlled_walls),
      bounds_(comm.size() > 1 && !controlled_walls && config.check_every > 1) {}

void StepReduction::settle() {
  if (comm_.size() > 1) rondel::settle(comm_, error_);
}

void StepReduction::start_step(const Integrator::Drift& drift, double dt, double cell_step) {
  stop_agreed_ = 0;
  cell_step_ = cell_step;
  drift_speed_ = drift.max_speed, drift_accel_ = drift.max_accel, dt_ = dt;
}

bool StepReduction::due_before_walls() {
  if (controlled_walls_) return true;
  // One rank needs no agreement: its "reduction" is free and exact every step.
  if (comm_.size() == 1 || config_.check_every == 1 || balance_pending_ || !bounds_known_) return true;
  ++since_reduction_;
  const double j = static_cast<double>(since_reduction_);
  // The largest displacement since the last build can grow per step by at most the speed times dt plus
  // the acceleration's share; both are bounded with a factor two over their values at the last reduction. A
  // deforming cell adds its terms' growth (known on every rank), with the same factor.
  predicted_ = base_disp_ + 2.0 * j * v_step_ + 2.0 * j * (j + 1.0) * a_step_ + 2.0 * j * cell_step_;
  return since_reduction_ >= config_.check_every;
}

double StepReduction::reduce(double moved, WallSet& walls, const WallLoads& loads, Decomposition& decomposition,
                             const DiscStore& discs, const ContactTable& pairs, Domain& cell,
                             const CellControl& control, const CellStressSums& cell_sums) {
  FusedReduction r;
  // The motion bound: measured by this step's drift over the free discs (the fixed ones are moved by their walls:
  // the walls' term), the speed after the half kick and the acceleration of the force it used.
  const double v = bounds_ ? drift_speed_ * dt_ : 0.0, a = bounds_ ? drift_accel_ * dt_ * dt_ : 0.0;
  const std::size_t s_disp = r.max(moved), s_v = r.max(v), s_a = r.max(a);
  const std::size_t s_err = r.max(static_cast<std::int64_t>(error_ ? comm_.size() - comm_.rank() : 0));
  const std::size_t s_stop = r.max(stop_request_);
  const auto wall_slots = controlled_walls_ ? loads.add_to(r) : std::vector<std::array<std::size_t, 4>>{};
  const std::array<std::size_t, 2> cell_slots = control.active() ? cell_sums.add_to(r) : std::array<std::size_t, 2>{};
  std::size_t s_work_max = 0, s_work_sum = 0;
  if (balance_pending_) s_work_max = r.max(balance_work_), s_work_sum = r.sum(balance_work_);
  r.reduce(comm_);
  if (r.max_int(s_err) > 0) raise_from(comm_, comm_.size() - static_cast<int>(r.max_int(s_err)), error_);
  stop_agreed_ = r.max_int(s_stop);
  if (controlled_walls_) Boundaries::apply(walls, r, wall_slots);
  if (control.active()) control.apply(cell, r, cell_slots);
  if (balance_pending_) {
    balance_pending_ = false;
    const double mean = static_cast<double>(r.sum_int(s_work_sum)) / comm_.size();
    imbalance_ = mean > 0.0 ? static_cast<double>(r.max_int(s_work_max)) / mean : 1.0;
    if (!remeasure_ && comm_.size() > 1 && (config_.force_balance || imbalance_ > config_.balance_threshold) &&
        decomposition.repartition(discs, pairs))
      rebalance_due_ = true;
    remeasure_ = false;
  }
  since_reduction_ = 0;
  base_disp_ = r.max_double(s_disp);
  predicted_ = base_disp_;
  v_step_ = r.max_double(s_v);
  a_step_ = r.max_double(s_a);
  bounds_known_ = bounds_;
  return base_disp_;
}

void StepReduction::check_balance(std::int64_t work, bool remeasure) {
  remeasure_ = remeasure;
  balance_work_ = work;
  balance_pending_ = true;
}

}  // namespace rondel
