#pragma once
#include <cstdint>
#include <exception>
#include <memory>
#include <string>
#include <utility>

#include "app/Boundaries.hpp"
#include "app/CellControl.hpp"
#include "app/DriverForces.hpp"
#include "app/Measures.hpp"
#include "app/PhaseTimes.hpp"
#include "app/RunFiles.hpp"
#include "app/RunState.hpp"
#include "app/Runner.hpp"
#include "app/StepReduction.hpp"
#include "core/Config.hpp"
#include "core/ContactTable.hpp"
#include "core/Diagnostics.hpp"
#include "core/DiscStore.hpp"
#include "core/ForceAssembly.hpp"
#include "core/NeighbourList.hpp"
#include "parallel/Communicator.hpp"
#include "parallel/Decomposition.hpp"
#include "parallel/DiscExchange.hpp"
#include "physics/CriticalTimeStep.hpp"
#include "physics/EnergyLedger.hpp"
#include "physics/LawRegistry.hpp"
#include "physics/StepCore.hpp"

namespace rondel {

// The composition root: builds the objects from the configuration and steps them (docs/design.md section 4).
// All set-up checks happen in the constructor, before any file is written. The run loop is Runner's, the
// files RunFiles', the file state Restart's, the reports Reports' and the measures Measures'.
class Simulation final : public RunTarget {
 public:
  // `restart_file`: continue from this checkpoint (its discs, contact history, walls, step, time, dt and
  // ledger), on any rank count; the configuration must select the same laws.
  Simulation(Config config, const Communicator& comm, bool write_files = true, const std::string& restart_file = "");
  Simulation(const Simulation&) = delete;  // its parts hold references to its configuration
  Simulation& operator=(const Simulation&) = delete;

  // Runs config.steps steps with diagnostics and output; returns the summary (also logged).
  RunSummary run() { return Runner(*this).run(); }
  std::int64_t advance_steps(std::int64_t n, const std::function<std::int64_t()>& stop_flags) override {
    return advance(n, stop_flags);
  }
  // The skin, the neighbour builds, and what this object's steps asked of MPI (collectives, messages, bytes).
  RunCounts counts() const override { return {neighbours_.skin(), neighbours_.builds(), steps_taken_, step_comm_}; }
  // One time step (docs/design.md section 4). On several ranks it makes at most one collective call (none
  // on most steps of a scene without controlled walls) and talks point to point with neighbouring ranks.
  void step() { advance_step(true); }
  // Up to n steps that nothing looks at in between: each step's closing half kick (step 7) is deferred and
  // done in the next step's first pass over the discs (Integrator::half_kick_drift), which saves a pass per
  // step and changes no bit. Before each step `stop_flags()` gives this rank's stop request
  // (request_stop); after a step whose reduction agreed on a stop it returns early. The state is complete
  // (full-step velocities, ledger booked) when it returns. Returns the steps taken.
  template <class StopFlags>
  std::int64_t advance(std::int64_t n, StopFlags&& stop_flags) {
    std::int64_t done = 0;
    while (done < n) {
      request_stop(stop_flags());
      advance_step(++done == n);
      if (agreed_stop() != 0) break;
    }
    close_step();
    return done;
  }
  // Collective: agrees on any rank's pending error (every rank throws it) and brings the walls' loads up
  // to this step. Every output below calls it first.
  void settle_errors() override;
  // The stop request of this rank for the coming step (Runner: twice the signal number, plus one for a
  // due wall-clock checkpoint) and, after step(), the maximum over the ranks if the step reduced (else 0).
  void request_stop(std::int64_t flags) { reduction_.request_stop(flags); }
  std::int64_t agreed_stop() const override { return reduction_.agreed_stop(); }
  // Bytes this rank holds for the decomposition, the exchanges and the neighbour search (the scaling audit).
  std::size_t decomposition_bytes() const { return decomposition_->memory_bytes(); }
  std::size_t exchange_bytes() const { return exchange_.memory_bytes(); }
  std::size_t neighbour_bytes() const { return neighbours_.memory_bytes(); }

