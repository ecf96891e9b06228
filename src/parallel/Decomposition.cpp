#include "parallel/Decomposition.hpp"

#include <algorithm>
#include <set>

#include "core/Errors.hpp"

namespace rondel {

namespace {
std::vector<int> sorted_without(std::set<int> ranks, int me) {
  ranks.erase(me);
  return {ranks.begin(), ranks.end()};
}
}  // namespace

std::unique_ptr<Partition> make_partition(const std::string& name, const PartitionContext& context) {
  std::unique_ptr<Partition> out;
  Partitioners::with(name, [&]<class Tag>() { out = make_partition(Tag{}, context); });
  if (!out)
    throw ConfigError("parallel.partitioner = " + name +
                      " is not allowed: " + config::choice_words<std::string>(Partitioners::choices(), false));
  return out;
}

Decomposition::Decomposition(const Domain& domain, double range, const std::string& partitioner,
                             const Communicator& comm, const Domain& sizing)
    : comm_(comm), grid_(domain, range, sizing), curve_(grid_.nx(), grid_.ny()), partitioner_(partitioner) {
  if (static_cast<std::size_t>(comm_.size()) > grid_.size())
    throw ConfigError(std::to_string(comm_.size()) + " MPI ranks but the domain has only " +
                      std::to_string(grid_.size()) + (grid_.size() == 1 ? " cell (" : " cells (") +
                      std::to_string(grid_.nx()) + " x " + std::to_string(grid_.ny()) +
                      ", side >= the interaction range): run on at most " + std::to_string(grid_.size()) + " ranks");
  map_ = make_partition(partitioner_, PartitionContext{grid_, curve_, comm_});
}

int Decomposition::owner_of_cell(std::size_t c) const {
  const int x = static_cast<int>(c % static_cast<std::size_t>(grid_.nx())) - box_x0_;
  const int y = static_cast<int>(c / static_cast<std::size_t>(grid_.nx())) - box_y0_;
  if (x >= 0 && x < box_nx_ && y >= 0 && y < box_ny_)
    return box_owner_[static_cast<std::size_t>(y) * static_cast<std::size_t>(box_nx_) + x];
  return map_->owner(c);
}

void Decomposition::install(const Partition* old) {
  const int me = comm_.rank();
  // This rank's cells: their bounding box plus one cell holds every cell whose owner the exchanges ask for
  // (periodic images of the far side excepted: those take the map's own lookup).
  int x0 = grid_.nx(), y0 = grid_.ny(), x1 = -1, y1 = -1;
  own_cells_ = 0;
  std::set<int> neighbours, from;
  std::vector<std::size_t> cells;
  map_->for_each_cell(me, [&](std::size_t c) { cells.push_back(c); });
  for (std::size_t c : cells) {
    const int cx = static_cast<int>(c % static_cast<std::size_t>(grid_.nx()));
    const int cy = static_cast<int>(c / static_cast<std::size_t>(grid_.nx()));
    x0 = std::min(x0, cx), x1 = std::max(x1, cx), y0 = std::min(y0, cy), y1 = std::max(y1, cy);
    ++own_cells_;
    for (std::size_t s : grid_.stencil(c)) {
      neighbours.insert(map_->owner(s));
      if (old) from.insert(old->owner(s));
    }
  }
  box_owner_.clear();
  box_nx_ = box_ny_ = 0;
  if (own_cells_ > 0) {
    box_x0_ = std::max(x0 - 1, 0), box_y0_ = std::max(y0 - 1, 0);
    box_nx_ = std::min(x1 + 1, grid_.nx() - 1) - box_x0_ + 1;
    box_ny_ = std::min(y1 + 1, grid_.ny() - 1) - box_y0_ + 1;
    const auto area = static_cast<std::int64_t>(box_nx_) * box_ny_;
    if (area > 16 * own_cells_ + 4096) {
      box_nx_ = box_ny_ = 0;  // a scattered map (metis): the map's lookup serves
    } else {
      box_owner_.resize(static_cast<std::size_t>(area));
      for (int y = 0; y < box_ny_; ++y)
        for (int x = 0; x < box_nx_; ++x)
          box_owner_[static_cast<std::size_t>(y) * box_nx_ + x] = map_->owner(grid_.index(box_x0_ + x, box_y0_ + y));
    }
  }
  neighbours_ = sorted_without(neighbours, me);
  if (!old) {
    send_to_ = receive_from_ = neighbours_;
    return;
  }
  // Discs now owned here were, at the last migration, in one of these cells or next to one: their old owners
  // may send. Symmetrically this rank may send to the new owners of the cells next to its old cells.
  std::set<int> to;
  old->for_each_cell(me, [&](std::size_t c) {
    for (std::size_t s : grid_.stencil(c)) to.insert(map_->owner(s));
  });
  for (int r : neighbours_) to.insert(r), from.insert(r);
  send_to_ = sorted_without(to, me);
  receive_from_ = sorted_without(from, me);
}

void Decomposition::migrated() { send_to_ = receive_from_ = neighbours_; }

std::int64_t Decomposition::rank_work(const DiscStore& discs, const ContactTable& pairs) {
  std::int64_t units = 0;
  for_each_work_unit(discs, pairs, [&units](std::size_t) { ++units; });
  return units;
}

void Decomposition::initial_partition(const DiscStore& discs, bool replicated) {
  map_->initial(discs, replicated);
  install(nullptr);
}

bool Decomposition::repartition(const DiscStore& discs, const ContactTable& pairs) {
  const std::unique_ptr<Partition> old = map_->copy();
  if (!map_->repartition(discs, pairs)) return false;
  install(old.get());
  return true;
}

std::size_t Decomposition::memory_bytes() const {
  return map_->memory_bytes() + box_owner_.capacity() * sizeof(int) +
         (neighbours_.capacity() + send_to_.capacity() + receive_from_.capacity()) * sizeof(int);
}

}  // namespace rondel
