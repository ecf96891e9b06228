#include "parallel/Decomposition.hpp"

#include <algorithm>

#include "core/Errors.hpp"

namespace rondel {

namespace {
// r into a small ascending list of ranks (a rank has few partners); the caller skips repeats of the last one.
void add_rank(std::vector<int>& ranks, int r) {
  const auto at = std::lower_bound(ranks.begin(), ranks.end(), r);
  if (at == ranks.end() || *at != r) ranks.insert(at, r);
}
std::vector<int> without(std::vector<int> ranks, int me) {
  ranks.erase(std::remove(ranks.begin(), ranks.end(), me), ranks.end());
  return ranks;
}
}  // namespace

Partition::Extent Partition::extent(int rank) const {
  Extent out;
  const auto nx = static_cast<std::size_t>(grid_.nx());
  for_each_cell(rank, [&](std::size_t c) {
    const int x = static_cast<int>(c % nx), y = static_cast<int>(c / nx);
    out.add(x, y, x + 1, y + 1);
  });
  return out;
}

void Partition::owners_in(int x0, int y0, int x1, int y1, int* out) const {
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) *out++ = owner(grid_.index(x, y));
}

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
  return owner_at(static_cast<int>(c % static_cast<std::size_t>(grid_.nx())),
                  static_cast<int>(c / static_cast<std::size_t>(grid_.nx())));
}

std::vector<std::size_t> Decomposition::own_cells() const {
  std::vector<std::size_t> out;
  out.reserve(static_cast<std::size_t>(own_cells_));
  if (comm_.size() == 1) {
    for (std::size_t c = 0; c < grid_.size(); ++c) out.push_back(c);
  } else if (box_nx_ > 0) {  // the table's rows
    for (int y = 0; y < box_ny_; ++y)
      for (int x = 0; x < box_nx_; ++x)
        if (box_owner_[static_cast<std::size_t>(y) * box_nx_ + x] == comm_.rank())
          out.push_back(grid_.index(box_x0_ + x, box_y0_ + y));
  } else {
    map_->for_each_cell(comm_.rank(), [&](std::size_t c) { out.push_back(c); });
    std::sort(out.begin(), out.end());
  }
  return out;
}

void Decomposition::frame(const Partition::Extent& mine) {
  // This rank's cells: their bounding box plus one cell holds every cell whose owner the exchanges ask for
  // (periodic images of the far side excepted: those take the map's own lookup).
  box_nx_ = box_ny_ = 0;
  if (mine.count == 0) return;
  box_x0_ = std::max(mine.x0 - 1, 0), box_y0_ = std::max(mine.y0 - 1, 0);
  box_nx_ = std::min(mine.x1, grid_.nx() - 1) - box_x0_ + 1;
  box_ny_ = std::min(mine.y1, grid_.ny() - 1) - box_y0_ + 1;
  if (static_cast<std::int64_t>(box_nx_) * box_ny_ > 16 * mine.count + 4096)
    box_nx_ = box_ny_ = 0;  // a scattered map (metis): the map's lookup serves
}

std::vector<int> Decomposition::owners_in_box(const Partition& map) const {
  std::vector<int> box(static_cast<std::size_t>(box_nx_) * static_cast<std::size_t>(box_ny_));
  map.owners_in(box_x0_, box_y0_, box_x0_ + box_nx_, box_y0_ + box_ny_, box.data());
  return box;
}

template <class F>
void Decomposition::owners_around(std::size_t cell, std::size_t at, const std::vector<int>& box, const Partition& map,
                                  F f) const {
  const auto nx = static_cast<std::size_t>(box_nx_);
  if (at != kOutside && at >= nx && at + nx < box.size() && at % nx > 0 && at % nx + 1 < nx) {
    for (const std::size_t row : {at - nx, at, at + nx})  // inside the table: its eight neighbours there
      for (std::size_t k = row - 1; k <= row + 1; ++k) f(box[k]);
    return;
  }
  grid_.for_each_in_stencil(cell, [&](int x, int y) {
    const std::size_t here = box_at(x, y);
    f(here != kOutside ? box[here] : map.owner(grid_.index(x, y)));
  });
}

void Decomposition::ranks_around(std::size_t cell, std::vector<int>& out) const {
  out.clear();
  owners_around(cell, box_at(cell), box_owner_, *map_, [&](int r) {
    if (r != comm_.rank() && std::find(out.begin(), out.end(), r) == out.end()) out.push_back(r);
  });
  std::sort(out.begin(), out.end());
}

