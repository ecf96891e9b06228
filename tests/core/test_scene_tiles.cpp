// scene.type = random_tiles (core/ScenePackingTiles.cpp): scene.count discs without overlap inside scene.region,
// ids 0 to N - 1, the exact material counts; found cell by cell (SceneType::cells), any set of cells gives the
// whole build's discs of those cells, bit for bit, once, in ascending gid, whatever the grid; the first map's
// weights are the expected counts; and a packing too dense or a region outside the domain is refused naming keys.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/CellGrid.hpp"
#include "core/Config.hpp"
#include "core/Errors.hpp"
#include "core/SceneBuilder.hpp"
#include "core/SceneTypes.hpp"
#include "physics/LawRegistry.hpp"

namespace rondel {
namespace {

const char* kTiles = R"(
[domain]
xlo = 0
xhi = 0.3
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
type = random_tiles
count = 3000
region = 0.01 0.29 0.02 0.3
radius_min = 0.001
radius_max = 0.002
materials = a b
material_fractions = 0.7 0.3
seed = 7
)";

std::vector<SceneDisc> whole_of(const Config& c) { return build_scene(SceneInputs{c.scene, c.domain, "", nullptr}); }

TEST(SceneTiles, TheDiscsFitTheRegionWithoutOverlapWithTheExactCounts) {
  const Config c = parse_config_text(kTiles);
  const auto whole = whole_of(c);
  ASSERT_EQ(whole.size(), 3000u);
  std::vector<int> materials(2, 0);
  for (std::size_t k = 0; k < whole.size(); ++k) {
    const SceneDisc& d = whole[k];
    ASSERT_EQ(d.gid, static_cast<std::int64_t>(k));
    EXPECT_TRUE(d.radius >= 0.001 && d.radius <= 0.002) << d.radius;
    EXPECT_TRUE(d.x.x - d.radius >= 0.01 && d.x.x + d.radius <= 0.29 && d.x.y - d.radius >= 0.02 &&
                d.x.y + d.radius <= 0.3)
        << "disc " << d.gid << " leaves scene.region";
    ++materials[static_cast<std::size_t>(d.material)];
  }
  EXPECT_EQ(materials, (std::vector<int>{2100, 900})) << "3000 x (0.7, 0.3)";
  // No two discs overlap (all pairs, sorted by x to stop early).
  std::vector<SceneDisc> by_x = whole;
  std::sort(by_x.begin(), by_x.end(), [](const SceneDisc& a, const SceneDisc& b) { return a.x.x < b.x.x; });
  std::size_t overlaps = 0;
  for (std::size_t i = 0; i < by_x.size(); ++i)
    for (std::size_t j = i + 1; j < by_x.size() && by_x[j].x.x - by_x[i].x.x < 0.004; ++j) {
      const Vec2 e = by_x[i].x - by_x[j].x;
      overlaps += std::sqrt(dot(e, e)) < by_x[i].radius + by_x[j].radius;
    }
  EXPECT_EQ(overlaps, 0u);
  // Spread over the region: each quarter of it holds about a quarter of the discs.
  for (int q = 0; q < 4; ++q) {
    const double x_mid = 0.15, y_mid = 0.16;
    const auto n = std::count_if(whole.begin(), whole.end(), [&](const SceneDisc& d) {
      return (d.x.x < x_mid) == (q % 2 == 0) && (d.x.y < y_mid) == (q / 2 == 0);
    });
    EXPECT_NEAR(static_cast<double>(n), 750.0, 60.0) << "quarter " << q;
  }
  // Another seed, other discs.
  const auto other = whole_of(parse_config_text(kTiles, {"--scene.seed=8"}));
  EXPECT_NE(other[0].x.x, whole[0].x.x);
}

TEST(SceneTiles, AnySetOfCellsGivesTheWholeBuildsDiscsOfThoseCellsOnce) {
  const Config c = parse_config_text(kTiles);
  const SceneInputs in{c.scene, c.domain, "", nullptr};
  ASSERT_GT(scene::by_cells(in), 0.0);
  const auto whole = build_scene(in);
  for (double range : {0.0045, 0.011, 0.05})
    for (std::size_t groups : {1u, 3u, 4u}) {
      SCOPED_TRACE("range " + std::to_string(range) + ", " + std::to_string(groups) + " groups");
      const CellGrid grid(c.domain, range);
      std::vector<int> seen(whole.size(), 0);
      for (std::size_t g = 0; g < groups; ++g) {
        // Scattered cells (every groups-th) and, for g = 0 of 4, a block of whole rows: runs of every length.
        std::vector<std::size_t> cells;
        for (std::size_t cell = 0; cell < grid.size(); ++cell)
          if (groups == 4 ? (g == 0 ? cell < grid.size() / 3 : cell >= grid.size() / 3 && cell % 3 == g - 1)
                          : cell % groups == g)
            cells.push_back(cell);
        struct Counted final : SceneSink {
          std::size_t announced = 0, reserves = 0;
          std::vector<SceneDisc> discs;
          void reserve(std::size_t n) override { announced = n, ++reserves; }
          void add(const SceneDisc& d) override { discs.push_back(d); }
        } sink;
        c.scene.type->cells(in, grid, cells, sink);
        EXPECT_EQ(sink.reserves, 1u);
        ASSERT_EQ(sink.announced, sink.discs.size()) << "the exact count before the discs";
        for (std::size_t k = 0; k < sink.discs.size(); ++k) {
          const SceneDisc& d = sink.discs[k];
          const SceneDisc& w = whole.at(static_cast<std::size_t>(d.gid));
          ASSERT_TRUE(d.x.x == w.x.x && d.x.y == w.x.y && d.radius == w.radius && d.material == w.material)
              << "disc " << d.gid << " differs from the whole build's";
          EXPECT_TRUE(std::binary_search(cells.begin(), cells.end(), grid.cell_of(d.x))) << "disc " << d.gid;
          if (k > 0) {
            EXPECT_LT(sink.discs[k - 1].gid, d.gid) << "ascending gid";
          }
          ++seen[static_cast<std::size_t>(d.gid)];
        }
      }
      EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<std::ptrdiff_t>(whole.size())) << "once each";
      // The first map's weights: the whole grid holds scene.count, half the region's width about half of it.
      const int nx = grid.nx(), ny = grid.ny();
      EXPECT_EQ(c.scene.type->rect_count(in, grid, 0, 0, nx, ny), 3000u);
      std::uint64_t left = 0;
      for (const auto& d : whole) left += grid.column_of(d.x) < nx / 2;
      const double expected = static_cast<double>(c.scene.type->rect_count(in, grid, 0, 0, nx / 2, ny));
      EXPECT_NEAR(expected, static_cast<double>(left), 0.05 * 3000) << "expected against placed";
    }
}

