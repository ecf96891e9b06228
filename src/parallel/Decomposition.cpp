#include "parallel/Decomposition.hpp"

#include <mpi.h>

#include <cstring>

#include "core/Errors.hpp"
#include "parallel/Partitioner.hpp"

namespace rondel {

Decomposition::Decomposition(const Domain& domain, double range, Partitioner partitioner, const Communicator& comm)
    : comm_(comm), grid_(domain, range), partitioner_(partitioner) {
  if (static_cast<std::size_t>(comm_.size()) > grid_.size())
    throw ConfigError(std::to_string(comm_.size()) + " MPI ranks but the domain has only " +
                      std::to_string(grid_.size()) + (grid_.size() == 1 ? " cell (" : " cells (") +
                      std::to_string(grid_.nx()) + " x " + std::to_string(grid_.ny()) +
                      ", side >= the interaction range): run on at most " + std::to_string(grid_.size()) + " ranks");
}

void Decomposition::set_map(std::vector<int> map) {
  // Computed on rank 0 and broadcast, so every rank holds exactly the same map.
  std::vector<char> bytes(map.size() * sizeof(int));
  if (comm_.root()) std::memcpy(bytes.data(), map.data(), bytes.size());
  comm_.broadcast(bytes);
  cell_rank_.resize(grid_.size());
  std::memcpy(cell_rank_.data(), bytes.data(), bytes.size());
}

void Decomposition::initial_partition(const std::vector<long>& weights) {
  if (partitioner_ == Partitioner::grid)
    set_map(grid_partition(grid_, comm_.size()));
  else
    set_map(comm_.root() ? metis_partition(grid_, comm_.size(), weights, {}) : std::vector<int>(grid_.size()));
}

bool Decomposition::repartition(const std::vector<long>& weights) {
  if (partitioner_ == Partitioner::grid || comm_.size() == 1) return false;
  const std::vector<int> old = cell_rank_;
  set_map(comm_.root() ? metis_partition(grid_, comm_.size(), weights, cell_rank_) : std::vector<int>(grid_.size()));
  return cell_rank_ != old;
}

double Decomposition::rank_work(const DiscStore& discs, const ContactTable& pairs) {
  std::size_t units = 0;
  for_each_work_unit(discs, pairs, [&units](std::size_t) { ++units; });
  return static_cast<double>(units);
}

std::vector<long> Decomposition::cell_work(const DiscStore& discs, const ContactTable& pairs) const {
  // Each unit of rank_work() lands in the cell of its disc, so moving a cell moves exactly its weight. (A
  // border row is also computed by the other rank; that duplicated cost is reported as the ghost fraction.)
  std::vector<long> work(grid_.size(), 0);
  for_each_work_unit(discs, pairs, [&](std::size_t i) { work[grid_.cell_of(discs.position[i])] += kWorkScale; });
  work = sum_over_ranks(std::move(work));
  for (long& w : work) w += 1;
  return work;
}

std::vector<long> Decomposition::initial_weights(const DiscStore& discs, bool replicated) const {
  std::vector<long> work(grid_.size(), 1);
  for_each_work_unit(discs, ContactTable{},
                     [&](std::size_t i) { work[grid_.cell_of(discs.position[i])] += kWorkScale; });
  if (!replicated) work = sum_over_ranks(std::move(work));
  return work;
}

std::vector<long> Decomposition::sum_over_ranks(std::vector<long> values) const {
  MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_LONG, MPI_SUM, comm_.comm());
  return values;
}

int Decomposition::empty_ranks() const {
  std::vector<bool> has(static_cast<std::size_t>(comm_.size()), false);
  for (int r : cell_rank_) has[r] = true;
  int n = 0;
  for (bool h : has) n += h ? 0 : 1;
  return n;
}

}  // namespace rondel
