#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/Domain.hpp"
#include "core/LedgerTerms.hpp"
#include "core/Wall.hpp"
#include "parallel/CanonicalOrder.hpp"
#include "parallel/Communicator.hpp"

namespace rondel {

class Hdf5File;

// The HDF5 layout of checkpoints and snapshots (FORMAT.md). Written collectively by every rank into one
// file; discs in ascending gid and contact rows in ascending key, so the content does not depend on the rank
// count (run metadata under /run_metadata and the ledger under /ledger excepted).
inline constexpr std::int64_t kStateFormatVersion = 5;
// The oldest version a reader takes: version 2 only dropped datasets of version 1 (a pair's f1, tq1, tq2, and
// M2 of an objective rolling law), so a version 1 file holds everything a restart reads; version 3 added the
// circle walls (kind 2) and the rotation of walls (/walls/centre, radius, omega, angle), which a file of an
// older version does not have (its walls neither rotate nor are circles); version 4 added
// /integrity:attributes_checksum (over every attribute), which a file of an older version is read without;
// version 5 added /cell (the periodic cell now: corner, lengths, tilt, rates, flips), without which the cell is
// the configuration's box standing still.
inline constexpr std::int64_t kOldestReadableFormatVersion = 1;

// The attributes of /cell that are numbers of the cell (its flips apart), named once for the writer and the reader.
template <class D>
auto cell_attributes(D& c) {
  using P = std::conditional_t<std::is_const_v<D>, const double*, double*>;
  return std::array<std::pair<const char*, P>, 8>{{{"xlo", &c.xlo},
                                                   {"xhi", &c.xhi},
                                                   {"ylo", &c.ylo},
                                                   {"yhi", &c.yhi},
                                                   {"tilt", &c.tilt},
                                                   {"rate_xx", &c.L.xx},
                                                   {"rate_xy", &c.L.xy},
                                                   {"rate_yy", &c.L.yy}}};
}

struct StateHeader {
  std::string kind;  // "checkpoint" or "snapshot"
  std::int64_t step = 0;
  double time = 0.0, dt = 0.0;
  std::string normal_law, tangential_law, rolling_law;
  std::vector<std::string> slots;              // history slot names, kernel order
  std::string config;                          // the resolved configuration
  LedgerTerms ledger;                          // the run's ledger (terms missing from a file read as zero)
  double box_width0 = 0.0, box_height0 = 0.0;  // the box walls' separation at the start (strain reference)
  std::string materials;  // the material table (core/Material.hpp material_table_text); "" in older files
  std::string run_id;     // the run that wrote the file (RunFiles: also in its config.ini); "" in older files
  Domain cell;            // the cell now (/cell: corner, lengths, tilt and rates; the periodic flags are the
                          // configuration's); has_cell false in older files
  bool has_cell = false;
  std::int64_t flips = 0;  // of the cell since the run began
};

// Whether a file's cell applies to the configured one: the file records one and the cell is periodic both ways.
inline bool records_cell(const StateHeader& h, const Domain& configured) {
  return h.has_cell && configured.periodic_x && configured.periodic_y;
}
// The configured cell with the shape `h` records (its lengths, corner and tilt; the rates and periodic flags stay
// the configuration's) where records_cell; else `configured` as it is.
inline Domain recorded_cell(const StateHeader& h, Domain configured) {
  if (records_cell(h, configured)) configured.take_shape(h.cell);
  return configured;
}

// Records of a group of a file other than discs and contact rows (a snapshot's bonds, the bonds' breaks): a key
// each, which sets their order in the file, and named columns, one dataset each (GROUP/NAME). `segments`: the
// records are line segments whose ends are the Vec2 columns "end1" and "end2", written as GROUP/points (2 M rows:
// each record's two ends, in place of the two columns) with GROUP/index (0 .. 2 M - 1), the XDMF line cells; otherwise
// GROUP/index
// holds the row numbers (the XDMF vertex cells of a "position" column).
struct RecordTable {
  std::vector<ContactKey> key;
  std::vector<std::pair<std::string, std::vector<double>>> reals;
  std::vector<std::pair<std::string, std::vector<std::int64_t>>> integers;
  std::vector<std::pair<std::string, std::vector<Vec2>>> vectors;
  bool segments = false;
  std::size_t size() const { return key.size(); }
};

// What a state file holds besides discs, contact rows and walls, when a run has it: a checkpoint's bond rows, a
// snapshot's bonds as segments, and the breaks since the last snapshot (both kinds of file).
struct StateExtras {
  const ContactTable* bonds = nullptr;         // /bonds of a checkpoint
  const RecordTable* bond_segments = nullptr;  // /bonds of a snapshot
  const RecordTable* breaks = nullptr;         // /breaks
};

// Writes checkpoints and snapshots (collective). `fields` selects the disc datasets of a snapshot (empty:
// every checkpointed field plus the contacts); a snapshot also gets the owner rank when "rank" is listed,
// and its row numbers ("index"). Records are put in file order by a distributed sample sort (CanonicalOrder:
// no rank holds a list of all keys) and each rank writes its block of every dataset at its prefix-sum
// offset. The records travel one dataset at a time, and every buffer is freed when the file is written: a
// checkpoint adds to the run's memory only while it is written, and at most the sort's 24 B of key and index a
// record, 4 B a row booked, one dataset's element (16 B at most) a record and, for the records that change rank,
// 4 B of index and one dataset's element sent or received (docs/scaling.md, "Memory of a run").
class StateWriter {
 public:
  // `extras`: what the run has besides (its bonds and their breaks).
  void write(const std::string& path, const StateHeader& header, DiscStore& discs, const ContactTable& pairs,
             const ContactTable& wall_rows, const WallSet& walls, const Communicator& comm,
             const std::vector<std::string>& fields, double wall_seconds, const StateExtras& extras = {});
  // The largest bytes this rank's checkpoint buffers held while writing any file so far.
  std::size_t checkpoint_structure_bytes() const { return peak_bytes_; }
  // Where the last write() spent its wall time on this rank: putting records in file order (sort,
  // splitters, exchange, merge), copying each dataset's block into place, and HDF5 (datasets, checksums,
  // attributes, opening and closing the file).
  struct Times {
    double order = 0.0, columns = 0.0, hdf5 = 0.0;
  };
  const Times& last_times() const { return times_; }