TEST(SceneTiles, ATiltedCellIsNotBuiltCellByCell) {
  const Config c = parse_config_text(kTiles);
  Domain tilted = c.domain;
  tilted.tilt = 0.01;
  EXPECT_EQ(scene::by_cells(SceneInputs{c.scene, tilted, "", nullptr}), 0.0) << "whole on every rank instead";
}

TEST(SceneTiles, TooManyDiscsOrARegionOutsideTheDomainAreRefusedNamingTheKeys) {
  const auto message = [](const std::vector<std::string>& args) {
    try {
      const Config c = parse_config_text(kTiles, args);
      whole_of(c);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string dense = message({"--scene.count=20000"});
  EXPECT_NE(dense.find("scene.count = 20000"), std::string::npos) << dense;
  EXPECT_NE(dense.find("scene.max_attempts"), std::string::npos) << dense;
  const std::string outside = message({"--scene.region=0.01 0.35 0.02 0.3"});
  EXPECT_NE(outside.find("scene.region"), std::string::npos) << outside;
  EXPECT_NE(outside.find("inside the domain"), std::string::npos) << outside;
  EXPECT_NE(message({"--scene.numbering=rows"}).find("scene.numbering"), std::string::npos);
  EXPECT_NE(message({"--scene.count=0"}).find("scene.count"), std::string::npos);
}

}  // namespace
}  // namespace rondel
