#pragma once
// Test support: a checkpoint in which only the disc of the highest gid lies behind a wall. A resume reads
// the discs in blocks by gid, one block per rank, so on N ranks only the last rank finds the error (the
// check of Simulation::setup_neighbours): the case of an error found on one rank other than 0.
#include <filesystem>
#include <string>

#include "core/Config.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "parallel/Communicator.hpp"
#include "parallel/StateFile.hpp"
#include "physics/LawRegistry.hpp"

namespace rondel::test {

constexpr int kBehindWallDiscs = 12;
// The message every rank must report.
inline std::string behind_wall_message() {
  return "disc " + std::to_string(kBehindWallDiscs - 1) + " lies behind wall 0";
}

// The configuration of the checkpoint: discs above the line y = 0.2 (normal up), no gravity.
inline std::string behind_wall_ini(const std::filesystem::path& output) {
  return "[run]\nsteps = 20\nprogress = false\noutput = " + output.string() + R"(
[domain]
xlo = 0
xhi = 1
ylo = 0
yhi = 1
[material]
density = 1000
[linear]
k_n = 1e5
zeta = 0.3
[coulomb]
k_s = 5e4
mu = 0.5
[walls]
lines = 0 0.2 0 1
[scene]
type = random
count = 1
radius_min = 0.02
radius_max = 0.02
)";
}

// Writes checkpoint_0000000005.h5 of `config` into `dir` (this process alone): kBehindWallDiscs discs at
// rest in a row at y = 0.6, except the last, at y = 0.1, behind the wall.
inline std::filesystem::path write_behind_wall_checkpoint(const std::filesystem::path& dir, const Config& config) {
  const LawSelection laws = law_selection(config);
  DiscStore discs;
  for (int i = 0; i < kBehindWallDiscs; ++i) {
    const double y = i + 1 == kBehindWallDiscs ? 0.1 : 0.6;
    discs.add(i, 0, 0.02, config.materials.front().density, config.thickness, Vec2{0.05 + 0.07 * i, y});
  }
  StateHeader h;
  h.kind = "checkpoint";
  h.step = 5;
  h.dt = 1e-4;
  h.time = 5e-4;
  h.normal_law = config.normal_law;
  h.tangential_law = config.tangential_law;
  h.rolling_law = config.rolling_law;
  h.slots = history_slots(laws);
  h.config = config.resolved_text;
  std::filesystem::create_directories(dir);
  const std::filesystem::path path = dir / "checkpoint_0000000005.h5";
  const ContactTable pairs = make_contact_table(laws, false), wall_rows = make_contact_table(laws, true);
  write_state_file(path.string(), h, discs, pairs, wall_rows, config.walls, Communicator::self(), {}, 0.0);
  return path;
}

}  // namespace rondel::test
