// How scenes number their discs (docs/benchmarks.md, "The order of the ids"): scene.numbering = rows numbers a
// random packing in rows of height twice the largest radius, by x within a row, without moving a disc;
// replicated copies of a csv file are numbered the same way across the whole box; the key is refused where it
// does not apply and for values other than placement and rows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>
#include <vector>

#include "core/Config.hpp"
#include "core/Errors.hpp"
#include "core/SceneBuilder.hpp"
#include "core/SceneCsv.hpp"
#include "core/SceneTypes.hpp"
#include "physics/LawRegistry.hpp"

namespace rondel {
namespace {

const std::string kRandom = R"(
[run]
steps = 1
[domain]
xlo = 0
xhi = 0.4
ylo = 0
yhi = 0.3
[linear]
k_n = 1e5
e = 0.8
[coulomb]
k_s = 7.5e4
mu = 0.5
[scene]
type = random
count = 600
radius_min = 0.002
radius_max = 0.005
seed = 11
)";

// The discs as (x, y, radius), sorted: the same set whatever the numbering.
std::vector<std::tuple<double, double, double>> places(const std::vector<SceneDisc>& discs) {
  std::vector<std::tuple<double, double, double>> p;
  for (const auto& d : discs) p.emplace_back(d.x.x, d.x.y, d.radius);
  std::sort(p.begin(), p.end());
  return p;
}

// Ids 0..n-1 in rows of height 2 R_max from ylo, by x within a row.
::testing::AssertionResult numbered_in_rows(const std::vector<SceneDisc>& discs, double ylo) {
  double R_max = 0.0;
  for (const auto& d : discs) R_max = std::max(R_max, d.radius);
  for (std::size_t k = 0; k < discs.size(); ++k) {
    if (discs[k].gid != static_cast<std::int64_t>(k))
      return ::testing::AssertionFailure() << "disc " << k << " has id " << discs[k].gid;
    if (k == 0) continue;
    const double row = std::floor((discs[k].x.y - ylo) / (2 * R_max));
    const double before = std::floor((discs[k - 1].x.y - ylo) / (2 * R_max));
    if (row < before || (row == before && discs[k].x.x < discs[k - 1].x.x))
      return ::testing::AssertionFailure() << "id " << k << " comes before id " << k - 1 << " in rows";
  }
  return ::testing::AssertionSuccess();
}

TEST(SceneNumbering, RandomInRowsMovesNoDisc) {
  const Config placed = parse_config_text(kRandom);
  const Config rows = parse_config_text(kRandom, {"--scene.numbering=rows"});
  EXPECT_EQ(placed.scene.numbering, Numbering::placement);
  const auto a = build_scene(SceneInputs{placed.scene, placed.domain, ""});
  const auto b = build_scene(SceneInputs{rows.scene, rows.domain, ""});
  ASSERT_EQ(a.size(), 600u);
  EXPECT_EQ(places(a), places(b));
  EXPECT_TRUE(numbered_in_rows(b, rows.scene.region[2]));
  EXPECT_FALSE(numbered_in_rows(a, placed.scene.region[2])) << "placement order is largest first, not rows";
  EXPECT_GE(a.front().radius, a.back().radius);
}

TEST(SceneNumbering, ReplicatedCopiesAreNumberedInRowsAcrossTheBox) {
  const auto dir = std::filesystem::temp_directory_path() / "rondel_scene_numbering";
  std::filesystem::create_directories(dir);
  const std::string file = (dir / "cell.csv").string();
  {
    // Four discs of a periodic cell of side 1, ids not 0-based and not in rows.
    std::ofstream out(file);
    out << "id,x,y,radius\n7,0.75,0.75,0.2\n3,0.25,0.25,0.2\n9,0.75,0.25,0.2\n5,0.25,0.75,0.2\n";
  }
  const std::string ini =
      "[run]\nsteps = 1\n[domain]\nxlo = 0\nxhi = 3\nylo = 0\nyhi = 2\nperiodic_x = true\n"
      "periodic_y = true\n[linear]\nk_n = 1e5\ne = 0.8\n[coulomb]\nk_s = 7.5e4\nmu = 0.5\n"
      "[scene]\ntype = csv\nfile = " +
      file + "\nreplicate_x = 3\nreplicate_y = 2\n";
  const Config c = parse_config_text(ini);
  const auto discs = build_scene(SceneInputs{c.scene, c.domain, ""});
  ASSERT_EQ(discs.size(), 24u);
  EXPECT_TRUE(numbered_in_rows(discs, 0.0));
  // Row 0 (y = 0.25) holds x = 0.25, 0.75, 1.25, ... 2.75: the copies side by side, not one after the other.
  for (int k = 0; k < 6; ++k) {
    EXPECT_DOUBLE_EQ(discs[static_cast<std::size_t>(k)].x.y, 0.25);
    EXPECT_DOUBLE_EQ(discs[static_cast<std::size_t>(k)].x.x, 0.25 + 0.5 * k);
  }
  // A file whose ids repeat is refused, naming the file and the id, replicated or not.
  {
    std::ofstream out(file, std::ios::app);
    out << "3,0.5,0.5,0.1\n";
  }
  for (const std::string copies : {"3", "1"}) {
    try {
      const Config d = parse_config_text(ini, {"--scene.replicate_x=" + copies});
      build_scene(SceneInputs{d.scene, d.domain, ""});
      ADD_FAILURE() << "a repeated id was accepted, replicate_x = " << copies;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("id 3 appears twice"), std::string::npos) << e.what();
    }
  }
  std::filesystem::remove_all(dir);
}