 private:
  void write_discs(Hdf5File& f, DiscStore& discs, const Communicator& comm, const std::vector<std::string>& fields);
  void write_rows(Hdf5File& f, const std::string& group, const ContactTable& rows, std::size_t n_owned,
                  const Communicator& comm);
  void write_records(Hdf5File& f, const std::string& group, const RecordTable& records, const Communicator& comm);
  // Writes one dataset of the arranged records in file order: its values *local(i) sent to the ranks whose block
  // holds them, then written (write_column); or from whole records exchanged before, a received one's value at
  // byte `at` of its record (write_arranged).
  template <class T, class Local>
  void write_column(Hdf5File& f, const std::string& name, Local&& local, const Communicator& comm);
  template <class T, class Local>
  void write_arranged(Hdf5File& f, const std::string& name, Local&& local, std::size_t at);
  std::size_t checkpoint_buffer_bytes() const;  // held now
  void note(std::size_t bytes);                 // into peak_bytes_ and the process's peak
  void release();

  CanonicalOrder order_;
  std::vector<std::uint32_t> booked_;  // the rows written, by index in their table
  std::vector<std::uint64_t> column_;  // one dataset's block (8-byte words: aligned for every type)
  Times times_;
  std::size_t peak_bytes_ = 0;
};

// One file with a writer of its own (tests and tools; a run keeps its writer in Checkpointing).
void write_state_file(const std::string& path, const StateHeader& header, DiscStore& discs, const ContactTable& pairs,
                      const ContactTable& wall_rows, const WallSet& walls, const Communicator& comm,
                      const std::vector<std::string>& fields, double wall_seconds);

// The largest checkpoint_structure_bytes() of any writer, and of the buffers of route_rows_to_owners, in
// this process so far (for the scaling audit: it must fall as 1/P at a fixed total size).
std::size_t peak_checkpoint_structure_bytes();
// Counts a structure of that many bytes into that peak (the routing's buffers, StateRouting.cpp).
void note_checkpoint_structure_bytes(std::size_t bytes);

// Collective reads (StateReader.cpp). The header is checked (format name and version, completeness); discs and rows
// come as this rank's block of the file, to be sent to their owners by the caller.
StateHeader read_state_header(const std::string& path, const Communicator& comm);
// Collective: the whole file checked, as --resume does before it takes a checkpoint: the header (format,
// version, `complete` = 1, the attributes' checksum), then every dataset read in blocks over the ranks
// against its checksum and against the row count of its group. InputError naming the file and the first
// thing wrong.
void verify_state_file(const std::string& path, const Communicator& comm);
// Number of discs the file holds.
std::uint64_t state_file_discs(const std::string& path, const Communicator& comm);
// Rows of a dataset of the file (0 when it has none).
std::int64_t state_file_rows(const std::string& path, const std::string& dataset, const Communicator& comm);
// The datasets of /discs the file holds (a snapshot has those of its output.snapshot_fields, and "index").
std::vector<std::string> state_file_disc_datasets(const std::string& path, const Communicator& comm);
void read_state_discs(const std::string& path, DiscStore& discs, const Communicator& comm);
// `bonds` (a configuration with bonds): this rank's block of /bonds too. A file with bonds read without `bonds`,
// or one without /bonds read with it, is refused (InputError naming the file): a run resumes with the bonds it had.
void read_state_rows(const std::string& path, ContactTable& pairs, ContactTable& wall_rows, const Communicator& comm,
                     ContactTable* bonds = nullptr);
WallSet read_state_walls(const std::string& path, const Communicator& comm);

// Refuses a file in which two discs share an id (InputError naming `path` and the smallest such id, on every
// rank alike; the ids must be >= 0). The same directory as route_rows_to_owners: O(N/P + P). Collective.
void check_unique_gids(const DiscStore& discs, const std::string& path, const Communicator& comm);

// Sends each row to the ranks owning its discs (both ends for disc pairs), rows sorted and de-duplicated;
// rows of a disc no rank owns are dropped. The owners are found through a distributed directory (gid g is
// registered on rank g mod P, which answers the owner of g to the ranks that ask), then each row travels
// once to each owner: O(N/P + P) per rank, no list of all discs anywhere. Collective.
void route_rows_to_owners(ContactTable& rows, bool both_ends, const DiscStore& discs, const Communicator& comm);

}  // namespace rondel
