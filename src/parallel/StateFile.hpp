#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/LedgerTerms.hpp"
#include "core/Wall.hpp"
#include "parallel/Communicator.hpp"

namespace rondel {

// The HDF5 layout of checkpoints and snapshots (FORMAT.md). Written collectively by every rank into one
// file; discs in ascending gid and contact rows in ascending key, so the content does not depend on the rank
// count (run metadata under /run_metadata and the ledger under /ledger excepted).
inline constexpr std::int64_t kStateFormatVersion = 1;

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
};

// Collective. `fields` selects the disc datasets of a snapshot (empty: every checkpointed field plus the
// contacts); a snapshot also gets the owner rank when "rank" is listed, and its row numbers ("index").
void write_state_file(const std::string& path, const StateHeader& header, DiscStore& discs, const ContactTable& pairs,
                      const ContactTable& wall_rows, const WallSet& walls, const Communicator& comm,
                      const std::vector<std::string>& fields, double wall_seconds);

// Collective reads. The header is checked (format name and version, completeness); discs and rows come as
// this rank's block of the file, to be sent to their owners by the caller.
StateHeader read_state_header(const std::string& path, const Communicator& comm);
// Number of discs the file holds.
std::uint64_t state_file_discs(const std::string& path, const Communicator& comm);
// The datasets of /discs the file holds (a snapshot has those of its output.snapshot_fields, and "index").
std::vector<std::string> state_file_disc_datasets(const std::string& path, const Communicator& comm);
void read_state_discs(const std::string& path, DiscStore& discs, const Communicator& comm);
void read_state_rows(const std::string& path, ContactTable& pairs, ContactTable& wall_rows, const Communicator& comm);
WallSet read_state_walls(const std::string& path, const Communicator& comm);

// Sends each row to the ranks owning its discs (both ends for disc pairs), rows sorted and de-duplicated.
void route_rows_to_owners(ContactTable& rows, bool both_ends, const DiscStore& discs, const Communicator& comm);

}  // namespace rondel
