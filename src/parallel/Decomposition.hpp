#pragma once
#include <string>
#include <vector>

#include "core/CellGrid.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "parallel/Communicator.hpp"

namespace rondel {

// The cell-to-rank map of the domain decomposition (docs/design.md section 6). Cells have side >= the
// interaction range (largest contact distance plus skin), so a disc interacts only with discs of its own
// and the 8 neighbouring cells; every rank holds the whole map.
class Decomposition {
 public:
  enum class Partitioner { grid, metis };

  Decomposition(const Domain& domain, double range, Partitioner partitioner, const Communicator& comm);

  const CellGrid& grid() const { return grid_; }
  const std::vector<int>& cell_rank() const { return cell_rank_; }
  int owner(Vec2 x) const { return cell_rank_[grid_.cell_of(x)]; }
  int owner_of_cell(std::size_t c) const { return cell_rank_[c]; }
  Partitioner partitioner() const { return partitioner_; }

  // First map: grid blocks, or METIS on the per-cell work (`weights`, identical on every rank).
  void initial_partition(const std::vector<long>& weights);
  // New METIS map from the present per-cell work (no-op for the grid partitioner); parts are relabelled to
  // keep most cells where they were. Returns true when the map changed.
  bool repartition(const std::vector<long>& weights);
  // The work measure of the load balance, one definition: each owned disc and each row it books (the row of
  // its lower-gid disc) is one unit. rank_work(): this rank's units (the imbalance is their max over mean).
  // cell_work(): the same units per cell, kWorkScale each, summed over ranks, plus one in every cell (METIS
  // needs positive weights; the scale makes that one count for nothing).
  static constexpr long kWorkScale = 100;
  static double rank_work(const DiscStore& discs, const ContactTable& pairs);
  std::vector<long> cell_work(const DiscStore& discs, const ContactTable& pairs) const;
  // The first partition's weights, before any contact row exists: the discs' units, plus one in every cell
  // on each rank. `replicated`: every rank holds the whole scene (a new one), the weights are this rank's;
  // otherwise (a restart) they are summed over ranks, so the floor of a cell is the rank count rather than
  // cell_work()'s one. That difference is kept: the partition of a restart, and with it the per-rank
  // ledger shares and the imbalance, ghost and migration columns, stay those of earlier versions.
  std::vector<long> initial_weights(const DiscStore& discs, bool replicated) const;
  // Element-wise sum over ranks of a per-cell array.
  std::vector<long> sum_over_ranks(std::vector<long> values) const;
  // Number of ranks that own no cell.
  int empty_ranks() const;

 private:
  void set_map(std::vector<int> map);
  // f(i) once per owned disc i and once per booked row, with the row's disc 1.
  template <class F>
  static void for_each_work_unit(const DiscStore& discs, const ContactTable& pairs, F f) {
    const std::size_t n = discs.n_owned();
    for (std::size_t i = 0; i < n; ++i) f(i);
    for (std::size_t r = 0; r < pairs.size(); ++r)
      if (static_cast<std::size_t>(pairs.i1[r]) < n) f(static_cast<std::size_t>(pairs.i1[r]));
  }

  const Communicator& comm_;
  CellGrid grid_;
  Partitioner partitioner_;
  std::vector<int> cell_rank_;
};

}  // namespace rondel
