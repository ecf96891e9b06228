#include "parallel/Decomposition.hpp"

#include <mpi.h>

#include <algorithm>
#include <cstring>
#include <set>
#include <stdexcept>

#include "core/Errors.hpp"
#include "parallel/Partitioner.hpp"

namespace rondel {

namespace {
// f(i) once per owned disc i and once per booked row, with the row's disc 1.
template <class F>
void for_each_work_unit(const DiscStore& discs, const ContactTable& pairs, F f) {
  const std::size_t n = discs.n_owned();
  for (std::size_t i = 0; i < n; ++i) f(i);
  for (std::size_t r = 0; r < pairs.size(); ++r)
    if (static_cast<std::size_t>(pairs.i1[r]) < n) f(static_cast<std::size_t>(pairs.i1[r]));
}
std::vector<int> sorted_without(std::set<int> ranks, int me) {
  ranks.erase(me);
  return {ranks.begin(), ranks.end()};
}
}  // namespace

Decomposition::Decomposition(const Domain& domain, double range, Partitioner partitioner, const Communicator& comm)
    : comm_(comm), grid_(domain, range), curve_(grid_.nx(), grid_.ny()), partitioner_(partitioner) {
  if (static_cast<std::size_t>(comm_.size()) > grid_.size())
    throw ConfigError(std::to_string(comm_.size()) + " MPI ranks but the domain has only " +
                      std::to_string(grid_.size()) + (grid_.size() == 1 ? " cell (" : " cells (") +
                      std::to_string(grid_.nx()) + " x " + std::to_string(grid_.ny()) +
                      ", side >= the interaction range): run on at most " + std::to_string(grid_.size()) + " ranks");
  if (partitioner_ == Partitioner::grid) blocks_ = grid_blocks(grid_, comm_.size());
}

int Decomposition::owner_in(const Map& m, std::size_t c) const {
  const int cx = static_cast<int>(c % static_cast<std::size_t>(grid_.nx()));
  const int cy = static_cast<int>(c / static_cast<std::size_t>(grid_.nx()));
  switch (partitioner_) {
    case Partitioner::grid:
      return grid_block_of(grid_, blocks_, cx, cy);
    case Partitioner::metis:
      return m.table[c];
    case Partitioner::sfc:
      break;
  }
  const std::uint64_t key = curve_.key(cx, cy);
  return static_cast<int>(std::upper_bound(m.cuts.begin(), m.cuts.end(), key) - m.cuts.begin()) - 1;
}

int Decomposition::owner_of_cell(std::size_t c) const {
  const int x = static_cast<int>(c % static_cast<std::size_t>(grid_.nx())) - box_x0_;
  const int y = static_cast<int>(c / static_cast<std::size_t>(grid_.nx())) - box_y0_;
  if (x >= 0 && x < box_nx_ && y >= 0 && y < box_ny_)
    return box_owner_[static_cast<std::size_t>(y) * static_cast<std::size_t>(box_nx_) + x];
  return owner_in(map_, c);
}

void Decomposition::for_each_cell(const Map& m, int rank, const std::function<void(std::size_t)>& f) const {
  switch (partitioner_) {
    case Partitioner::sfc:
      curve_.for_each_in(m.cuts[rank], m.cuts[rank + 1], [&](int cx, int cy) { f(grid_.index(cx, cy)); });
      return;
    case Partitioner::grid: {
      // Columns cx with floor(cx px / nx) = bx, i.e. ceil(bx nx / px) <= cx < ceil((bx + 1) nx / px).
      const long px = blocks_.first, py = blocks_.second, nx = grid_.nx(), ny = grid_.ny();
      const long bx = rank % px, by = rank / px;
      auto first = [](long b, long n, long p) { return (b * n + p - 1) / p; };
      for (long cy = first(by, ny, py); cy < first(by + 1, ny, py); ++cy)
        for (long cx = first(bx, nx, px); cx < first(bx + 1, nx, px); ++cx)
          f(grid_.index(static_cast<int>(cx), static_cast<int>(cy)));
      return;
    }
    case Partitioner::metis:
      for (std::size_t c = 0; c < m.table.size(); ++c)
        if (m.table[c] == rank) f(c);
      return;
  }
}

void Decomposition::install(Map next, bool first) {
  const Map old = std::move(map_);
  map_ = std::move(next);
  const int me = comm_.rank();
  // This rank's cells: their bounding box plus one cell holds every cell whose owner the exchanges ask for
  // (periodic images of the far side excepted: those take the map's own lookup).
  int x0 = grid_.nx(), y0 = grid_.ny(), x1 = -1, y1 = -1;
  own_cells_ = 0;
  std::set<int> neighbours, from;
  std::vector<std::size_t> cells;
  for_each_cell(map_, me, [&](std::size_t c) { cells.push_back(c); });
  for (std::size_t c : cells) {
    const int cx = static_cast<int>(c % static_cast<std::size_t>(grid_.nx()));
    const int cy = static_cast<int>(c / static_cast<std::size_t>(grid_.nx()));
    x0 = std::min(x0, cx), x1 = std::max(x1, cx), y0 = std::min(y0, cy), y1 = std::max(y1, cy);
    ++own_cells_;
    for (std::size_t s : grid_.stencil(c)) {
      neighbours.insert(owner_in(map_, s));
      if (!first) from.insert(owner_in(old, s));
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
          box_owner_[static_cast<std::size_t>(y) * box_nx_ + x] = owner_in(map_, grid_.index(box_x0_ + x, box_y0_ + y));
    }
  }
  neighbours_ = sorted_without(neighbours, me);
  if (first) {
    send_to_ = receive_from_ = neighbours_;
    return;
  }
  // Discs now owned here were, at the last migration, in one of these cells or next to one: their old owners
  // may send. Symmetrically this rank may send to the new owners of the cells next to its old cells.
  std::set<int> to;
  for_each_cell(old, me, [&](std::size_t c) {
    for (std::size_t s : grid_.stencil(c)) to.insert(owner_in(map_, s));
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

std::vector<std::pair<std::uint64_t, std::uint64_t>> Decomposition::weighted_cells(const DiscStore& discs,
                                                                                   const ContactTable& pairs) const {
  std::vector<std::uint64_t> keys;
  for_each_work_unit(discs, pairs, [&](std::size_t i) {
    const Vec2 x = discs.position[i];
    keys.push_back(curve_.key(grid_.column_of(x.x), grid_.row_of(x.y)));
  });
  std::sort(keys.begin(), keys.end());
  std::vector<std::pair<std::uint64_t, std::uint64_t>> out;
  for (std::uint64_t k : keys) {
    if (out.empty() || out.back().first != k) out.emplace_back(k, 0);
    out.back().second += kCurveScale;
  }
  return out;
}

void Decomposition::clamp_into(std::vector<std::pair<std::uint64_t, std::uint64_t>>& cells, std::uint64_t lo,
                               std::uint64_t hi) const {
  // A disc that has drifted into a neighbour's cell since the last migration is counted in this range's
  // first or last cell, so the walk of weighted_cuts() stays inside the range.
  const std::uint64_t below_lo = curve_.count_below(lo), below_hi = curve_.count_below(hi);
  if (cells.empty()) return;
  // A rank without cells holds no discs after the migration that follows every change of map.
  if (below_hi == below_lo) throw std::logic_error("Decomposition: discs on a rank whose key range holds no cell");
  const std::uint64_t first = curve_.key_of_cell_number(below_lo), last = curve_.key_of_cell_number(below_hi - 1);
  std::vector<std::pair<std::uint64_t, std::uint64_t>> out;
  for (auto [key, extra] : cells) {
    key = std::clamp(key, first, last);
    if (!out.empty() && out.back().first == key)
      out.back().second += extra;
    else
      out.emplace_back(key, extra);
  }
  std::sort(out.begin(), out.end());
  // Clamping keeps the order except for merged ends; merge equal keys once more after the sort.
  cells.clear();
  for (const auto& c : out) {
    if (!cells.empty() && cells.back().first == c.first)
      cells.back().second += c.second;
    else
      cells.push_back(c);
  }
}

std::vector<std::uint64_t> Decomposition::weighted_cuts(
    const std::vector<std::pair<std::uint64_t, std::uint64_t>>& cells, std::uint64_t lo, std::uint64_t hi,
    std::uint64_t offset, std::uint64_t total) const {
  // Cut j opens rank j at the cell that holds the point t_j = j total / P of the work along the curve (cell
  // c holds [before(c), before(c) + weight(c)), before(c) being the work of the cells of lower key). This
  // range holds [offset, offset + its work); each cell weighs one plus its extra, and runs of cells without
  // extra are crossed by counting cells along the curve. Each t_j lies in exactly one cell, so exactly one
  // rank finds each cut.
  const auto P = static_cast<std::uint64_t>(comm_.size());
  std::vector<std::uint64_t> cuts(P + 1, 0);
  auto target = [&](std::uint64_t j) {
    return static_cast<std::uint64_t>((static_cast<unsigned __int128>(j) * total) / P);
  };
  std::uint64_t j = 1;
  while (j < P && target(j) < offset) ++j;
  std::uint64_t acc = offset, pos = lo;
  auto cross_gap = [&](std::uint64_t end) {
    const std::uint64_t before = curve_.count_below(pos), gap = curve_.count_below(end) - before;
    for (; j < P && target(j) < acc + gap; ++j) cuts[j] = curve_.key_of_cell_number(before + (target(j) - acc));
    acc += gap;
    pos = end;
  };
  for (const auto& [key, extra] : cells) {
    cross_gap(key);
    for (; j < P && target(j) < acc + 1 + extra; ++j) cuts[j] = key;
    acc += 1 + extra;
    pos = key + 1;
  }
  cross_gap(hi);
  return cuts;
}

void Decomposition::initial_partition(const DiscStore& discs, bool replicated) {
  const int P = comm_.size();
  Map m;
  if (partitioner_ == Partitioner::metis) {
    set_metis(metis_weights(discs, ContactTable{}, replicated), {}, true);
    return;
  }
  if (partitioner_ == Partitioner::sfc) {
    if (replicated) {
      const auto cells = weighted_cells(discs, ContactTable{});
      std::uint64_t total = curve_.cells();
      for (const auto& c : cells) total += c.second;
      m.cuts = weighted_cuts(cells, 0, curve_.key_end(), 0, total);
    } else {
      m.cuts.assign(static_cast<std::size_t>(P) + 1, 0);
      for (int j = 1; j < P; ++j)
        m.cuts[j] = curve_.key_of_cell_number(curve_.cells() * static_cast<std::uint64_t>(j) / P);
    }
    m.cuts[0] = 0;
    m.cuts[P] = curve_.key_end();
  }
  install(std::move(m), true);
}

bool Decomposition::repartition(const DiscStore& discs, const ContactTable& pairs) {
  if (comm_.size() == 1 || partitioner_ == Partitioner::grid) return false;
  if (partitioner_ == Partitioner::metis) {
    const std::vector<int> old = map_.table;
    set_metis(metis_weights(discs, pairs, false), old, false);
    return map_.table != old;
  }
  // This rank's key range, its work, the work of the lower ranges (a scan) and the whole (a reduction);
  // each rank finds the cuts that fall in its range and one reduction gives every rank all of them.
  const int me = comm_.rank(), P = comm_.size();
  const std::uint64_t lo = map_.cuts[me], hi = map_.cuts[me + 1];
  auto cells = weighted_cells(discs, pairs);
  clamp_into(cells, lo, hi);
  std::uint64_t mine = curve_.count_below(hi) - curve_.count_below(lo), offset = 0, total = 0;
  for (const auto& c : cells) mine += c.second;
  comm_.count_collective();
  MPI_Exscan(&mine, &offset, 1, MPI_UINT64_T, MPI_SUM, comm_.comm());
  if (me == 0) offset = 0;
  total = static_cast<std::uint64_t>(comm_.sum(static_cast<std::int64_t>(mine)));
  Map m;
  m.cuts = weighted_cuts(cells, lo, hi, offset, total);
  comm_.count_collective();
  MPI_Allreduce(MPI_IN_PLACE, m.cuts.data(), P + 1, MPI_UINT64_T, MPI_MAX, comm_.comm());
  m.cuts[0] = 0;
  m.cuts[P] = curve_.key_end();
  if (m.cuts == map_.cuts) return false;
  install(std::move(m), false);
  return true;
}

std::vector<long> Decomposition::metis_weights(const DiscStore& discs, const ContactTable& pairs,
                                               bool replicated) const {
  // METIS needs the whole cell graph's weights on rank 0: one per cell plus kWorkScale per unit.
  std::vector<long> work(grid_.size(), 0);
  for_each_work_unit(discs, pairs, [&](std::size_t i) { work[grid_.cell_of(discs.position[i])] += kWorkScale; });
  if (!replicated) {
    comm_.count_collective();
    MPI_Allreduce(MPI_IN_PLACE, work.data(), static_cast<int>(work.size()), MPI_LONG, MPI_SUM, comm_.comm());
  }
  for (long& w : work) w += 1;
  return work;
}

void Decomposition::set_metis(const std::vector<long>& weights, const std::vector<int>& previous, bool first) {
  std::vector<int> map = comm_.root() ? metis_partition(grid_, comm_.size(), weights, previous) : std::vector<int>();
  std::vector<char> bytes(map.size() * sizeof(int));
  if (comm_.root()) std::memcpy(bytes.data(), map.data(), bytes.size());
  comm_.broadcast(bytes);
  Map m;
  m.table.resize(grid_.size());
  std::memcpy(m.table.data(), bytes.data(), bytes.size());
  if (!first && m.table == map_.table) return;
  install(std::move(m), first);
}

int Decomposition::empty_ranks() const {
  // Every rank knows the cut keys (sfc) or the blocks (grid); metis holds the table.
  int n = 0;
  if (partitioner_ == Partitioner::sfc) {
    for (int r = 0; r < comm_.size(); ++r)
      if (curve_.count_below(map_.cuts[r + 1]) == curve_.count_below(map_.cuts[r])) ++n;
  } else if (partitioner_ == Partitioner::metis) {
    std::vector<bool> has(static_cast<std::size_t>(comm_.size()), false);
    for (int r : map_.table) has[r] = true;
    for (bool h : has) n += h ? 0 : 1;
  }
  return n;
}

std::size_t Decomposition::memory_bytes() const {
  return map_.cuts.capacity() * sizeof(std::uint64_t) + map_.table.capacity() * sizeof(int) +
         box_owner_.capacity() * sizeof(int) +
         (neighbours_.capacity() + send_to_.capacity() + receive_from_.capacity()) * sizeof(int);
}

}  // namespace rondel
