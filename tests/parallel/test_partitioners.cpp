// The partitioners (src/parallel/Partitioner.*) and the cell-to-rank map of Decomposition (docs/design.md
// section 6): every cell gets a rank, every rank gets cells, the load is balanced within a bound, and the
// map is a deterministic function of its inputs (the same on every rank). The pure functions run on every
// rank of the MPI test binary alike; the Decomposition cases use MPI_COMM_WORLD.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "ParallelTestUtil.hpp"
#include "core/Errors.hpp"
#include "parallel/CellMaps.hpp"
#include "parallel/Decomposition.hpp"
#include "parallel/Hilbert.hpp"
#include "support/Assertions.hpp"

namespace rondel {
namespace {

using partest::all_gather;
using partest::world_size;

// A grid of nx x ny cells: a box of nx x ny units with the interaction range 1.
CellGrid grid_of(int nx, int ny, bool periodic = false) {
  return CellGrid(Domain{0.0, static_cast<double>(nx), 0.0, static_cast<double>(ny), periodic, periodic}, 1.0);
}

// Weight per rank; fails unless every cell has a rank in [0, ranks) and every rank has a cell.
::testing::AssertionResult weights_per_rank(const std::vector<int>& map, const std::vector<long>& weights, int ranks,
                                            std::vector<long>* per_rank) {
  per_rank->assign(static_cast<std::size_t>(ranks), 0);
  std::vector<int> cells(static_cast<std::size_t>(ranks), 0);
  for (std::size_t c = 0; c < map.size(); ++c) {
    if (map[c] < 0 || map[c] >= ranks)
      return ::testing::AssertionFailure() << "cell " << c << " has rank " << map[c] << " of " << ranks;
    (*per_rank)[map[c]] += weights[c];
    ++cells[map[c]];
  }
  for (int r = 0; r < ranks; ++r)
    if (cells[r] == 0) return ::testing::AssertionFailure() << "rank " << r << " of " << ranks << " has no cell";
  return ::testing::AssertionSuccess();
}

double imbalance(const std::vector<long>& per_rank) {
  long total = 0, most = 0;
  for (long w : per_rank) total += w, most = std::max(most, w);
  return static_cast<double>(most) * static_cast<double>(per_rank.size()) / static_cast<double>(total);
}

TEST(Hilbert, KeysOrderEveryCellAndTheRangeQueriesAgreeWithBruteForce) {
  for (const auto& [nx, ny] : std::vector<std::pair<int, int>>{{1, 1}, {5, 3}, {8, 8}, {13, 40}, {100, 7}}) {
    const HilbertGrid h(nx, ny);
    std::map<std::uint64_t, std::pair<int, int>> by_key;
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) {
        const std::uint64_t k = h.key(x, y);
        ASSERT_LT(k, h.key_end());
        ASSERT_TRUE(by_key.emplace(k, std::make_pair(x, y)).second) << "key " << k << " twice";
        int px = -1, py = -1;
        h.point(k, px, py);
        ASSERT_EQ(px, x);
        ASSERT_EQ(py, y);
      }
    // Consecutive keys are neighbouring cells on the square (the curve's locality).
    for (std::uint64_t k = 0; k + 1 < h.key_end(); ++k) {
      int x0, y0, x1, y1;
      h.point(k, x0, y0);
      h.point(k + 1, x1, y1);
      ASSERT_EQ(std::abs(x0 - x1) + std::abs(y0 - y1), 1) << "keys " << k << ", " << k + 1;
    }
    std::vector<std::uint64_t> keys;
    for (const auto& kv : by_key) keys.push_back(kv.first);
    for (std::uint64_t m = 0; m < keys.size(); ++m) ASSERT_EQ(h.key_of_cell_number(m), keys[m]);
    for (std::uint64_t k = 0; k <= h.key_end(); k += 1 + h.key_end() / 97) {
      const auto below = static_cast<std::uint64_t>(std::lower_bound(keys.begin(), keys.end(), k) - keys.begin());
      ASSERT_EQ(h.count_below(k), below) << nx << " x " << ny << ", k = " << k;
      std::vector<std::uint64_t> seen;
      h.for_each_key_in(k / 2, k, [&](std::uint64_t key, int x, int y) {
        ASSERT_EQ(key, h.key(x, y)) << x << ", " << y;
        seen.push_back(key);
      });
      const auto lo = std::lower_bound(keys.begin(), keys.end(), k / 2);
      ASSERT_EQ(seen, std::vector<std::uint64_t>(lo, keys.begin() + static_cast<std::ptrdiff_t>(below)));
    }
    // key_at_work: the cell holding each point of the work along the curve, cells of weight 0 to 4.
    const auto w = [](int x, int y) { return static_cast<std::uint64_t>((7 * x + 3 * y) % 5); };
    const HilbertGrid::RectWeight rect = [&](int x0, int y0, int x1, int y1) {
      std::uint64_t sum = 0;
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) sum += w(x, y);
      return sum;
    };
    std::uint64_t before = 0;
    for (const auto& [key, cell] : by_key) {
      const std::uint64_t here = w(cell.first, cell.second);
      for (std::uint64_t t = before; t < before + here; ++t)
        ASSERT_EQ(h.key_at_work(t, rect), key) << nx << " x " << ny << ", t = " << t;
      before += here;
    }
    EXPECT_EQ(before, rect(0, 0, nx, ny));
  }
}

