// parallel.partitioner = sfc (the default; docs/design.md section 6): the cells in Hilbert-curve order
// (Hilbert.hpp) cut into P contiguous key ranges of equal work. The map is the P + 1 cut keys, the same on every
// rank; the owner of a cell is a binary search. The cuts are found from distributed prefix sums (one scan and two
// reductions), and a repartition moves the cuts, so most work stays in place.
#include <mpi.h>

#include <algorithm>
#include <stdexcept>
#include <utility>
#include <vector>

#include "parallel/Decomposition.hpp"
#include "parallel/Partition.hpp"

namespace rondel {

namespace {

using Cells = std::vector<std::pair<std::uint64_t, std::uint64_t>>;  // (cell key, extra weight), ascending key

// The point j total / P of the work along the curve, where cut j opens rank j (j x total needs 128 bits: GCC's and
// Clang's extension).
std::uint64_t cut_target(std::uint64_t j, std::uint64_t total, std::uint64_t P) {
  __extension__ typedef unsigned __int128 Wide;
  return static_cast<std::uint64_t>((static_cast<Wide>(j) * total) / P);
}

class SfcPartition final : public Partition {
 public:
  explicit SfcPartition(const PartitionContext& c) : Partition(c.grid), curve_(c.curve), comm_(c.comm) {}
  std::unique_ptr<Partition> copy() const override { return std::make_unique<SfcPartition>(*this); }
  int owner(std::size_t c) const override { return owner_of_key(curve_.key(column(c), row(c))); }
  void for_each_cell(int rank, const std::function<void(std::size_t)>& f) const override {
    curve_.for_each_key_in(cuts_[rank], cuts_[rank + 1],
                           [&](std::uint64_t, int cx, int cy) { f(grid_.index(cx, cy)); });
  }
  // Whole nodes of the curve: a node inside one rank's key range is one rectangle of owners.
  Extent extent(int rank) const override {
    const std::uint64_t lo = cuts_[rank], hi = cuts_[rank + 1];
    Extent out;
    curve_.cover(
        0, 0, grid_.nx(), grid_.ny(),
        [&](std::uint64_t b, std::uint64_t e) { return e <= lo || b >= hi || (lo <= b && e <= hi); },
        [&](std::uint64_t b, std::uint64_t, int x0, int y0, int x1, int y1) {
          if (b >= lo && b < hi) out.add(x0, y0, x1, y1);
        });
    return out;
  }
  void owners_in(int x0, int y0, int x1, int y1, int* out) const override {
    const std::size_t width = static_cast<std::size_t>(x1 - x0);
    curve_.cover(
        x0, y0, x1, y1, [&](std::uint64_t b, std::uint64_t e) { return owner_of_key(b) == owner_of_key(e - 1); },
        [&](std::uint64_t b, std::uint64_t, int a0, int b0, int a1, int b1) {
          const int r = owner_of_key(b);
          for (int y = b0; y < b1; ++y)
            std::fill_n(out + static_cast<std::size_t>(y - y0) * width + static_cast<std::size_t>(a0 - x0), a1 - a0, r);
        });
  }
  void initial(const DiscStore& discs, bool replicated) override;
  bool repartition(const DiscStore& discs, const ContactTable& pairs) override;
  bool weigh(const RectUnits& units) override;
  int empty_ranks() const override {
    int n = 0;
    for (int r = 0; r < comm_.size(); ++r)
      if (curve_.count_below(cuts_[r + 1]) == curve_.count_below(cuts_[r])) ++n;
    return n;
  }
  std::size_t memory_bytes() const override { return cuts_.capacity() * sizeof(std::uint64_t); }

 private:
  int owner_of_key(std::uint64_t key) const {
    return static_cast<int>(std::upper_bound(cuts_.begin(), cuts_.end(), key) - cuts_.begin()) - 1;
  }
  int column(std::size_t c) const { return static_cast<int>(c % static_cast<std::size_t>(grid_.nx())); }
  int row(std::size_t c) const { return static_cast<int>(c / static_cast<std::size_t>(grid_.nx())); }
  // This rank's work units as weighted cells.
  Cells weighted_cells(const DiscStore& discs, const ContactTable& pairs) const;
  void clamp_into(Cells& cells, std::uint64_t lo, std::uint64_t hi) const;
  // The cuts from this range's weighted cells (collective); true when they changed.
  bool cut(const Cells& cells);
  std::vector<std::uint64_t> weighted_cuts(const Cells& cells, std::uint64_t lo, std::uint64_t hi, std::uint64_t offset,
                                           std::uint64_t total) const;

