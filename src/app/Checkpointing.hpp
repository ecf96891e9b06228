#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/Domain.hpp"
#include "parallel/Communicator.hpp"
#include "parallel/StateFile.hpp"

namespace rondel {

// Checkpoint and snapshot files of an output directory (docs/design.md section 7, FORMAT.md):
//  - checkpoint_<step>.h5, written under a temporary name (.checkpoint_<step>.h5.<pid>-<attempt>.part) and renamed when
//    complete, so a killed writer never leaves a file that looks usable; the newest `keep` are kept;
//  - snapshot_<step>.h5 with the selected fields, and snapshots.xdmf listing them for ParaView: per snapshot a
//    grid of discs (one vertex cell per disc) and a grid of walls (one line cell per wall, drawn within
//    `domain`, docs/paraview.md), and in a cell periodic both ways a grid of its four edges at that step.
class Checkpointing {
 public:
  // `verify`: each checkpoint is read back (verify_state_file) before it is renamed into place and older
  // ones are removed.
  Checkpointing(std::string directory, int keep, bool verify, std::vector<std::string> snapshot_fields,
                const Domain& domain, const Communicator& comm);

  // Collective. Returns the path written. A failure (IoError, on every rank: the disk, or a file that does
  // not read back as written) removes the partial file and keeps the previous checkpoints.
  std::string write_checkpoint(const StateHeader& header, DiscStore& discs, const ContactTable& pairs,
                               const ContactTable& wall_rows, const WallSet& walls, double wall_seconds,
                               const StateExtras& extras = {});
  // `extras`: the bonds as segments and the breaks since the last snapshot (a run with bonds).
  std::string write_snapshot(const StateHeader& header, DiscStore& discs, const WallSet& walls, std::int64_t n_discs,
                             const StateExtras& extras = {});

  // The newest checkpoint of `directory` that passes verify_state_file (collective): it opens, is complete,
  // and its attributes and datasets match their checksums, and it was written by the directory's run (the id
  // in its config.ini, when both have one); throws InputError naming the directory when there is none.
  // `skipped` receives the files passed over, with the reason.
  static std::string newest_checkpoint(const std::string& directory, const Communicator& comm,
                                       std::vector<std::string>* skipped = nullptr);
  static std::string file_name(const char* prefix, std::int64_t step);
  // The run id that the config.ini of `directory` names ("" when it names none: a run before the ids).
  static std::string run_id_of(const std::string& directory);
  // The drawn part of each wall, two points per wall: a segment as it is; an infinite line clipped to the
  // domain box and to the discs' side of the other lines (so the walls of a box meet at its corners).
  static std::vector<Vec2> wall_outline(const WallSet& walls, const Domain& domain);
  // The edges of a cell periodic both ways, two points per edge (bottom, right, top, left: the top shifted by
  // the tilt); none for any other domain.
  static std::vector<Vec2> cell_outline(const Domain& cell);
  // A resumed run keeps the snapshots already in the directory up to `step` in its XDMF series (collective).
  void adopt_snapshots(std::int64_t step);
  // A replaced run (run.overwrite) leaves no checkpoint or snapshot that could be taken for the new one's.
  void remove_old_files() const;
  // The peak bytes of this rank's checkpoint and snapshot structures so far (StateWriter), for the scaling
  // audit: O(N/P + P), see StateWriter::checkpoint_structure_bytes.
  std::size_t checkpoint_structure_bytes() const { return writer_.checkpoint_structure_bytes(); }

 private:
  void write_xdmf() const;

  std::string dir_;
  int keep_;
  bool verify_;
  std::vector<std::string> fields_;
  Domain domain_;
  const Communicator& comm_;
  std::int64_t token_;         // rank 0's process id: part of every temporary checkpoint name
  std::int64_t attempts_ = 0;  // checkpoints attempted by this run (the other part)
  StateWriter writer_;         // kept across files: its buffers are reused
  struct Snapshot {
    std::string file;
    std::int64_t step, discs;
    double time;
    std::vector<std::string> fields;     // the /discs datasets the file holds
    std::vector<Vec2> walls;             // wall_outline() at that step
    std::vector<Vec2> cell;              // cell_outline() at that step
    std::int64_t bonds = 0, breaks = 0;  // the rows of /bonds and /breaks (a run with bonds)
  };
  std::vector<Snapshot> snapshots_;
};

}  // namespace rondel