  // A view of the present state for the reports, the files and the restart (RunState.hpp).
  RunState state() const override;
  const Config& config() const { return config_; }
  const Communicator& comm() const { return comm_; }
  const DiscStore& discs() const { return discs_; }
  DiscStore& discs() { return discs_; }
  const ContactTable& pairs() const { return pairs_; }
  const ContactTable& wall_rows() const { return wall_rows_; }
  // The parallel bonds on this rank (an empty table without bonds).
  const ContactTable& bonds() const { return bonds_; }
  const WallSet& walls() const { return walls_; }
  // This rank's share of the energy ledger (the whole ledger on one rank).
  const EnergyLedger& ledger() const { return core_.ledger(); }
  // The run's ledger: every rank's share summed (collective).
  EnergyLedger global_ledger() const;
  const CriticalStep& critical() const override { return critical_; }
  double dt() const { return dt_; }
  double time() const { return time_; }
  std::int64_t step_count() const { return step_; }
  const Decomposition& decomposition() const { return *decomposition_; }
  // This rank's seconds per phase so far (PhaseTimes.hpp), set-up included.
  const PhaseTimes& phases() const { return phases_; }
  PhaseTimes& phases() override { return phases_; }
  // Seconds this rank spent in communication (ghost updates, rebuilds with migration, and the step's
  // reductions), including waiting for other ranks.
  double comm_seconds() const { return phases_.seconds(PhaseTimes::communication); }
  RunFiles& files() override { return files_; }
  // A script's writes between steps (the Python module, app/Steering.hpp). `edit` changes this rank's owned discs
  // and returns the kinetic energy it added here, booked as W_driver; the list of fixed discs follows and the next
  // step reduces (the motion bound of the last reduction no longer holds).
  void edit_discs(const std::function<double(DiscStore&)>& edit);
  // A script changed the motion otherwise (the cell's rates): the next step reduces.
  void motion_changed() { reduction_.motion_changed(); }
  // The walls, for a script's control of their velocities and servo targets (from the next step on).
  WallSet& steered_walls() { return walls_; }
  // A script's body forces on some discs (DriverForces.hpp), from the next step on.
  void set_driver_forces(const std::vector<std::int64_t>& gids, const std::vector<Vec2>& forces) {
    driver_forces_.set(gids, forces, discs_);
  }
  const DriverForces& driver_forces() const { return driver_forces_; }
  // The cell (the domain), for a script's control of its rates, and its stress control's targets.
  Domain& steered_cell() { return config_.domain; }
  CellControl& steered_cell_control() { return cell_control_; }
  // Collective: writes a checkpoint into the output directory now; returns its path.
  std::string write_checkpoint() override;
  // Collective: a snapshot into the output directory now.
  void write_snapshot() override;
  double kinetic_energy() const;
  DiagnosticsRow diagnostics() override;
  // This rank's contact summary at the last diagnostics() (counts, stored energy).
  const ContactSummary& last_contacts() const override { return summary_; }
  // Collective: the macroscopic measures now (Measures.hpp), from the contact summary of diagnostics().
  MeasuresRow measures(const ContactSummary& contacts) override;
  MeasuresRow measures() {
    diagnostics();
    return measures(summary_);
  }
  // Every disc as "gid,x,y,vx,vy,theta,omega" in hexadecimal floats, ascending gid (bit-exact), gathered
  // on rank 0 (collective; other ranks get an empty string).
  std::string state_text() const;
  // Collective: the same lines as final.csv at `path`, written by every rank in gid order (MPI-IO, no
  // gather: what a run writes; state_text() serves tests).
  void write_final(const std::string& path) const override;

