#pragma once
#include <string>

#include "app/RunState.hpp"
#include "core/ContactTable.hpp"
#include "core/Diagnostics.hpp"
#include "core/DiscStore.hpp"
#include "core/ExactSum.hpp"
#include "core/Wall.hpp"
#include "parallel/Communicator.hpp"
#include "physics/ContactPass.hpp"
#include "physics/EnergyLedger.hpp"

namespace rondel {

// What the run reports about a simulation's present state (RunState); every function is collective.
class Reports {
 public:
  explicit Reports(const RunState& state);

  // The run's ledger: every rank's share summed.
  EnergyLedger global_ledger() const;
  // Kinetic energy of the free discs.
  double kinetic_energy() const;
  // A row of diagnostics.csv; `stored`: this rank's contact summary (the kernel's stored-energy pass);
  // `scale` receives the ledger's updated energy scale.
  DiagnosticsRow diagnostics(const ContactSummary& stored, double& scale) const;
  // Throws InstabilityError when the kinetic energy is not finite or the ledger residual is too large.
  // `d_other_peak`: the largest D_other of the run's diagnostics rows so far (updated; -inf before the
  // first): D_other, which holds the contacts' dissipation, may only grow from its start (-E_stored(0)).
  void check_stability(const DiagnosticsRow& row, double& d_other_peak) const;
  // Every disc as "gid,x,y,vx,vy,theta,omega,radius", ascending gid, on rank 0: hexadecimal floats, or
  // decimal ones with output.final_format = decimal.
  std::string state_text() const;
  // Collective: final.csv at `path`, each rank writing its block in gid order (no gather).
  void write_final(const std::string& path) const;

 private:
  // This rank's translational and rotational kinetic energy of the free discs, added to the sums.
  void kinetic_sums(ExactSum& trans, ExactSum& rot) const;
  std::string most_energetic_disc() const;

  RunState state_;
  const Communicator& comm_;
  const DiscStore& discs_;
  const ContactTable &pairs_, &wall_rows_;
  const WallSet& walls_;
  const EnergyLedger& ledger_;
};

}  // namespace rondel
