#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/CellGrid.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "parallel/Communicator.hpp"
#include "parallel/Hilbert.hpp"

namespace rondel {

// The cell-to-rank map of the domain decomposition (docs/design.md section 6, docs/scaling.md). Cells have
// side >= the interaction range (largest contact distance plus skin), so a disc interacts only with discs
// of its own and the 8 neighbouring cells. No rank holds anything over all cells:
//  - sfc (default): the cells in Hilbert-curve order (Hilbert.hpp) cut into P contiguous key ranges of equal
//    work; the map is the P + 1 cut keys, the same on every rank, and a repartition moves the cuts, so most
//    work stays in place. The cuts are found from distributed prefix sums (two scans and one reduction).
//  - grid: px x py blocks of cells (no table).
//  - metis: a k-way METIS partition of the whole cell graph, computed on rank 0 and broadcast: every rank
//    holds the whole map (O(cells) per rank); kept for graph-quality partitions of moderate size.
// Each rank keeps the owners of its cells and of the cells around them in a small table (its bounding box
// plus one cell), its neighbouring ranks (those owning a cell next to one of its cells) and, after a change
// of map, the ranks it sends discs to and receives discs from in the next migration.
class Decomposition {
 public:
  enum class Partitioner { sfc, grid, metis };

  Decomposition(const Domain& domain, double range, Partitioner partitioner, const Communicator& comm);

  const CellGrid& grid() const { return grid_; }
  int owner(Vec2 x) const { return owner_of_cell(grid_.cell_of(x)); }
  // Any cell's owner: from the table of this rank's neighbourhood, else from the map.
  int owner_of_cell(std::size_t c) const;
  Partitioner partitioner() const { return partitioner_; }
  // Ranks owning a cell next to one of this rank's cells (periodic images included), ascending, not this one.
  const std::vector<int>& neighbours() const { return neighbours_; }
  // The partners of the next migration: the neighbours, or after a change of map every rank that may send
  // here (an old owner of a cell next to one of this rank's new cells) and every rank this one may send to.
  // The relation is symmetric, so each rank knows whom to expect. migrated() returns to the neighbours.
  const std::vector<int>& send_to() const { return send_to_; }
  const std::vector<int>& receive_from() const { return receive_from_; }
  void migrated();

  // First map. `replicated`: every rank holds every disc (a new scene), so the weighted map is computed on
  // every rank alike from its own discs (no communication). Otherwise (a restart, discs spread by file
  // block) sfc starts from an equal-cell cut: the caller migrates the discs (to any rank), then calls
  // repartition() for the weighted cut.
  void initial_partition(const DiscStore& discs, bool replicated);
  // A new map from the present work (collective); returns true when it changed.
  bool repartition(const DiscStore& discs, const ContactTable& pairs);

  // The work measure of the load balance, one definition: each owned disc and each row it books (the row of
  // its lower-gid disc) is one unit; a cell weighs kWorkScale per unit plus one (so that empty space counts
  // a little; see kCurveScale for sfc). rank_work(): this rank's units (the imbalance is their max over mean).
  static constexpr long kWorkScale = 100;  // metis (its weights are 32-bit integers)
  // sfc: a unit weighs 2^16 cells, so the empty cells of a large sparse domain (a chamber, a hopper's air)
  // do not shift the cuts by a measurable part of the discs' work. 64-bit sums, 128-bit cut targets.
  static constexpr std::uint64_t kCurveScale = std::uint64_t{1} << 16;
  static std::int64_t rank_work(const DiscStore& discs, const ContactTable& pairs);
  // Number of ranks that own no cell.
  int empty_ranks() const;
  // Bytes this rank holds for the decomposition (map, neighbourhood table, partner lists).
  std::size_t memory_bytes() const;

 private:
  struct Map {
    std::vector<std::uint64_t> cuts;  // sfc: rank r owns keys [cuts[r], cuts[r + 1])
    std::vector<int> table;           // metis: owner of every cell
  };
  int owner_in(const Map& m, std::size_t c) const;
  void for_each_cell(const Map& m, int rank, const std::function<void(std::size_t)>& f) const;
  // Makes `next` the map: the neighbourhood table, the neighbours and the migration partners from the old map.
  void install(Map next, bool first);
  // (cell key, extra weight) of this rank's work units, ascending key, one entry per cell.
  std::vector<std::pair<std::uint64_t, std::uint64_t>> weighted_cells(const DiscStore& discs,
                                                                      const ContactTable& pairs) const;
  void clamp_into(std::vector<std::pair<std::uint64_t, std::uint64_t>>& cells, std::uint64_t lo,
                  std::uint64_t hi) const;
  std::vector<std::uint64_t> weighted_cuts(const std::vector<std::pair<std::uint64_t, std::uint64_t>>& cells,
                                           std::uint64_t lo, std::uint64_t hi, std::uint64_t offset,
                                           std::uint64_t total) const;
  std::vector<long> metis_weights(const DiscStore& discs, const ContactTable& pairs, bool replicated) const;
  void set_metis(const std::vector<long>& weights, const std::vector<int>& previous, bool first);

  const Communicator& comm_;
  CellGrid grid_;
  HilbertGrid curve_;
  Partitioner partitioner_;
  std::pair<int, int> blocks_{1, 1};
  Map map_;
  int box_x0_ = 0, box_y0_ = 0, box_nx_ = 0, box_ny_ = 0;
  std::vector<int> box_owner_;
  std::vector<int> neighbours_, send_to_, receive_from_;
  std::int64_t own_cells_ = 0;
};

}  // namespace rondel