 private:
  void build_discs();
  // The scene's discs, each checked to lie in the domain (every rank builds the whole scene).
  void add_scene_discs();
  // The largest and smallest radius, the sum of the radii and the count of every disc, once the discs exist (created or
  // loaded).
  void measure_radii();
  // walls.rough_materials, once the discs are glued; a warning for a material that nothing uses.
  void assign_rough_materials();
  void warn_unused_materials() const;
  void setup_neighbours();
  // neighbour.skin, or by default a quarter of the discs' mean radius.
  double skin_for(double mean_radius) const { return config_.skin > 0.0 ? config_.skin : 0.25 * mean_radius; }
  // A periodic length holds at least twice the interaction range.
  void check_periodic_lengths() const;
  void setup_boundaries();
  // The discs to the owners of their cells (each rank keeps its own of a whole scene; blocks are routed; a scene
  // built cell by cell is there already).
  void distribute_discs();
  // `units` (a scene built cell by cell): the first map weighted by the discs each cell will hold.
  void make_decomposition(bool replicated, double range, const Partition::RectUnits* units = nullptr);
  void load_checkpoint(const std::string& path);
  // The deformed cell of a checkpoint (its shape and flips; the rates are this configuration's).
  void resume_cell(const StateHeader& h, const std::string& path);
  // Collective, before the first file is written: a stop signal received during set-up (by any rank) ends it
  // here, every rank alike (StoppedInSetup, exit 10), the output directory as it was.
  void stop_if_signalled(const std::string& restart_file) const;
  // A wall that carries glued discs in the checkpoint stays rough.
  void keep_rough_walls(const std::string& path);
  void resolve_time_step();
  // A resumed run's time step: run.dt when it differs from the checkpoint's, else the checkpoint's, checked
  // against this configuration's critical step.
  void resume_time_step(double file_dt, const std::string& path);
  // The initial overlaps over every rank's discs (on the first neighbour list): refused above
  // scene.max_initial_overlap.
  void check_initial_overlaps();
  // Discs anywhere (a scene built in blocks, a checkpoint read in blocks, a new grid) to the ranks that own their
  // cells on a new decomposition; settle_owners: to the cut weighted by their work.
  void route_to_owners();
  void settle_owners();
  // `on_owners`: every disc is on the owner of its cell (right after distribute_discs), so no migration is due.
  void rebuild(bool on_owners = false);
  // A deforming cell: its step h += dt L h and its flip (SimulationStep.cpp); its shape into the decomposition's
  // grid at a rebuild (a new grid when the cell has halved or doubled a side's cells), refused when a length has
  // fallen below twice the interaction range.
  void deform_cell();
  void follow_cell();
  void regrid();
  // The smallest and most tilted cell of the run (a decomposition grid's counts serve it all).
  Domain cell_sizing() const;
  // The inputs of the step's serial core (StepCore); `bounds`: the drift measures the motion bound.
  StepInputs step_inputs(bool bounds);
  // The bond table when the scene has bonds, else nullptr.
  ContactTable* bond_rows() { return config_.bonds ? &bonds_ : nullptr; }
  // The bonds of a new scene on its first neighbour list (bonds.gap), and their local indices after a rebuild.
  void create_bonds();
  void bonds_from_file();  // bonds.file's pairs, checked
  void relink_bonds();
  // step() with `close`; without it the closing kick and the step's ledger booking wait for the next step's
  // drift or close_step().
  void advance_step(bool close);
  // The deferred closing kick of the last step and its ledger booking, if one is pending.
  void close_step();
  // The run's parts of a step (SimulationStep.cpp): steps 2 and 3 after the drift, and what follows the sums.
  struct StepHooks;
  void walls_and_neighbours(const Integrator::Drift& drift);
  void after_kernel(LedgerStep& work);
  std::exception_ptr overlap_error(const LedgerStep& work) const;
  std::exception_ptr motion_error(double moved) const;

  Config config_;
  const Communicator& comm_;
  bool write_files_;
  LawSelection laws_;
  KernelOps kernel_;
  DiscStore discs_;
  WallSet walls_;
  ContactTable pairs_, wall_rows_;
  ContactTable bonds_;             // the parallel bonds (a bond table when config_.bonds; else empty and unused)
  std::vector<BondBreak> breaks_;  // the breaks this rank booked since the last diagnostics
  NeighbourList neighbours_;
  ForceAssembly assembly_;
  StepCore core_;  // the step's serial core and the ledger of the steps
  CriticalStep critical_;
  double dt_ = 0.0;
  double time_ = 0.0;
  std::int64_t step_ = 0;
  double R_min_ = 0.0, R_max_ = 0.0, R_total_ = 0.0;  // over every disc (measure_radii): extremes, sum
  std::int64_t n_discs_ = 0;                          // every disc (measure_radii)
  std::unique_ptr<Decomposition> decomposition_;
  bool weighed_ = false;  // the first map was weighted by the discs the scene will place (no repartition due)
  DiscExchange exchange_;
  PhaseTimes phases_;
  std::size_t migrated_ = 0;
  std::size_t regrids_ = 0;  // new decomposition grids of a deforming cell (regrid)
  RunFiles files_;
  Boundaries boundaries_{0.2, 0.1};
  BoxGeometry box0_;            // the box at the start of the run (reference of the strains)
  ContactSummary summary_;      // of the last diagnostics
  DriverForces driver_forces_;  // a script's body forces (empty in a run of the executable)
  CellControl cell_control_;    // the servo of a stress-controlled cell
  StepReduction reduction_;     // the step's one reduction (docs/scaling.md)
  WallLoads loads_;             // this rank's part of the controlled walls' loads, of the last step
  CellStressSums cell_sums_;    // this rank's part of its contact stress, of the last step
  bool repartitioned_ = false;  // the last step migrated the discs to a new map
  bool cell_rebuild_ = false;   // the cell flipped: this step builds a new list
  double cell_step_ = 0.0;      // a deforming cell's growth of the displacement bound per step
  std::int64_t flips_ = 0;      // of the cell since the run began, with their sign (Domain::flip)
  std::int64_t steps_taken_ = 0;
  CommStats step_comm_;
};

}  // namespace rondel
