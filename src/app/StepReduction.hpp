#pragma once
// The step's one reduction (docs/design.md section 6, docs/scaling.md): a single small MPI_Allreduce
// (FusedReduction) carries the largest displacement since the last neighbour build and the bound of the discs'
// motion, the lowest rank with a pending error, the stop request (signals, wall-clock checkpoints), the exact
// loads of the controlled walls and the balance counts. With controlled walls it runs every step, before they
// steer; otherwise only when due: the displacement since the last build is bounded between two reductions by the
// speed and the acceleration at the last one (twice each), and the next reduction comes before that bound could
// reach the rebuild criterion, or after parallel.check_every steps. On one rank the "reduction" is free and exact
// every step. The protocol's state lives here; Simulation asks it.
#include <cstdint>
#include <exception>

#include "app/Boundaries.hpp"
#include "app/CellControl.hpp"
#include "core/Config.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/Integrator.hpp"
#include "core/Wall.hpp"
#include "parallel/Communicator.hpp"
#include "parallel/Decomposition.hpp"

namespace rondel {

class StepReduction {
 public:
  // `controlled_walls`: controlled walls or a stress-controlled cell (a reduction every step).
  StepReduction(const Communicator& comm, const Config& config, bool controlled_walls);

  // This rank's error, kept (the first one) until a reduction or settle() agrees on it: every rank then throws
  // the lowest failing rank's error.
  void keep(std::exception_ptr error) {
    if (!error_) error_ = std::move(error);
  }
  bool failed() const { return error_ != nullptr; }
  const std::exception_ptr& error() const { return error_; }
  // Collective on several ranks: agrees on every rank's pending error.
  void settle();

  // The stop request of this rank for the coming step (Runner: twice the signal number, plus one for a due
  // wall-clock checkpoint); after a step that reduced, the maximum over the ranks (else 0).
  void request_stop(std::int64_t flags) { stop_request_ = flags; }
  std::int64_t agreed_stop() const { return stop_agreed_; }

  // Whether the drift measures the motion bound (several ranks, no controlled walls, spaced checks).
  bool measures_bounds() const { return bounds_; }
  // A new step: its drift's largest |v| and |F/m| of the free discs (with measures_bounds()), and in a deforming
  // cell the growth per step of the displacement bound's cell terms (the same on every rank).
  void start_step(const Integrator::Drift& drift, double dt, double cell_step = 0.0);
  // Whether this step must reduce before the walls move: with controlled walls every step, else when the bound or
  // the interval asks for it (it counts the steps without a reduction).
  bool due_before_walls();
  // The bound of the largest displacement since the last build over every rank, as it stands (no reduction).
  double predicted() const { return predicted_; }
  // The reduction: returns the largest displacement since the last build over every rank (`moved`: this rank's).
  // Agrees on errors and stop requests, sets the controlled walls' loads from `loads`, and decides a pending
  // balance check (a repartition of `decomposition` from the discs' and rows' work).
  // With a stress-controlled cell, its exact stress sums too: `cell` takes the servo's rates.
  double reduce(double moved, WallSet& walls, const WallLoads& loads, Decomposition& decomposition,
                const DiscStore& discs, const ContactTable& pairs, Domain& cell, const CellControl& control,
                const CellStressSums& cell_sums);

  // A balance check in the next reduction: this rank's `work` (Decomposition::rank_work). `remeasure`: the check
  // after a repartition, which measures the new map's imbalance and repartitions nothing.
  void check_balance(std::int64_t work, bool remeasure);
  // A repartition decided in a reduction, not yet carried out (the discs migrate at the next rebuild).
  bool rebalance_due() const { return rebalance_due_; }
  // The neighbour list was rebuilt: the displacement counts from zero, a pending repartition is done.
  void rebuilt() {
    rebalance_due_ = false;
    base_disp_ = predicted_ = 0.0;
  }
  // The discs' motion was changed from outside the step (a script's writes): the next step reduces, since the bound
  // of the last reduction no longer holds.
  void motion_changed() { bounds_known_ = false; }
  // The max over mean work per rank at the last balance check.
  double imbalance() const { return imbalance_; }

 private:
  const Communicator& comm_;
  const Config& config_;
  bool controlled_walls_;
  bool bounds_;
  std::exception_ptr error_;
  std::int64_t stop_request_ = 0, stop_agreed_ = 0;
  std::int64_t since_reduction_ = 0;
  double base_disp_ = 0.0, predicted_ = 0.0;      // largest displacement at the last reduction; its bound now
  double v_step_ = 0.0, a_step_ = 0.0;            // largest |v| dt and |F/m| dt^2 at the last reduction
  double cell_step_ = 0.0;                        // the cell's share of the bound's growth per step
  double drift_speed_ = 0.0, drift_accel_ = 0.0;  // this rank's largest |v| and |F/m| of this step's drift
  double dt_ = 0.0;
  bool bounds_known_ = false;  // the first step (and a restart's) reduces
  bool balance_pending_ = false, remeasure_ = false, rebalance_due_ = false;
  std::int64_t balance_work_ = 0;
  double imbalance_ = 1.0;
};

}  // namespace rondel