TEST(Hilbert, ACoverSplitsARectangleIntoWholeNodesWhereverTheOwnerDoesNotChange) {
  // Owners by key ranges (cuts), as the sfc map: the cover's nodes fill every cell of the rectangle once, each
  // with the owner of its cells' keys, and it visits a number of nodes that grows with the cuts, not the cells.
  for (const auto& [nx, ny] : std::vector<std::pair<int, int>>{{1, 1}, {5, 3}, {13, 40}, {100, 7}, {300, 200}}) {
    const HilbertGrid h(nx, ny);
    for (int parts : {1, 2, 5}) {
      std::vector<std::uint64_t> cuts;
      for (int j = 0; j <= parts; ++j) cuts.push_back(h.key_end() * static_cast<std::uint64_t>(j) / parts + (j % 2));
      cuts.back() = h.key_end();
      const auto owner = [&](std::uint64_t k) {
        return static_cast<int>(std::upper_bound(cuts.begin(), cuts.end(), k) - cuts.begin()) - 1;
      };
      for (const auto& [x0, y0, x1, y1] :
           std::vector<std::array<int, 4>>{{0, 0, nx, ny}, {nx / 3, ny / 4, nx, ny / 2 + 1}, {nx - 1, 0, nx, ny}}) {
        const int w = x1 - x0;
        std::vector<int> seen(static_cast<std::size_t>(w) * static_cast<std::size_t>(y1 - y0), -1);
        std::size_t nodes = 0;
        h.cover(
            x0, y0, x1, y1, [&](std::uint64_t b, std::uint64_t e) { return owner(b) == owner(e - 1); },
            [&](std::uint64_t b, std::uint64_t e, int a0, int b0, int a1, int b1) {
              ++nodes;
              ASSERT_LT(b, e);
              ASSERT_TRUE(x0 <= a0 && a0 < a1 && a1 <= x1 && y0 <= b0 && b0 < b1 && b1 <= y1);
              for (int y = b0; y < b1; ++y)
                for (int x = a0; x < a1; ++x) {
                  ASSERT_TRUE(h.key(x, y) >= b && h.key(x, y) < e) << x << ", " << y;
                  int& at = seen[static_cast<std::size_t>(y - y0) * w + (x - x0)];
                  ASSERT_EQ(at, -1) << "cell " << x << ", " << y << " twice";
                  at = owner(b);
                }
            });
        for (int y = y0; y < y1; ++y)
          for (int x = x0; x < x1; ++x)
            ASSERT_EQ(seen[static_cast<std::size_t>(y - y0) * w + (x - x0)], owner(h.key(x, y))) << x << ", " << y;
        if (nx * ny >= 60000) {  // a cut splits one node a level, four children each; the rectangle's edges too
          const std::size_t levels = 10, edge = 2 * static_cast<std::size_t>(w + y1 - y0);
          EXPECT_LE(nodes, 4 * levels * (static_cast<std::size_t>(parts) + edge)) << nx << " x " << ny;
          EXPECT_LT(nodes, seen.size() / 4);
        }
      }
    }
  }
}

