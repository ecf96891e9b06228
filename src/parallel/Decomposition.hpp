#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/CellGrid.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "parallel/Communicator.hpp"
#include "parallel/Hilbert.hpp"
#include "parallel/Partition.hpp"

namespace rondel {

// The cell-to-rank map of the domain decomposition (docs/design.md section 6, docs/scaling.md). Cells have
// side >= the interaction range (largest contact distance plus skin), so a disc interacts only with discs
// of its own and the 8 neighbouring cells. The map is a Partition of the partitioner named in
// parallel.partitioner (core/Partitioners.hpp, parallel/Partition.hpp); no rank holds anything over all cells
// (but metis, which is for moderate sizes).
// Each rank keeps the owners of its cells and of the cells around them in a small table (its bounding box
// plus one cell), its neighbouring ranks (those owning a cell next to one of its cells) and, after a change
// of map, the ranks it sends discs to and receives discs from in the next migration.
class Decomposition {
 public:
  // `partitioner`: a word of parallel.partitioner; `sizing`: the smallest, most tilted cell of the run (a
  // deforming cell's grid counts are fixed for the run, CellGrid).
  Decomposition(const Domain& domain, double range, const std::string& partitioner, const Communicator& comm,
                const Domain& sizing);
  Decomposition(const Domain& domain, double range, const std::string& partitioner, const Communicator& comm)
      : Decomposition(domain, range, partitioner, comm, domain) {}

  const CellGrid& grid() const { return grid_; }
  // A deforming cell's shape now (the cells' counts and owners kept): before a migration.
  void follow(const Domain& domain) { grid_.follow(domain); }
  int owner(Vec2 x) const { return owner_at(grid_.column_of(x), grid_.row_of(x.y)); }
  // Any cell's owner: from the table of this rank's neighbourhood, else from the map.
  int owner_of_cell(std::size_t c) const;
  const std::string& partitioner() const { return partitioner_; }
  // The ranks but this one owning a cell of the stencil around the cell of x, ascending, into `out` (a ghost's
  // destinations; none for an inner cell of this rank).
  void ghost_ranks(Vec2 x, std::vector<int>& out) const {
    const int cx = grid_.column_of(x), cy = grid_.row_of(x.y);
    const std::size_t at = box_at(cx, cy);
    if (at != kOutside && box_owner_[at] == comm_.rank() && !box_border_[at])
      out.clear();
    else
      ranks_around(grid_.index(cx, cy), out);
  }
  // This rank's cells in row-major order (ascending index).
  std::vector<std::size_t> own_cells() const;
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
  // First map, before any disc exists, weighted by the discs each cell will hold (Partition::weigh): true when
  // the partitioner could (no repartition() is due once the discs are built), else the equal-cell cut.
  bool initial_partition(const Partition::RectUnits& units);
  // A new map from the present work (collective); returns true when it changed.
  bool repartition(const DiscStore& discs, const ContactTable& pairs);

  // The work measure of the load balance (for_each_work_unit, Partition.hpp): a cell weighs kWorkScale per unit
  // plus one (so that empty space counts a little; see kCurveScale for sfc). rank_work(): this rank's units (the
  // imbalance is their max over mean).
  static constexpr long kWorkScale = 100;  // metis (its weights are 32-bit integers)
  // sfc: a unit weighs 2^16 cells, so the empty cells of a large sparse domain (a chamber, a hopper's air)
  // do not shift the cuts by a measurable part of the discs' work. 64-bit sums, 128-bit cut targets.
  static constexpr std::uint64_t kCurveScale = std::uint64_t{1} << 16;
  static std::int64_t rank_work(const DiscStore& discs, const ContactTable& pairs);
  // Number of ranks that own no cell.
  int empty_ranks() const { return map_->empty_ranks(); }
  // Bytes this rank holds for the decomposition (map, neighbourhood table, partner lists).
  std::size_t memory_bytes() const;

 private:
  // The neighbourhood table, the neighbours and (`old`: the map before) the migration partners of the map.
  void install(const Partition* old);
  // The neighbourhood table's extent for this rank's cells (none for a scattered map), and its owners by `map`.
  void frame(const Partition::Extent& mine);
  std::vector<int> owners_in_box(const Partition& map) const;
  // f(owner) for each cell of the stencil around `cell` (`at`: its entry in the table, or kOutside) by `map`, its
  // table over the box `box`.
  template <class F>
  void owners_around(std::size_t cell, std::size_t at, const std::vector<int>& box, const Partition& map, F f) const;
  // visit(cell, at) for this rank's cells (`cells` when there is no table) but, when `skip_inner`, the table's
  // inner cells with only this rank's cells around them.
  template <class F>
  void for_each_own(const std::vector<std::size_t>& cells, bool skip_inner, F visit) const;
  // The ranks but this one around `cell` (ghost_ranks beyond the inner cells).
  void ranks_around(std::size_t cell, std::vector<int>& out) const;
  // The owner of cell (cx, cy): the table's, else the map's (one rank: this one).
  int owner_at(int cx, int cy) const {
    const std::size_t at = box_at(cx, cy);
    return at != kOutside ? box_owner_[at] : comm_.size() == 1 ? 0 : map_->owner(grid_.index(cx, cy));
  }
  // The entry of cell (cx, cy) in the neighbourhood table, kOutside beyond it.
  static constexpr std::size_t kOutside = SIZE_MAX;
  std::size_t box_at(int cx, int cy) const {
    const int x = cx - box_x0_, y = cy - box_y0_;
    return x >= 0 && x < box_nx_ && y >= 0 && y < box_ny_ ? static_cast<std::size_t>(y) * box_nx_ + x : kOutside;
  }
  std::size_t box_at(std::size_t c) const {
    return box_at(static_cast<int>(c % static_cast<std::size_t>(grid_.nx())),
                  static_cast<int>(c / static_cast<std::size_t>(grid_.nx())));
  }

  const Communicator& comm_;
  CellGrid grid_;
  HilbertGrid curve_;
  std::string partitioner_;
  std::unique_ptr<Partition> map_;
  int box_x0_ = 0, box_y0_ = 0, box_nx_ = 0, box_ny_ = 0;
  std::vector<int> box_owner_;
  std::vector<std::uint8_t> box_border_;  // 1 for a cell of this rank with another rank's cell around it
  std::vector<int> neighbours_, send_to_, receive_from_;
  std::int64_t own_cells_ = 0;
};

}  // namespace rondel
