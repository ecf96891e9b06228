#pragma once
// What the reports, the files and the restart read of a simulation's present state (Simulation::state()): a view,
// valid while the simulation lives and until its next step. Reports, Restart and Runner see a run through it and
// through RunTarget (Runner.hpp), not through the whole Simulation.
#include <cstddef>
#include <cstdint>

#include "app/Boundaries.hpp"
#include "core/Config.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/Wall.hpp"
#include "parallel/Communicator.hpp"
#include "physics/EnergyLedger.hpp"
#include "physics/LawRegistry.hpp"

namespace rondel {

struct RunState {
  const Config& config;
  const Communicator& comm;
  const LawSelection& laws;
  const DiscStore& discs;
  const ContactTable& pairs;
  const ContactTable& wall_rows;
  const WallSet& walls;
  const EnergyLedger& ledger;  // this rank's share (the whole ledger on one rank)
  const BoxGeometry& box0;     // the box at the start of the stage (the reference of the strains)
  std::int64_t step = 0;
  double time = 0.0, dt = 0.0;
  double imbalance = 1.0;    // max over mean work per rank at the last balance check
  std::size_t ghosts = 0;    // ghost discs this rank holds
  std::size_t migrated = 0;  // discs this rank has sent to others so far
  std::int64_t flips = 0;    // of the periodic cell since the run began (config.domain is the cell now)
  std::size_t regrids = 0;   // new decomposition grids of the deforming cell in this process (Simulation::regrid)
};

}  // namespace rondel
