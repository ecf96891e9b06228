#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "parallel/Communicator.hpp"
#include "parallel/StateFile.hpp"

namespace rondel {

// Checkpoint and snapshot files of an output directory (docs/design.md section 7, FORMAT.md):
//  - checkpoint_<step>.h5, written under a temporary name (.checkpoint_<step>.h5.part) and renamed when
//    complete, so a killed writer never leaves a file that looks usable; the newest `keep` are kept;
//  - snapshot_<step>.h5 with the selected fields, and snapshots.xdmf listing them for ParaView.
class Checkpointing {
 public:
  Checkpointing(std::string directory, int keep, std::vector<std::string> snapshot_fields, const Communicator& comm);

  // Collective. Returns the path written.
  std::string write_checkpoint(const StateHeader& header, DiscStore& discs, const ContactTable& pairs,
                               const ContactTable& wall_rows, const WallSet& walls, double wall_seconds);
  std::string write_snapshot(const StateHeader& header, DiscStore& discs, const WallSet& walls, std::int64_t n_discs);

  // The newest checkpoint of `directory` that opens and is complete (collective); throws InputError naming
  // the directory when there is none. `skipped` receives the files passed over, with the reason.
  static std::string newest_checkpoint(const std::string& directory, const Communicator& comm,
                                       std::vector<std::string>* skipped = nullptr);
  static std::string file_name(const char* prefix, std::int64_t step);
  // A resumed run keeps the snapshots already in the directory up to `step` in its XDMF series (collective).
  void adopt_snapshots(std::int64_t step);
  // A replaced run (run.overwrite) leaves no checkpoint or snapshot that could be taken for the new one's.
  void remove_old_files() const;

 private:
  void write_xdmf() const;

  std::string dir_;
  int keep_;
  std::vector<std::string> fields_;
  const Communicator& comm_;
  struct Snapshot {
    std::string file;
    std::int64_t step, discs;
    double time;
  };
  std::vector<Snapshot> snapshots_;
};

}  // namespace rondel