TEST(SceneNumbering, EachRanksBlockOfTheCopiesIsTheWholeReplicationsDiscsOfItsIds) {
  // 60 discs of a cell 0.3 x 0.2 (some of one x, rows of the box cut through the file's rows), copied 5 x 3 times:
  // each rank builds only the box rows that hold its ids (scene_csv::replicated_block).
  const auto dir = std::filesystem::temp_directory_path() / "rondel_replicated_blocks";
  std::filesystem::create_directories(dir);
  const std::string file = (dir / "tile.csv").string();
  {
    std::ofstream out(file);
    out << "id,x,y,radius\n";
    SceneRandom rng(3);
    for (int k = 0; k < 60; ++k)
      out << 100 + 7 * k << "," << (k % 4 == 0 ? 0.15 : 0.3 * rng.uniform()) << "," << 0.2 * rng.uniform() << ","
          << 0.004 + 0.003 * rng.uniform() << "\n";
  }
  const std::string ini =
      "[domain]\nxlo = 0\nxhi = 1.5\nylo = 0\nyhi = 0.6\nperiodic_x = true\nperiodic_y = true\n[linear]\nk_n = 1e5\n"
      "[coulomb]\nk_s = 7.5e4\nmu = 0.5\n[scene]\ntype = csv\nfile = " +
      file + "\nreplicate_x = 5\nreplicate_y = 3\n";
  const Config c = parse_config_text(ini);
  const auto whole = build_scene(SceneInputs{c.scene, c.domain, ""});
  ASSERT_EQ(whole.size(), 900u);
  const auto tile = scene_csv::whole_file(c.scene, file);
  for (int ranks : {1, 2, 3, 7, 64, 1000}) {
    std::size_t k = 0;
    for (int r = 0; r < ranks; ++r)
      for (const auto& d : scene_csv::replicated_block(c.scene, c.domain, tile, r, ranks)) {
        ASSERT_LT(k, whole.size()) << ranks << " ranks";
        const auto& w = whole[k++];
        ASSERT_TRUE(d.gid == w.gid && d.x.x == w.x.x && d.x.y == w.x.y && d.radius == w.radius)
            << "id " << d.gid << " (the whole replication's " << w.gid << "), rank " << r << " of " << ranks;
      }
    EXPECT_EQ(k, whole.size()) << ranks << " ranks";
  }
  std::filesystem::remove_all(dir);
}

TEST(SceneNumbering, TheKeyIsRefusedWhereItDoesNotApply) {
  for (const auto& [overrides, what] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"--scene.numbering=spiral"}, "placement | rows"},
           {{"--scene.numbering=Rows"}, "placement | rows"},
           {{"--scene.type=lattice_square", "--scene.nx=3", "--scene.ny=3", "--scene.radius=0.005",
             "--scene.numbering=rows"},
            "only with scene.type = random"}}) {
    try {
      parse_config_text(kRandom, overrides);
      ADD_FAILURE() << "accepted: " << overrides.back();
    } catch (const ConfigError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("scene.numbering"), std::string::npos) << m;
      EXPECT_NE(m.find(what), std::string::npos) << m;
    }
  }
}

}  // namespace
}  // namespace rondel
