#pragma once
// The serial core of one time step (docs/design.md section 4), written once for a run (Simulation) and for the
// one-contact rig of the tests (tests/physics/OneContactRig.hpp): step 1, the half kick and drift of the owned
// discs (with the last step's closing kick when it was deferred); steps 4 to 6, the sums and the contact kernel;
// step 7, the closing half kick, now or deferred to the next step's drift. What a run does between them comes in
// as hooks: steps 2 and 3 (the walls, the step's reduction, the neighbour list or the ghosts) after the drift,
// and after the kernel the checks and the walls' loads of step 6. The step's ledger terms are booked into the
// core's ledger when its closing kick is done.
#include "core/BodyForce.hpp"
#include "core/ContactParams.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/Domain.hpp"
#include "core/ForceAssembly.hpp"
#include "core/Integrator.hpp"
#include "core/Wall.hpp"
#include "physics/BondPass.hpp"
#include "physics/EnergyLedger.hpp"
#include "physics/LawRegistry.hpp"

namespace rondel {

// Where a step's time goes, for the hooks' clocks: the integrator's passes, the forces.
enum class StepPhase { integrate, force };

// The state a step changes and its settings.
struct StepInputs {
  DiscStore& discs;
  ContactTable& pairs;
  ContactTable& wall_rows;
  const ForceAssembly& assembly;
  const KernelOps& kernel;
  const Domain& domain;
  const WallSet& walls;
  const ContactParamTable& params;
  BodyForce body;
  double dt = 0.0;
  double damping = 0.0;             // run.local_damping
  double overlap_limit = INFINITY;  // run.max_overlap: the kernel reports overlaps above it
  bool bounds = false;              // the drift measures the motion bound of spaced reductions
  // The parallel bonds (nullptr: the scene has none), where their breaks are recorded, and the discs' thickness.
  ContactTable* bonds = nullptr;
  std::vector<BondBreak>* breaks = nullptr;
  double thickness = 1.0;
  std::int64_t step = 0;  // the step being taken (the bonds' break records)
  BondContext bond_context() const { return BondContext{discs, domain, params, thickness, dt, step}; }
};

// A run's hooks that do nothing (the rig's, and the base of a run's).
struct NoStepHooks {
  void lap(StepPhase) {}
  void between(const Integrator::Drift&) {}
  void after(LedgerStep&) {}
};

class StepCore {
 public:
  // The forces of the initial state for the first half kick (a new run; a restart takes them from its file): the
  // kernel with a zero increment, committing no history and booking no work (KernelOps::initial).
  static void initial_forces(const StepInputs& in) {
    ForceAssembly::begin(in.discs, in.body);
    in.kernel.initial(KernelContext{in.discs, in.domain, in.walls, in.params, 0.0}, in.pairs, in.wall_rows,
                      ForceSums::of(in.discs));
    if (in.bonds) bonds::apply(in.bond_context(), *in.bonds, ForceSums::of(in.discs));
    in.assembly.finish(in.discs);
  }

  // One time step. hooks.between(drift) runs steps 2 and 3, hooks.after(work) what follows the sums of step 6
  // (`work`: the kernel's ledger terms of the step, which it may add to), hooks.lap(phase) marks where the time
  // went. `close`: the closing kick now, else it waits for the next step's drift or close(). Returns the step's
  // kernel terms.
  template <class Hooks>
  const LedgerStep& advance(const StepInputs& in, bool close, Hooks&& hooks) {
    // 1. Half kick and drift of the owned discs (their sums start with the body force, the drift books gravity's
    //    work); a closing kick the last step deferred comes first, in the same pass, and books that step.
    const Integrator::Drift drift =
        Integrator::half_kick_drift(in.discs, in.domain, in.dt, in.body, in.bounds, in.damping, kick_pending_);
    if (kick_pending_) ledger_.add(pending_work_, pending_W_g_, pending_D_open_ + drift.D_close);
    kick_pending_ = false;
    hooks.lap(StepPhase::integrate);
    // 2, 3. The walls, the step's reduction, the neighbour list or the ghosts (the hooks).
    hooks.between(drift);
    // 4. The sums of the fixed discs and the ghosts begin (the drift began the free discs').
    in.assembly.begin_fixed_and_ghosts(in.discs);
    // 5. The contact kernel over every row, adding each row's terms to its discs' sums in ascending partner gid;
    //    then the bonds in theirs.
    work_ = LedgerStep{};
    in.kernel.run(KernelContext{in.discs, in.domain, in.walls, in.params, in.dt, in.overlap_limit}, in.pairs,
                  in.wall_rows, ForceSums::of(in.discs), work_);
    if (in.bonds) bonds::step(in.bond_context(), *in.bonds, ForceSums::of(in.discs), work_, *in.breaks);
    work_.W_cell += drift.W_cell;  // the drift's wraps in a moving cell (+0 otherwise)
    hooks.lap(StepPhase::force);
    // 6. The sums are complete; the fixed discs are finished; then the hooks (checks, loads).
    in.assembly.finish(in.discs);
    hooks.after(work_);
    hooks.lap(StepPhase::force);
    // 7. The closing half kick, or its deferral to the next step's drift (nothing looks in between).
    if (close) {
      const double D_kick = Integrator::half_kick(in.discs, in.dt, in.damping);
      ledger_.add(work_, drift.W_g, drift.D_damping + D_kick);
    } else {
      kick_pending_ = true;
      pending_work_ = work_, pending_W_g_ = drift.W_g, pending_D_open_ = drift.D_damping;
    }
    hooks.lap(StepPhase::integrate);
    return work_;
  }

  // The deferred closing kick of the last step and its ledger booking, if one is pending.
  void close(const StepInputs& in) {
    if (!kick_pending_) return;
    const double D_kick = Integrator::half_kick(in.discs, in.dt, in.damping);
    ledger_.add(pending_work_, pending_W_g_, pending_D_open_ + D_kick);
    kick_pending_ = false;
  }

  // The ledger of the steps (this rank's share of a run's).
  EnergyLedger& ledger() { return ledger_; }
  const EnergyLedger& ledger() const { return ledger_; }

 private:
  EnergyLedger ledger_;
  LedgerStep work_;
  // A deferred closing kick: the last step's terms wait for it to be booked.
  bool kick_pending_ = false;
  LedgerStep pending_work_;
  double pending_W_g_ = 0.0, pending_D_open_ = 0.0;
};

}  // namespace rondel