TEST(GridPartition, EveryCellInOneRectangularBlockOfBalancedSize) {
  for (const auto& [nx, ny] : std::vector<std::pair<int, int>>{{12, 9}, {7, 5}, {20, 3}, {1, 8}, {16, 16}}) {
    const CellGrid grid = grid_of(nx, ny);
    ASSERT_EQ(grid.nx(), nx);
    ASSERT_EQ(grid.ny(), ny);
    for (int ranks = 1; ranks <= 6; ++ranks) {
      std::vector<int> map;
      try {
        map = grid_partition(grid, ranks);
      } catch (const ConfigError&) {
        continue;  // no px x py layout fits (checked by GridPartition.RefusesRanksWithoutALayout)
      }
      const std::string at = std::to_string(nx) + " x " + std::to_string(ny) + ", " + std::to_string(ranks) + " ranks";
      ASSERT_EQ(map.size(), grid.size()) << at;
      std::vector<long> cells;
      ASSERT_TRUE(weights_per_rank(map, std::vector<long>(grid.size(), 1), ranks, &cells)) << at;
      // Each rank's cells fill their bounding box: a block.
      std::map<int, std::vector<int>> box;  // rank -> {xmin, xmax, ymin, ymax}
      for (int cy = 0; cy < ny; ++cy)
        for (int cx = 0; cx < nx; ++cx) {
          auto [it, fresh] =
              box.try_emplace(map[static_cast<std::size_t>(cy) * nx + cx], std::vector<int>{cx, cx, cy, cy});
          auto& b = it->second;
          b = {std::min(b[0], cx), std::max(b[1], cx), std::min(b[2], cy), std::max(b[3], cy)};
        }
      for (const auto& [r, b] : box)
        EXPECT_EQ(cells[r], static_cast<long>(b[1] - b[0] + 1) * (b[3] - b[2] + 1)) << at << ": rank " << r;
      // Block sides differ by at most one cell: the blocks are as equal as the grid allows.
      std::set<int> widths, heights;
      for (const auto& [r, b] : box) widths.insert(b[1] - b[0] + 1), heights.insert(b[3] - b[2] + 1);
      EXPECT_LE(*widths.rbegin() - *widths.begin(), 1) << at;
      EXPECT_LE(*heights.rbegin() - *heights.begin(), 1) << at;
    }
  }
}

TEST(GridPartition, RefusesRanksWithoutALayout) {
  // 2 x 2 cells on 5 ranks: neither 1 x 5 nor 5 x 1 blocks fit.
  try {
    grid_partition(grid_of(2, 2), 5);
    FAIL() << "no ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_TRUE(test::names(e.what(), "parallel.partitioner = metis"));
  }
}

TEST(MetisPartition, EveryCellAssignedAndUniformWorkBalanced) {
  const CellGrid grid = grid_of(16, 12, true);
  const std::vector<long> weights(grid.size(), 3);
  EXPECT_EQ(metis_partition(grid, 1, weights, {}), std::vector<int>(grid.size(), 0));
  for (int ranks = 2; ranks <= 5; ++ranks) {
    const std::vector<int> map = metis_partition(grid, ranks, weights, {});
    ASSERT_EQ(map.size(), grid.size());
    std::vector<long> per_rank;
    ASSERT_TRUE(weights_per_rank(map, weights, ranks, &per_rank)) << ranks << " ranks";
    EXPECT_LE(imbalance(per_rank), 1.05) << ranks << " ranks";
    EXPECT_EQ(metis_partition(grid, ranks, weights, {}), map) << "not deterministic, " << ranks << " ranks";
  }
}

TEST(MetisPartition, ConcentratedWorkBalanced) {
  // Work 20 per cell in the bottom-left quarter, 1 elsewhere (a pile in a corner).
  const CellGrid grid = grid_of(24, 12);
  std::vector<long> weights(grid.size(), 1);
  for (int cy = 0; cy < 6; ++cy)
    for (int cx = 0; cx < 12; ++cx) weights[static_cast<std::size_t>(cy) * 24 + cx] = 20;
  for (int ranks = 2; ranks <= 4; ++ranks) {
    std::vector<long> per_rank;
    ASSERT_TRUE(weights_per_rank(metis_partition(grid, ranks, weights, {}), weights, ranks, &per_rank));
    EXPECT_LE(imbalance(per_rank), 1.05) << ranks << " ranks";
  }
}

TEST(MetisPartition, RelabellingKeepsTheWorkWhereItWas) {
  // A permuted labelling of the previous map is mapped back to it exactly.
  const CellGrid grid = grid_of(10, 10);
  const std::vector<long> weights(grid.size(), 2);
  const std::vector<int> previous = metis_partition(grid, 4, weights, {});
  std::vector<int> permuted(previous.size());
  const int perm[4] = {2, 0, 3, 1};
  for (std::size_t c = 0; c < previous.size(); ++c) permuted[c] = perm[previous[c]];
  EXPECT_EQ(relabel_parts(permuted, previous, weights, 4), previous);
  EXPECT_EQ(relabel_parts(permuted, {}, weights, 4), permuted);  // no previous map: unchanged
  // A repartition with the previous map keeps most of the weight on its rank.
  std::vector<long> shifted = weights;
  shifted[0] = 40;
  const std::vector<int> next = metis_partition(grid, 4, shifted, previous);
  long kept = 0, total = 0;
  for (std::size_t c = 0; c < next.size(); ++c) total += shifted[c], kept += next[c] == previous[c] ? shifted[c] : 0;
  EXPECT_GE(static_cast<double>(kept), 0.5 * static_cast<double>(total));
}

