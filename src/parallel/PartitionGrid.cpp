// parallel.partitioner = grid: regular px x py blocks of cells (px py = ranks, blocks as square as the grid
// allows); the owner of a cell is computed, no table, and the map never changes.
#include <cmath>

#include "core/Errors.hpp"
#include "parallel/CellMaps.hpp"
#include "parallel/Partition.hpp"

namespace rondel {

std::pair<int, int> grid_blocks(const CellGrid& grid, int ranks) {
  // The factorisation px x py = ranks whose blocks are closest to square (in cells).
  int best_px = 1;
  double best = INFINITY;
  for (int px = 1; px <= ranks; ++px) {
    if (ranks % px != 0) continue;
    const int py = ranks / px;
    if (px > grid.nx() || py > grid.ny()) continue;
    const double aspect =
        std::fabs(std::log((static_cast<double>(grid.nx()) / px) / (static_cast<double>(grid.ny()) / py)));
    if (aspect < best) best = aspect, best_px = px;
  }
  if (!std::isfinite(best))
    throw ConfigError("parallel.partitioner = grid: " + std::to_string(ranks) +
                      " ranks cannot be laid out in blocks of the " + std::to_string(grid.nx()) + " x " +
                      std::to_string(grid.ny()) + " cell grid; use fewer ranks or parallel.partitioner = metis");
  return {best_px, ranks / best_px};
}

int grid_block_of(const CellGrid& grid, std::pair<int, int> blocks, int cx, int cy) {
  const int bx = static_cast<int>(static_cast<long>(cx) * blocks.first / grid.nx());
  const int by = static_cast<int>(static_cast<long>(cy) * blocks.second / grid.ny());
  return by * blocks.first + bx;
}

std::vector<int> grid_partition(const CellGrid& grid, int ranks) {
  const auto blocks = grid_blocks(grid, ranks);
  std::vector<int> map(grid.size());
  for (int cy = 0; cy < grid.ny(); ++cy)
    for (int cx = 0; cx < grid.nx(); ++cx) map[grid.index(cx, cy)] = grid_block_of(grid, blocks, cx, cy);
  return map;
}

namespace {

class GridPartition final : public Partition {
 public:
  explicit GridPartition(const PartitionContext& c) : Partition(c.grid), blocks_(grid_blocks(c.grid, c.comm.size())) {}
  std::unique_ptr<Partition> copy() const override { return std::make_unique<GridPartition>(*this); }
  int owner(std::size_t c) const override {
    const auto nx = static_cast<std::size_t>(grid_.nx());
    return grid_block_of(grid_, blocks_, static_cast<int>(c % nx), static_cast<int>(c / nx));
  }
  void for_each_cell(int rank, const std::function<void(std::size_t)>& f) const override {
    // Columns cx with floor(cx px / nx) = bx, i.e. ceil(bx nx / px) <= cx < ceil((bx + 1) nx / px).
    const long px = blocks_.first, py = blocks_.second, nx = grid_.nx(), ny = grid_.ny();
    const long bx = rank % px, by = rank / px;
    auto first = [](long b, long n, long p) { return (b * n + p - 1) / p; };
    for (long cy = first(by, ny, py); cy < first(by + 1, ny, py); ++cy)
      for (long cx = first(bx, nx, px); cx < first(bx + 1, nx, px); ++cx)
        f(grid_.index(static_cast<int>(cx), static_cast<int>(cy)));
  }
  void initial(const DiscStore&, bool) override {}
  bool repartition(const DiscStore&, const ContactTable&) override { return false; }
  int empty_ranks() const override { return 0; }
  std::size_t memory_bytes() const override { return 0; }

 private:
  std::pair<int, int> blocks_;
};

}  // namespace

std::unique_ptr<Partition> make_partition(GridPartitioner, const PartitionContext& context) {
  return std::make_unique<GridPartition>(context);
}

}  // namespace rondel
