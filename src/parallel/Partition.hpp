#pragma once
// A cell-to-rank map and the way to make it from the work: one implementation per partitioner of the registry
// (core/Partitioners.hpp), each in its own file (PartitionSfc.cpp, PartitionGrid.cpp, PartitionMetis.cpp) with its
// make_partition overload declared here. make_partition(name, ...) instantiates the overload of every tag of the
// registry, so a tag without one does not compile. Decomposition holds one and asks it for owners and cells.
#include <algorithm>
#include <climits>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "core/CellGrid.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/Partitioners.hpp"
#include "parallel/Communicator.hpp"
#include "parallel/Hilbert.hpp"

namespace rondel {

// What a partition needs: the cells, their Hilbert keys and the ranks.
struct PartitionContext {
  const CellGrid& grid;
  const HilbertGrid& curve;
  const Communicator& comm;
};

class Partition {
 public:
  virtual ~Partition() = default;
  // The same map, to compare the next one with (the partners of a migration after a change of map).
  virtual std::unique_ptr<Partition> copy() const = 0;
  // The owner of cell c (any cell), and f(c) for every cell of `rank`.
  virtual int owner(std::size_t c) const = 0;
  virtual void for_each_cell(int rank, const std::function<void(std::size_t)>& f) const = 0;
  // The cells of `rank`: how many, and their bounding rectangle [x0, x1) x [y0, y1) (empty when none).
  struct Extent {
    std::int64_t count = 0;
    int x0 = INT_MAX, y0 = INT_MAX, x1 = INT_MIN, y1 = INT_MIN;
    void add(int a0, int b0, int a1, int b1) {
      count += static_cast<std::int64_t>(a1 - a0) * (b1 - b0);
      x0 = std::min(x0, a0), y0 = std::min(y0, b0), x1 = std::max(x1, a1), y1 = std::max(y1, b1);
    }
  };
  virtual Extent extent(int rank) const;
  // The owners of the cells [x0, x1) x [y0, y1) (within the grid) row by row into `out`.
  virtual void owners_in(int x0, int y0, int x1, int y1, int* out) const;
  // The first map. `replicated`: every rank holds every disc (a new scene), so the weighted map is computed on
  // every rank alike without communication; otherwise (discs spread by file block) a map that the caller
  // migrates the discs with before repartition() weighs them.
  virtual void initial(const DiscStore& discs, bool replicated) = 0;
  // A new map from the present work (collective); false when it did not change or this partitioner keeps its map.
  virtual bool repartition(const DiscStore& discs, const ContactTable& pairs) = 0;
  // After initial(): the map weighted by the discs the cells will hold, before any disc exists: the map
  // repartition() would make from those discs. `units(x0, y0, x1, y1)`: the discs of the cells [x0, x1) x
  // [y0, y1). False when this partitioner cannot (the caller builds the discs on this map and calls
  // repartition()).
  using RectUnits = HilbertGrid::RectWeight;
  virtual bool weigh(const RectUnits& /*units*/) { return false; }
  // The number of ranks that own no cell.
  virtual int empty_ranks() const = 0;
  virtual std::size_t memory_bytes() const = 0;

 protected:
  explicit Partition(const CellGrid& grid) : grid_(grid) {}
  Partition(const Partition&) = default;
  const CellGrid& grid_;
};

// The work measure of the load balance, one definition: each owned disc and each row it books (the row of its
// lower-gid disc) is one unit; f(i) once per unit with the disc i it is counted at.
template <class F>
void for_each_work_unit(const DiscStore& discs, const ContactTable& pairs, F f) {
  const std::size_t n = discs.n_owned();
  for (std::size_t i = 0; i < n; ++i) f(i);
  for (std::size_t r = 0; r < pairs.size(); ++r)
    if (static_cast<std::size_t>(pairs.i1[r]) < n) f(static_cast<std::size_t>(pairs.i1[r]));
}

// One overload per partitioner of the registry.
std::unique_ptr<Partition> make_partition(SfcPartitioner, const PartitionContext& context);
std::unique_ptr<Partition> make_partition(GridPartitioner, const PartitionContext& context);
std::unique_ptr<Partition> make_partition(MetisPartitioner, const PartitionContext& context);

// The partition of the partitioner named `name` (a word of parallel.partitioner).
std::unique_ptr<Partition> make_partition(const std::string& name, const PartitionContext& context);

}  // namespace rondel