// The map of a Decomposition on MPI_COMM_WORLD: every cell has a rank, no rank is empty, every rank sees
// the same owners (a test may hold an array over all cells; the product does not), owner(x) is the owner of
// x's cell, and the neighbour lists are symmetric and exactly the owners of the cells around a rank's cells.
void expect_world_map(const Decomposition& d) {
  const int n = world_size(), me = partest::world_rank();
  const CellGrid& g = d.grid();
  std::vector<int> map(g.size());
  for (std::size_t c = 0; c < g.size(); ++c) map[c] = d.owner_of_cell(c);
  std::vector<long> cells;
  ASSERT_TRUE(weights_per_rank(map, std::vector<long>(g.size(), 1), n, &cells));
  EXPECT_EQ(d.empty_ranks(), 0);
  std::string mine;
  for (int r : map) mine += std::to_string(r) + ",";
  for (const std::string& other : all_gather(mine)) EXPECT_EQ(other, mine) << "ranks hold different maps";
  for (double x : {0.5, 3.2, 11.9})
    for (double y : {0.1, 5.5}) EXPECT_EQ(d.owner({x, y}), map[g.cell_of({x, y})]);
  std::set<int> expect;
  for (std::size_t c = 0; c < g.size(); ++c)
    if (map[c] == me)
      for (std::size_t s : g.stencil(c))
        if (map[s] != me) expect.insert(map[s]);
  EXPECT_EQ(std::vector<int>(expect.begin(), expect.end()), d.neighbours());
  std::string nb;
  for (int r : d.neighbours()) nb += std::to_string(r) + ",";
  const auto all = all_gather(nb);
  for (int r : d.neighbours())
    EXPECT_NE(("," + all[r]).find("," + std::to_string(me) + ","), std::string::npos)
        << "rank " << r << " is a neighbour of " << me << " but not the other way round";
}

// Discs on a third of the domain (the left part), one per unit square: every rank holds all of them.
DiscStore discs_on_left_third(const Domain& domain) {
  DiscStore discs;
  std::int64_t gid = 0;
  for (double x = 0.5; x < domain.xhi / 3.0; x += 1.0)
    for (double y = 0.5; y < domain.yhi; y += 1.0) discs.add(gid++, 0, 0.1, 1.0, 1.0, {x, y}, {}, 0.0);
  return discs;
}

TEST(Decomposition, SfcGridAndMetisMapsOnTheWorld) {
  static const Communicator world(MPI_COMM_WORLD);
  const Domain domain{0.0, 12.0, 0.0, 8.0, true, false};
  for (const auto& partitioner : Partitioners::choices()) {  // every partitioner of the registry
    const std::string kind = partitioner.word;
    Decomposition d(domain, 1.0, kind, world);
    DiscStore discs = discs_on_left_third(domain);
    d.initial_partition(discs, true);
    expect_world_map(d);
    // Keep this rank's discs, then repartition from them (the distributed path).
    std::vector<bool> elsewhere(discs.n_owned());
    for (std::size_t i = 0; i < discs.n_owned(); ++i) elsewhere[i] = d.owner(discs.position[i]) != world.rank();
    discs.remove_owned(elsewhere);
    d.repartition(discs, ContactTable{});
    expect_world_map(d);
    EXPECT_EQ(d.partitioner(), kind);
  }
}

