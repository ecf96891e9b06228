// parallel.partitioner = metis: a k-way METIS partition of the cell graph (8-neighbour stencil, periodic wrap)
// with the work per cell as vertex weights (kWorkScale per unit plus one), fixed seed; computed on rank 0 and
// broadcast, so every rank holds the whole map (O(cells) per rank: for moderate sizes). The new parts are
// relabelled so that most of the weight stays on the rank that had it.
#include <metis.h>
#include <mpi.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <tuple>

#include "parallel/CellMaps.hpp"
#include "parallel/Decomposition.hpp"
#include "parallel/Partition.hpp"

namespace rondel {

std::vector<int> relabel_parts(const std::vector<int>& parts, const std::vector<int>& previous,
                               const std::vector<long>& weights, int ranks) {
  if (previous.size() != parts.size()) return parts;
  std::vector<long> overlap(static_cast<std::size_t>(ranks) * ranks, 0);
  for (std::size_t c = 0; c < parts.size(); ++c)
    overlap[static_cast<std::size_t>(parts[c]) * ranks + previous[c]] += weights[c];
  std::vector<std::tuple<long, int, int>> order;  // (-overlap, part, rank)
  for (int p = 0; p < ranks; ++p)
    for (int r = 0; r < ranks; ++r) order.emplace_back(-overlap[static_cast<std::size_t>(p) * ranks + r], p, r);
  std::sort(order.begin(), order.end());
  std::vector<int> label(ranks, -1);
  std::vector<bool> taken(ranks, false);
  for (const auto& [neg, p, r] : order) {
    if (label[p] >= 0 || taken[r]) continue;
    label[p] = r;
    taken[r] = true;
  }
  std::vector<int> out(parts.size());
  for (std::size_t c = 0; c < parts.size(); ++c) out[c] = label[parts[c]];
  return out;
}

std::vector<int> metis_partition(const CellGrid& grid, int ranks, const std::vector<long>& weights,
                                 const std::vector<int>& previous) {
  if (ranks == 1) return std::vector<int>(grid.size(), 0);
  idx_t n = static_cast<idx_t>(grid.size());
  std::vector<idx_t> xadj{0}, adjncy, vwgt(grid.size());
  for (std::size_t c = 0; c < grid.size(); ++c) {
    for (std::size_t nb : grid.stencil(c))
      if (nb != c) adjncy.push_back(static_cast<idx_t>(nb));
    xadj.push_back(static_cast<idx_t>(adjncy.size()));
    vwgt[c] = static_cast<idx_t>(std::min<long>(weights[c], 1L << 30));
  }
  idx_t ncon = 1, nparts = ranks, objval = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 20151;
  options[METIS_OPTION_NUMBERING] = 0;
  options[METIS_OPTION_UFACTOR] = 10;  // allowed load imbalance 1.01
  std::vector<idx_t> part(grid.size());
  const int status = METIS_PartGraphKway(&n, &ncon, xadj.data(), adjncy.data(), vwgt.data(), nullptr, nullptr, &nparts,
                                         nullptr, nullptr, options, &objval, part.data());
  if (status != METIS_OK) throw std::runtime_error("METIS_PartGraphKway failed with status " + std::to_string(status));
  std::vector<int> parts(part.begin(), part.end());
  return relabel_parts(parts, previous, weights, ranks);
}

namespace {

class MetisPartition final : public Partition {
 public:
  explicit MetisPartition(const PartitionContext& c) : Partition(c.grid), comm_(c.comm) {}
  std::unique_ptr<Partition> copy() const override { return std::make_unique<MetisPartition>(*this); }
  int owner(std::size_t c) const override { return table_[c]; }
  void for_each_cell(int rank, const std::function<void(std::size_t)>& f) const override {
    for (std::size_t c = 0; c < table_.size(); ++c)
      if (table_[c] == rank) f(c);
  }
  void initial(const DiscStore& discs, bool replicated) override {
    table_ = partition(weights(discs, ContactTable{}, replicated), {});
  }
  bool repartition(const DiscStore& discs, const ContactTable& pairs) override {
    if (comm_.size() == 1) return false;
    std::vector<int> next = partition(weights(discs, pairs, false), table_);
    if (next == table_) return false;
    table_ = std::move(next);
    return true;
  }
  int empty_ranks() const override {
    std::vector<bool> has(static_cast<std::size_t>(comm_.size()), false);
    for (int r : table_) has[r] = true;
    return static_cast<int>(std::count(has.begin(), has.end(), false));
  }
  std::size_t memory_bytes() const override { return table_.capacity() * sizeof(int); }

 private:
  // METIS needs the whole cell graph's weights on rank 0: one per cell plus kWorkScale per unit.
  std::vector<long> weights(const DiscStore& discs, const ContactTable& pairs, bool replicated) const {
    std::vector<long> work(grid_.size(), 0);
    for_each_work_unit(discs, pairs,
                       [&](std::size_t i) { work[grid_.cell_of(discs.position[i])] += Decomposition::kWorkScale; });
    if (!replicated) {
      comm_.count_collective();
      MPI_Allreduce(MPI_IN_PLACE, work.data(), static_cast<int>(work.size()), MPI_LONG, MPI_SUM, comm_.comm());
    }
    for (long& w : work) w += 1;
    return work;
  }
  // Rank 0 partitions, every rank receives the map.
  std::vector<int> partition(const std::vector<long>& weights, const std::vector<int>& previous) const {
    std::vector<int> map = comm_.root() ? metis_partition(grid_, comm_.size(), weights, previous) : std::vector<int>();
    std::vector<char> bytes(map.size() * sizeof(int));
    if (comm_.root()) std::memcpy(bytes.data(), map.data(), bytes.size());
    comm_.broadcast(bytes);
    std::vector<int> table(grid_.size());
    std::memcpy(table.data(), bytes.data(), bytes.size());
    return table;
  }

  const Communicator& comm_;
  std::vector<int> table_;  // the owner of every cell
};

}  // namespace

std::unique_ptr<Partition> make_partition(MetisPartitioner, const PartitionContext& context) {
  return std::make_unique<MetisPartition>(context);
}

}  // namespace rondel