  const HilbertGrid& curve_;
  const Communicator& comm_;
  std::vector<std::uint64_t> cuts_;  // rank r owns keys [cuts_[r], cuts_[r + 1])
};

Cells SfcPartition::weighted_cells(const DiscStore& discs, const ContactTable& pairs) const {
  std::vector<std::uint64_t> keys;
  int last_x = -1, last_y = -1;  // discs in gid order, and a disc's rows, come in runs of one cell
  std::uint64_t last_key = 0;
  for_each_work_unit(discs, pairs, [&](std::size_t i) {
    const Vec2 x = discs.position[i];
    const int cx = grid_.column_of(x), cy = grid_.row_of(x.y);
    if (cx != last_x || cy != last_y) last_key = curve_.key(last_x = cx, last_y = cy);
    keys.push_back(last_key);
  });
  std::sort(keys.begin(), keys.end());
  Cells out;
  for (std::uint64_t k : keys) {
    if (out.empty() || out.back().first != k) out.emplace_back(k, 0);
    out.back().second += Decomposition::kCurveScale;
  }
  return out;
}

void SfcPartition::clamp_into(Cells& cells, std::uint64_t lo, std::uint64_t hi) const {
  // A disc that has drifted into a neighbour's cell since the last migration is counted in this range's
  // first or last cell, so the walk of weighted_cuts() stays inside the range.
  const std::uint64_t below_lo = curve_.count_below(lo), below_hi = curve_.count_below(hi);
  if (cells.empty()) return;
  // A rank without cells holds no discs after the migration that follows every change of map.
  if (below_hi == below_lo) throw std::logic_error("Decomposition: discs on a rank whose key range holds no cell");
  const std::uint64_t first = curve_.key_of_cell_number(below_lo), last = curve_.key_of_cell_number(below_hi - 1);
  Cells out;
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

std::vector<std::uint64_t> SfcPartition::weighted_cuts(const Cells& cells, std::uint64_t lo, std::uint64_t hi,
                                                       std::uint64_t offset, std::uint64_t total) const {
  // Cut j opens rank j at the cell that holds the point t_j = j total / P of the work along the curve (cell
  // c holds [before(c), before(c) + weight(c)), before(c) being the work of the cells of lower key). This
  // range holds [offset, offset + its work); each cell weighs one plus its extra, and runs of cells without
  // extra are crossed by counting cells along the curve. Each t_j lies in exactly one cell, so exactly one
  // rank finds each cut.
  const auto P = static_cast<std::uint64_t>(comm_.size());
  std::vector<std::uint64_t> cuts(P + 1, 0);
  auto target = [&](std::uint64_t j) { return cut_target(j, total, P); };
  std::uint64_t j = 1;
  while (j < P && target(j) < offset) ++j;
  std::uint64_t acc = offset, pos = lo;
  auto cross_gap = [&](std::uint64_t end) {
    if (end == pos) return;  // the next cell follows on the curve: no gap to count (the same cuts, no search)
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

void SfcPartition::initial(const DiscStore& discs, bool replicated) {
  const int P = comm_.size();
  if (replicated) {
    const auto cells = weighted_cells(discs, ContactTable{});
    std::uint64_t total = curve_.cells();
    for (const auto& c : cells) total += c.second;
    cuts_ = weighted_cuts(cells, 0, curve_.key_end(), 0, total);
  } else {
    cuts_.assign(static_cast<std::size_t>(P) + 1, 0);
    for (int j = 1; j < P; ++j)
      cuts_[j] = curve_.key_of_cell_number(curve_.cells() * static_cast<std::uint64_t>(j) / P);
  }
  cuts_[0] = 0;
  cuts_[P] = curve_.key_end();
}

bool SfcPartition::repartition(const DiscStore& discs, const ContactTable& pairs) {
  if (comm_.size() == 1) return false;
  auto cells = weighted_cells(discs, pairs);
  clamp_into(cells, cuts_[comm_.rank()], cuts_[comm_.rank() + 1]);
  return cut(cells);
}

bool SfcPartition::weigh(const RectUnits& units) {
  // Each cell weighs one plus kCurveScale per disc, as repartition() weighs them; each rank finds every cut by a
  // descent of the curve, O(P log side) rectangles and no cell visited, no communication.
  const int P = comm_.size();
  const auto work = [&](int x0, int y0, int x1, int y1) {
    return static_cast<std::uint64_t>(x1 - x0) * static_cast<std::uint64_t>(y1 - y0) +
           Decomposition::kCurveScale * units(x0, y0, x1, y1);
  };
  const std::uint64_t total = work(0, 0, grid_.nx(), grid_.ny());
  for (int j = 1; j < P; ++j)
    cuts_[j] =
        curve_.key_at_work(cut_target(static_cast<std::uint64_t>(j), total, static_cast<std::uint64_t>(P)), work);
  return true;
}

bool SfcPartition::cut(const Cells& cells) {
  // This rank's key range, its work, the work of the lower ranges (a scan) and the whole (a reduction);
  // each rank finds the cuts that fall in its range and one reduction gives every rank all of them.
  const int me = comm_.rank(), P = comm_.size();
  const std::uint64_t lo = cuts_[me], hi = cuts_[me + 1];
  std::uint64_t mine = curve_.count_below(hi) - curve_.count_below(lo), offset = 0;
  for (const auto& c : cells) mine += c.second;
  comm_.count_collective();
  MPI_Exscan(&mine, &offset, 1, MPI_UINT64_T, MPI_SUM, comm_.comm());
  if (me == 0) offset = 0;
  const auto total = static_cast<std::uint64_t>(comm_.sum(static_cast<std::int64_t>(mine)));
  std::vector<std::uint64_t> cuts = weighted_cuts(cells, lo, hi, offset, total);
  comm_.count_collective();
  MPI_Allreduce(MPI_IN_PLACE, cuts.data(), P + 1, MPI_UINT64_T, MPI_MAX, comm_.comm());
  cuts[0] = 0;
  cuts[P] = curve_.key_end();
  if (cuts == cuts_) return false;
  cuts_ = std::move(cuts);
  return true;
}

}  // namespace

std::unique_ptr<Partition> make_partition(SfcPartitioner, const PartitionContext& context) {
  return std::make_unique<SfcPartition>(context);
}

}  // namespace rondel