TEST(Decomposition, SfcCutsBalanceTheWorkAndAgreeWithTheReplicatedCut) {
  // The weighted cut of a replicated scene (each rank alone) and the distributed cut (scans over ranks
  // holding their own discs) are the same map; each rank's work (disc units x 100 + one per cell) is within
  // one cell's weight of the mean.
  static const Communicator world(MPI_COMM_WORLD);
  const Domain domain{0.0, 40.0, 0.0, 30.0, false, false};
  Decomposition replicated(domain, 1.0, "sfc", world);
  DiscStore all = discs_on_left_third(domain);
  replicated.initial_partition(all, true);
  Decomposition spread(domain, 1.0, "sfc", world);
  spread.initial_partition(all, false);  // equal-cell cut
  DiscStore mine = all;
  std::vector<bool> elsewhere(mine.n_owned());
  for (std::size_t i = 0; i < mine.n_owned(); ++i) elsewhere[i] = spread.owner(mine.position[i]) != world.rank();
  mine.remove_owned(elsewhere);
  spread.repartition(mine, ContactTable{});
  const CellGrid& g = replicated.grid();
  std::vector<long> work(static_cast<std::size_t>(world_size()), 0);
  for (std::size_t c = 0; c < g.size(); ++c) {
    ASSERT_EQ(replicated.owner_of_cell(c), spread.owner_of_cell(c)) << "cell " << c;
    work[replicated.owner_of_cell(c)] += 1;
  }
  for (std::size_t i = 0; i < all.n_owned(); ++i)
    work[replicated.owner(all.position[i])] += static_cast<long>(Decomposition::kCurveScale);
  long total = 0, most = 0;
  for (long w : work) total += w, most = std::max(most, w);
  EXPECT_LE(most, total / world_size() + static_cast<long>(Decomposition::kCurveScale) + 1)
      << "imbalance " << imbalance(work);
}

TEST(Decomposition, SfcRepartitionKeepsMostCellsInPlace) {
  // A shift of the work by a few cells moves the cuts a little: most cells keep their rank.
  static const Communicator world(MPI_COMM_WORLD);
  const Domain domain{0.0, 40.0, 0.0, 30.0, false, false};
  Decomposition d(domain, 1.0, "sfc", world);
  DiscStore all = discs_on_left_third(domain);
  d.initial_partition(all, true);
  std::vector<int> before(d.grid().size());
  for (std::size_t c = 0; c < before.size(); ++c) before[c] = d.owner_of_cell(c);
  DiscStore mine;
  std::int64_t gid = 0;
  for (std::size_t i = 0; i < all.n_owned(); ++i) {
    const Vec2 x = all.position[i] + Vec2{2.0, 0.0};
    if (d.owner(all.position[i]) == world.rank()) mine.add(gid, 0, 0.1, 1.0, 1.0, x, {}, 0.0);
    ++gid;
  }
  d.repartition(mine, ContactTable{});
  std::size_t kept = 0;
  for (std::size_t c = 0; c < before.size(); ++c) kept += d.owner_of_cell(c) == before[c] ? 1 : 0;
  EXPECT_GE(static_cast<double>(kept), 0.5 * static_cast<double>(before.size()));
}

TEST(Partition, ExtentsAndRectangleOwnersAgreeWithTheCellByCellMap) {
  // Every partitioner's extent(rank) and owners_in() (sfc's from whole curve nodes, the others' by default)
  // against owner() and for_each_cell() cell by cell.
  static const Communicator world(MPI_COMM_WORLD);
  const CellGrid grid = grid_of(37, 23);
  const HilbertGrid curve(grid.nx(), grid.ny());
  const DiscStore discs = discs_on_left_third(Domain{0.0, 37.0, 0.0, 23.0, false, false});
  for (const auto& partitioner : Partitioners::choices()) {
    const std::unique_ptr<Partition> map = make_partition(partitioner.word, PartitionContext{grid, curve, world});
    map->initial(discs, true);
    for (int r = 0; r < world.size(); ++r) {
      Partition::Extent brute;
      map->for_each_cell(r, [&](std::size_t c) {
        const int x = static_cast<int>(c % 37), y = static_cast<int>(c / 37);
        brute.add(x, y, x + 1, y + 1);
      });
      const Partition::Extent e = map->extent(r);
      EXPECT_EQ(std::vector<int>({e.x0, e.y0, e.x1, e.y1}), std::vector<int>({brute.x0, brute.y0, brute.x1, brute.y1}))
          << partitioner.word << ", rank " << r;
      EXPECT_EQ(e.count, brute.count) << partitioner.word << ", rank " << r;
    }
    std::vector<int> owners(static_cast<std::size_t>(20 * 9));
    map->owners_in(11, 7, 31, 16, owners.data());
    for (int y = 7; y < 16; ++y)
      for (int x = 11; x < 31; ++x)
        ASSERT_EQ(owners[static_cast<std::size_t>(y - 7) * 20 + (x - 11)], map->owner(grid.index(x, y)))
            << partitioner.word << ", cell " << x << ", " << y;
  }
}

}  // namespace
}  // namespace rondel