template <class F>
void Decomposition::for_each_own(const std::vector<std::size_t>& cells, bool skip_inner, F visit) const {
  if (box_nx_ == 0) {
    for (std::size_t c : cells) visit(c, kOutside);
    return;
  }
  const int me = comm_.rank();
  const auto nx = static_cast<std::size_t>(box_nx_);
  const int* o = box_owner_.data();
  const auto all_mine = [&](std::size_t at) {  // an inner cell of the table with its eight neighbours here
    for (const std::size_t row : {at - nx, at, at + nx})
      if (o[row - 1] != me || o[row] != me || o[row + 1] != me) return false;
    return true;
  };
  for (int y = 0; y < box_ny_; ++y)  // this rank's cells in the table's rows
    for (int x = 0; x < box_nx_; ++x) {
      const std::size_t at = static_cast<std::size_t>(y) * nx + x;
      if (o[at] != me) continue;
      if (skip_inner && y > 0 && y + 1 < box_ny_ && x > 0 && x + 1 < box_nx_ && all_mine(at)) continue;
      visit(grid_.index(box_x0_ + x, box_y0_ + y), at);
    }
}

void Decomposition::install(const Partition* old) {
  const int me = comm_.rank();
  box_owner_.clear();
  box_border_.clear();
  box_nx_ = box_ny_ = 0;
  if (comm_.size() == 1) {  // every cell, no neighbour: the map's lookup serves
    own_cells_ = static_cast<std::int64_t>(grid_.size());
    neighbours_.clear(), send_to_.clear(), receive_from_.clear();
    return;
  }
  const Partition::Extent mine = map_->extent(me);
  own_cells_ = mine.count;
  frame(mine);
  std::vector<std::size_t> cells, old_cells;  // this rank's cells when there is no table; its old cells
  if (old) old->for_each_cell(me, [&](std::size_t c) { old_cells.push_back(c); });
  std::vector<int> box_old;  // the old map's owners over the same box
  if (box_nx_ > 0) {
    box_owner_ = owners_in_box(*map_);
    if (old) box_old = owners_in_box(*old);
    box_border_.assign(box_owner_.size(), 0);
  } else {
    map_->for_each_cell(me, [&](std::size_t c) { cells.push_back(c); });
  }
  // The ranks around this rank's cells, its border cells (a ghost's source) and, after a change of map, the
  // cells' old owners; runs of one owner are common.
  std::vector<int> neighbours, from;
  int last = -1, last_old = -1;
  const auto visit = [&](std::size_t c, std::size_t at) {
    bool border = false;
    owners_around(c, at, box_owner_, *map_, [&](int r) {
      border = border || r != me;
      if (r != last) add_rank(neighbours, last = r);
    });
    if (border && at != kOutside) box_border_[at] = 1;
    if (old)
      owners_around(c, at, box_old, *old, [&](int o) {
        if (o != last_old) add_rank(from, last_old = o);
      });
  };
  for_each_own(cells, !old, visit);
  neighbours_ = without(neighbours, me);
  if (!old) {
    send_to_ = receive_from_ = neighbours_;
    return;
  }
  // Discs now owned here were, at the last migration, in one of these cells or next to one: their old owners
  // may send. Symmetrically this rank may send to the new owners of the cells next to its old cells.
  std::vector<int> to = neighbours_;
  last = -1;
  for (std::size_t c : old_cells)
    owners_around(c, box_at(c), box_owner_, *map_, [&](int r) {
      if (r != last) add_rank(to, last = r);
    });
  for (int r : neighbours_) add_rank(from, r);
  send_to_ = without(to, me);
  receive_from_ = without(from, me);
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

bool Decomposition::initial_partition(const Partition::RectUnits& units) {
  map_->initial(DiscStore{}, false);
  const bool weighed = map_->weigh(units);
  install(nullptr);
  return weighed;
}

bool Decomposition::repartition(const DiscStore& discs, const ContactTable& pairs) {
  const std::unique_ptr<Partition> old = map_->copy();
  if (!map_->repartition(discs, pairs)) return false;
  install(old.get());
  return true;
}

std::size_t Decomposition::memory_bytes() const {
  return map_->memory_bytes() + box_owner_.capacity() * sizeof(int) + box_border_.capacity() +
         (neighbours_.capacity() + send_to_.capacity() + receive_from_.capacity()) * sizeof(int);
}

}  // namespace rondel
