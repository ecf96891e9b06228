#pragma once
#include <string>
#include <vector>

#include "app/RunState.hpp"
#include "core/Config.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/SceneBuilder.hpp"
#include "core/SceneTypes.hpp"
#include "core/Wall.hpp"
#include "parallel/Communicator.hpp"
#include "parallel/StateFile.hpp"
#include "physics/EnergyLedger.hpp"
#include "physics/LawRegistry.hpp"

namespace rondel {

// A run's state in a Rondel file (FORMAT.md), both ways: the header a checkpoint or snapshot carries, and
// what a restart or a scene.type = file stage takes back from one.
class Restart {
 public:
  // Collective (the global ledger): the header of a file of `kind` ("checkpoint", "snapshot") now.
  static StateHeader header(const RunState& state, const char* kind);

  // A checkpoint to continue from: reads its header (collective) and checks that the configuration selects
  // the same laws (or run.reset_history).
  Restart(std::string path, const Config& config, const LawSelection& laws, const Communicator& comm);
  const StateHeader& file_header() const { return header_; }
  // This rank's share of the discs (throws when the file holds none).
  void read_discs(DiscStore& discs) const;
  // Wall positions and loads from the file, controls from the configuration (the counts must agree).
  void read_walls(WallSet& walls) const;
  // The contact rows, routed to the owners of their discs (distributed already); none when the laws differ.
  // `bonds` (a configuration with bonds): the file's bonds too, each to the owners of its two discs.
  void read_rows(ContactTable& pairs, ContactTable& wall_rows, const DiscStore& discs,
                 ContactTable* bonds = nullptr) const;
  // The ledger continues: every rank carries the scale, rank 0 the integrals.
  void read_ledger(EnergyLedger& ledger) const;

  // scene.type = file: this rank's block of the discs of `path` (a directory: its newest complete checkpoint);
  // box walls take their positions from the file. History, step, time and strains start afresh. Collective.
  // A cell periodic in x and y takes the file's shape (lengths and tilt; its rates stay the configuration's) into
  // `cell`.
  static std::vector<SceneDisc> scene_from_file(const std::string& path, const Config& config, WallSet& walls,
                                                Domain& cell, const Communicator& comm);

 private:
  void check_laws_match() const;
  bool same_laws() const;

  std::string path_;
  const Config& config_;
  const LawSelection& laws_;
  const Communicator& comm_;
  StateHeader header_;
};

// The reader of scene.type = file (core/SceneTypes.hpp): Restart::scene_from_file into these walls and cell, each
// rank its block; and of a CSV scene in blocks of its bytes (CsvScene.cpp).
class FileScene final : public SceneFileReader {
 public:
  FileScene(const Config& config, WallSet& walls, Domain& cell, const Communicator& comm)
      : config_(config), walls_(walls), cell_(cell), comm_(comm) {}
  std::vector<SceneDisc> discs(const std::string& path) const override {
    return Restart::scene_from_file(path, config_, walls_, cell_, comm_);
  }
  std::vector<SceneDisc> csv(const SceneConfig& s, const std::string& path) const override;

 private:
  const Config& config_;
  WallSet& walls_;
  Domain& cell_;
  const Communicator& comm_;
};

}  // namespace rondel
