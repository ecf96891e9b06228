// What each rank needs to build its own block of a lattice (core/SceneBuilder.hpp): a keyed permutation that is a
// bijection, and material slots with the exact counts of the fractions, each computed for one site alone; and to
// build the discs of its own cells (SceneType::by_cells): every disc once, in the cell the grid puts it in, and
// the counts the first map is weighted by.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "core/CellGrid.hpp"
#include "core/Config.hpp"
#include "core/SceneBuilder.hpp"
#include "core/SceneTypes.hpp"
#include "physics/LawRegistry.hpp"

namespace rondel {
namespace {

TEST(SceneBlocks, TheKeyedPermutationIsABijectionOfEverySize) {
  for (std::uint64_t n : {1u, 2u, 3u, 5u, 64u, 100u, 1000u, 4097u, 65536u}) {
    std::vector<std::uint64_t> image(n);
    for (std::uint64_t k = 0; k < n; ++k) image[k] = scene::keyed_permutation(k, n, 12345);
    std::vector<std::uint64_t> sorted = image;
    std::sort(sorted.begin(), sorted.end());
    for (std::uint64_t k = 0; k < n; ++k) ASSERT_EQ(sorted[k], k) << "n = " << n;
    if (n >= 100) {
      std::uint64_t fixed = 0;
      for (std::uint64_t k = 0; k < n; ++k) fixed += image[k] == k;
      EXPECT_LT(fixed, n / 10) << "n = " << n << ": hardly a shuffle";
      EXPECT_NE(image, [&] {
        std::vector<std::uint64_t> other(n);
        for (std::uint64_t k = 0; k < n; ++k) other[k] = scene::keyed_permutation(k, n, 54321);
        return other;
      }()) << "another key, the same order";
    }
  }
}

TEST(SceneBlocks, ALatticesMaterialsHaveTheExactCountsOfTheirFractions) {
  const Config c = parse_config_text(R"(
[domain]
xlo = 0
xhi = 1
ylo = 0
yhi = 1
[linear]
k_n = 1e6
[coulomb]
k_s = 7.5e5
mu = 0.5
[material.a]
density = 2650
[material.b]
density = 7800
[material.c]
density = 1000
[scene]
type = lattice_square
nx = 37
ny = 23
radius = 0.005
spacing = 0.02
x0 = 0.01
y0 = 0.01
materials = a b c
material_fractions = 0.5 0.3 0.2
)");
  const SceneInputs in{c.scene, c.domain, "", nullptr};
  const auto whole = build_scene(in);
  ASSERT_EQ(whole.size(), 851u);
  std::vector<int> count(3, 0);
  for (const auto& d : whole) ++count[static_cast<std::size_t>(d.material)];
  EXPECT_EQ(count, (std::vector<int>{426, 255, 170})) << "851 x (0.5, 0.3, 0.2), largest remainder";
  // Any cut into blocks gives the same discs.
  for (int ranks : {2, 3, 7}) {
    std::size_t k = 0;
    for (int r = 0; r < ranks; ++r)
      for (const auto& d : build_scene_block(in, r, ranks)) {
        ASSERT_EQ(d.gid, whole[k].gid);
        EXPECT_EQ(d.material, whole[k].material) << "disc " << d.gid << " in " << ranks << " blocks";
        ++k;
      }
    EXPECT_EQ(k, whole.size());
  }
}

// The lattice of `ini` cut into groups of cells (cell % groups): each group's discs are the whole build's discs of
// its cells, once, in ascending gid, and rect_count gives the number in each cell and rectangle of cells.
void check_cells(const std::string& ini, const std::vector<std::string>& args, double range, std::size_t groups) {
  const Config c = parse_config_text(ini, args);
  const SceneInputs in{c.scene, c.domain, "", nullptr};
  ASSERT_GT(scene::by_cells(in), 0.0) << ini;
  const auto whole = build_scene(in);
  const CellGrid grid(c.domain, range);
  ASSERT_GT(grid.size(), 20u) << "cells of several discs and of none";
  std::vector<std::uint64_t> in_cell(grid.size(), 0);
  for (const auto& d : whole) ++in_cell[grid.cell_of(d.x)];
  std::vector<int> seen(whole.size(), 0);
  for (std::size_t g = 0; g < groups; ++g) {
    std::vector<std::size_t> cells;
    for (std::size_t cell = g; cell < grid.size(); cell += groups) cells.push_back(cell);
    struct Counted final : SceneSink {  // the count announced first, then the discs
      std::size_t announced = 0, reserves = 0;
      std::vector<SceneDisc> discs;
      void reserve(std::size_t n) override { announced = n, ++reserves; }
      void add(const SceneDisc& d) override { discs.push_back(d); }
    } sink;
    c.scene.type->cells(in, grid, cells, sink);
    const auto& part = sink.discs;
    EXPECT_EQ(sink.reserves, 1u);
    EXPECT_EQ(sink.announced, part.size()) << "the exact count before the discs";
    for (std::size_t k = 0; k < part.size(); ++k) {
      const auto& d = part[k];
      const auto& w = whole.at(static_cast<std::size_t>(d.gid));
      EXPECT_TRUE(d.x.x == w.x.x && d.x.y == w.x.y && d.radius == w.radius && d.v.x == w.v.x && d.omega == w.omega &&
                  d.material == w.material)
          << "disc " << d.gid;
      EXPECT_EQ(grid.cell_of(d.x) % groups, g) << "disc " << d.gid << " of another group's cell";
      if (k > 0) {
        EXPECT_LT(part[k - 1].gid, d.gid) << "ascending gid";
      }
      ++seen[static_cast<std::size_t>(d.gid)];
    }
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<std::ptrdiff_t>(whole.size())) << "each disc once";
  // rect_count of every cell, and of rectangles of many cells, against the discs the grid puts there.
  const int nx = grid.nx(), ny = grid.ny();
  const auto count = [&](int x0, int y0, int x1, int y1) {
    std::uint64_t sum = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) sum += in_cell[grid.index(x, y)];
    return sum;
  };
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x)
      ASSERT_EQ(c.scene.type->rect_count(in, grid, x, y, x + 1, y + 1), in_cell[grid.index(x, y)]) << x << ", " << y;
  for (int x0 = 0; x0 < nx; x0 += 2)
    for (int y0 = 0; y0 < ny; y0 += 3)
      for (int w : {1, 2, 5, nx})
        for (int h : {1, 3, ny}) {
          const int x1 = std::min(nx, x0 + w), y1 = std::min(ny, y0 + h);
          ASSERT_EQ(c.scene.type->rect_count(in, grid, x0, y0, x1, y1), count(x0, y0, x1, y1))
              << "[" << x0 << ", " << x1 << ") x [" << y0 << ", " << y1 << ")";
        }
}

