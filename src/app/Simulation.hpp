#pragma once
#include <cstdint>
#include <fstream>
#include <memory>
#include <string>

#include "app/Boundaries.hpp"
#include "app/Checkpointing.hpp"
#include "app/Measures.hpp"
#include "core/Config.hpp"
#include "core/SceneBuilder.hpp"
#include "core/ContactTable.hpp"
#include "core/Diagnostics.hpp"
#include "core/DiscStore.hpp"
#include "core/ExactSum.hpp"
#include "core/ForceAssembly.hpp"
#include "core/NeighbourList.hpp"
#include "parallel/Communicator.hpp"
#include "parallel/Decomposition.hpp"
#include "parallel/DiscExchange.hpp"
#include "physics/CriticalTimeStep.hpp"
#include "physics/EnergyLedger.hpp"
#include "physics/LawRegistry.hpp"

namespace rondel {

struct RunSummary {
  int stop_signal = 0;          // the signal that stopped the run early (0: it ran to the end)
  std::string last_checkpoint;  // path of the last checkpoint written ("" if none)
  std::int64_t steps = 0;
  std::int64_t discs = 0;
  double wall_seconds = 0.0;
  double disc_steps_per_second = 0.0;
  double dt = 0.0;
  CriticalStep critical;
  double ledger_residual = 0.0;
  std::size_t neighbour_builds = 0;
};

// The composition root: builds the objects from the configuration and runs the time loop of DESIGN.md
// section 4. All set-up checks happen in the constructor, before any file is written.
class Simulation {
 public:
  // `restart_file`: continue from this checkpoint (its discs, contact history, walls, step, time, dt and
  // ledger), on any rank count; the configuration must select the same laws.
  Simulation(Config config, const Communicator& comm, bool write_files = true, const std::string& restart_file = "");

  // Runs config.steps steps with diagnostics and output; returns the summary (also logged).
  RunSummary run();
  // One time step (DESIGN.md section 4).
  void step();

  const Config& config() const { return config_; }
  const DiscStore& discs() const { return discs_; }
  DiscStore& discs() { return discs_; }
  const ContactTable& pairs() const { return pairs_; }
  const ContactTable& wall_rows() const { return wall_rows_; }
  const WallSet& walls() const { return walls_; }
  // This rank's share of the energy ledger (the whole ledger on one rank).
  const EnergyLedger& ledger() const { return ledger_; }
  // The run's ledger: every rank's share summed (collective).
  EnergyLedger global_ledger() const;
  const CriticalStep& critical() const { return critical_; }
  double dt() const { return dt_; }
  double time() const { return time_; }
  std::int64_t step_count() const { return step_; }
  std::size_t neighbour_builds() const { return neighbours_.builds(); }
  const Decomposition& decomposition() const { return *decomposition_; }
  std::size_t ghost_count() const { return exchange_.ghost_count(); }
  double imbalance() const { return imbalance_; }
  // Seconds this rank spent in the step's communication (ghost updates, rebuilds with migration, and the
  // step's reductions), including waiting for other ranks.
  double comm_seconds() const { return comm_seconds_; }
  // Collective: writes a checkpoint into the output directory now; returns its path.
  std::string write_checkpoint();
  double kinetic_energy() const;
  DiagnosticsRow diagnostics();
  // Collective: the macroscopic measures now (Measures.hpp), from the contact summary of diagnostics().
  MeasuresRow measures(const ContactSummary& contacts);
  MeasuresRow measures() { diagnostics(); return measures(summary_); }
  // Every disc as "gid,x,y,vx,vy,theta,omega" in hexadecimal floats, ascending gid (bit-exact), gathered
  // on rank 0 (collective; other ranks get an empty string).
  std::string state_text() const;

 private:
  void build_discs();
  void setup_neighbours();
  // This rank's translational and rotational kinetic energy of the free discs, added to the sums.
  void kinetic_sums(ExactSum& trans, ExactSum& rot) const;
  void setup_boundaries();
  void distribute_discs();
  void make_decomposition(bool replicated);
  // Files (SimulationFiles.cpp).
  std::vector<SceneDisc> scene_from_file();
  void load_checkpoint(const std::string& path);
  void check_laws_match(const StateHeader& header, const std::string& path) const;
  StateHeader state_header(const char* kind) const;
  void balance_load();
  void resolve_time_step();
  void check_initial_state();
  void rebuild();
  void log(const std::string& line);
  void prepare_output(bool resuming);
  void write_snapshot();
  void check_stability(const DiagnosticsRow& row) const;
  std::string most_energetic_disc() const;
  [[noreturn]] void report_overlap(const LedgerStep& work) const;

  Config config_;
  const Communicator& comm_;
  bool write_files_;
  LawSelection laws_;
  KernelOps kernel_;
  DiscStore discs_;
  WallSet walls_;
  ContactTable pairs_, wall_rows_;
  NeighbourList neighbours_;
  ForceAssembly assembly_;
  EnergyLedger ledger_;
  CriticalStep critical_;
  double dt_ = 0.0;
  double time_ = 0.0;
  std::int64_t step_ = 0;
  std::unique_ptr<Decomposition> decomposition_;
  DiscExchange exchange_;
  bool rebalance_due_ = false;
  double imbalance_ = 1.0;
  double comm_seconds_ = 0.0;
  std::size_t migrated_ = 0;
  std::unique_ptr<Checkpointing> files_;
  Boundaries boundaries_{0.2, 0.1};
  bool controlled_walls_ = false;
  bool rough_walls_ = false;
  BoxGeometry box0_;          // the box at the start of the run (reference of the strains)
  ContactSummary summary_;    // of the last diagnostics
  std::ofstream measures_;
  double wall_seconds_ = 0.0;  // wall time of earlier runs of this simulation (before a restart) and this one
  std::ofstream log_;
  DiagnosticsWriter diag_;
};

}  // namespace rondel