const char* kCellLattice = R"(
[domain]
xlo = 0
xhi = 0.5
ylo = 0
yhi = 0.4
[linear]
k_n = 1e6
[coulomb]
k_s = 1e6
mu = 0.5
[material.a]
density = 2650
[material.b]
density = 7800
[scene]
nx = 20
ny = 13
radius = 0.005
spacing = 0.0123
x0 = 0.05
y0 = 0.0
materials = a b
material_fractions = 0.7 0.3
)";

TEST(SceneBlocks, ALatticeBuiltCellByCellIsTheWholeBuildsDiscsOnce) {
  // Square and hexagonal rows, cells narrower and wider than the spacing, a site on a cell's lower edge (y0 = 0,
  // the grid's first row) and on the domain's upper edge.
  for (const char* type : {"lattice_square", "lattice_hex"})
    for (double range : {0.01, 0.0123, 0.031, 0.07}) {
      SCOPED_TRACE(std::string(type) + ", range " + std::to_string(range));
      check_cells(kCellLattice, {std::string("--scene.type=") + type}, range, 3);
    }
  check_cells(kCellLattice, {"--scene.type=lattice_square", "--scene.spacing=0.02", "--scene.ny=21"}, 0.04,
              2);  // y = yhi
}

TEST(SceneBlocks, ALatticeThatWrapsRoundAPeriodicSideIsNotBuiltCellByCell) {
  const std::vector<std::string> periodic{"--scene.type=lattice_square", "--domain.periodic_x=true"};
  check_cells(kCellLattice, periodic, 0.03, 4);
  // The 20th column at x0 + 19 x 0.0123 = 0.3 + 0.2337 lies beyond xhi = 0.5: it wraps to the left side.
  std::vector<std::string> shifted = periodic;
  shifted.push_back("--scene.x0=0.3");
  const Config wraps = parse_config_text(kCellLattice, shifted);
  EXPECT_EQ(scene::by_cells(SceneInputs{wraps.scene, wraps.domain, "", nullptr}), 0.0);
  EXPECT_TRUE(scene::in_blocks(wraps.scene)) << "built in blocks instead";
}

}  // namespace
}  // namespace rondel
