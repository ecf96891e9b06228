// A lattice built by each rank (docs/scaling.md, "Set-up"): the discs of its own cells (SceneType::by_cells, a
// lattice inside the domain) or, when the lattice wraps round a periodic side, its block of gids sent to the owners
// of their cells (scene::in_blocks). The run gives the bits of the 1-rank run with every partitioner (check_scene),
// each rank holds only its block before the discs move, and the set-up's refusals are the same on any rank count. A
// Rondel file and a CSV file are read in blocks too.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <utility>

#include "ParallelTestUtil.hpp"
#include "core/Config.hpp"
#include "core/SceneBuilder.hpp"
#include "core/SceneTypes.hpp"
#include "physics/LawRegistry.hpp"

namespace rondel {
namespace {

using namespace partest;

// A hexagonal lattice of 30 x 24 discs with a drift falls into a box with rolling resistance: every disc crosses
// rank borders on its way down.
const char* kLattice = R"(
[domain]
xlo = 0
xhi = 0.07
ylo = 0
yhi = 0.06
[gravity]
y = -9.81
[linear]
k_n = 1e6
e = 0.4
[coulomb]
k_s = 7.5e5
mu = 0.5
[contact]
rolling = wang
[wang]
k_r = 2e5
mu_r = 0.1
[walls]
box = bottom left right
[scene]
type = lattice_hex
nx = 30
ny = 24
radius = 0.00095
spacing = 0.0021
x0 = 0.003
y0 = 0.004
vx = 0.3
vy = -0.2
omega = 20
)";

TEST(SetupBlocks, ALatticeBuiltCellByCellGivesTheBitsOfOneRank) {
  const Config c = parse_config_text(kLattice);
  ASSERT_GT(scene::by_cells(SceneInputs{c.scene, c.domain, "", nullptr}), 0.0);
  check_scene("lattice by cells", kLattice, 4000, 500, true);
}

// Periodic in x, the lattice from x = 0.05 on: its right part wraps to the left side.
std::string wrapping_lattice() {
  std::string ini = kLattice;
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"yhi = 0.06\n", "yhi = 0.06\nperiodic_x = true\n"},
                                 {"box = bottom left right", "box = bottom"},
                                 {"x0 = 0.003", "x0 = 0.05"}})
    ini.replace(ini.find(from), from.size(), to);
  return ini;
}

TEST(SetupBlocks, ALatticeThatWrapsIsBuiltInBlocksAndGivesTheBitsOfOneRank) {
  const std::string ini = wrapping_lattice();
  const Config c = parse_config_text(ini);
  ASSERT_EQ(scene::by_cells(SceneInputs{c.scene, c.domain, "", nullptr}), 0.0);
  check_scene("lattice in blocks", ini, 1500, 500, true);
}

// The same box with a random packing placed tile by tile (scene.type = random_tiles): each rank places the tiles of
// its cells and their halo.
std::string random_tiles() {
  std::string ini = kLattice;
  ini.replace(ini.find("type = lattice_hex"), std::string::npos,
              "type = random_tiles\ncount = 700\nregion = 0.001 0.069 0.001 0.05\nradius_min = 0.0007\n"
              "radius_max = 0.001\nvx = 0.3\nvy = -0.2\nomega = 20\nseed = 5\n");
  return ini;
}

TEST(SetupBlocks, ARandomPackingPlacedTileByTileGivesTheBitsOfOneRank) {
  const std::string ini = random_tiles();
  const Config c = parse_config_text(ini);
  ASSERT_GT(scene::by_cells(SceneInputs{c.scene, c.domain, "", nullptr}), 0.0);
  check_scene("random tiles", ini, 4000, 500, true);
}

// The InputError that the set-up of `ini` with `args` throws on all the ranks, checked to be the one it throws on
// one rank alone ("" when it did not throw).
std::string refused_alike(const std::string& ini, const std::vector<std::string>& args) {
  std::string here, one;
  bool threw = false;
  try {
    const Communicator world;
    Simulation s(parse_config_text(ini, args), world, false);
  } catch (const InputError& e) {
    threw = true;
    here = e.what();
  }
  EXPECT_TRUE(all_ranks(threw)) << "refused on some ranks only";
  if (world_rank() == 0) {
    const Communicator self(MPI_COMM_SELF);
    try {
      Simulation s(parse_config_text(ini, args), self, false);
    } catch (const InputError& e) {
      one = e.what();
    }
  }
  one = broadcast(one);
  EXPECT_FALSE(one.empty());
  EXPECT_EQ(here, one);
  return here;
}

TEST(SetupBlocks, ARandomPackingTooDenseIsRefusedWithTheSameMessageOnAnyRankCount) {
  const std::string here = refused_alike(random_tiles(), {"--scene.count=3000"});
  EXPECT_NE(here.find("scene.count = 3000: the discs do not fit"), std::string::npos) << here;
}

TEST(SetupBlocks, ARondelFileSceneIsReadInBlocksAndGivesTheBitsOfOneRank) {
  // A stage from the checkpoint of a 1-rank run (300 steps in: the lattice falling, turning, drifting): each rank
  // reads its block of the file's discs (scene::in_blocks), sent to the owners of their cells.
  SharedTempDir tmp("file-scene");
  const std::string out = (tmp.path() / "prepare").string();
  if (world_rank() == 0) {
    const Communicator self(MPI_COMM_SELF);
    Simulation prepare(parse_config_text(kLattice, {"--run.output=" + out, "--run.steps=300"}), self, true);
    prepare.run();
  }
  world_barrier();
  std::string ini = kLattice;
  ini.replace(ini.find("[scene]"), std::string::npos, "[scene]\ntype = file\nfile = " + out + "\n");
  const Config c = parse_config_text(ini);
  ASSERT_TRUE(scene::in_blocks(c.scene));
  check_scene("file scene in blocks", ini, 1500, 500, true);
}

TEST(SetupBlocks, ACsvSceneIsReadInBlocksOfItsBytesAndGivesTheBitsOfOneRank) {
  // The final.csv of a 1-rank run (300 steps in) as a CSV scene: each rank parses the lines that start in its block of
  // the file's bytes, and the discs go to the owners of their cells.
  SharedTempDir tmp("csv-scene");
  const std::string out = (tmp.path() / "prepare").string();
  if (world_rank() == 0) {
    const Communicator self(MPI_COMM_SELF);
    Simulation prepare(parse_config_text(kLattice, {"--run.output=" + out, "--run.steps=300"}), self, true);
    prepare.run();
  }
  world_barrier();
  std::string ini = kLattice;
  ini.replace(ini.find("[scene]"), std::string::npos, "[scene]\ntype = csv\nfile = " + out + "/final.csv\n");
  const Config c = parse_config_text(ini);
  ASSERT_TRUE(scene::in_blocks(c.scene));
  check_scene("csv scene in blocks", ini, 1500, 500, true);
}

TEST(SetupBlocks, AReplicatedCsvSceneIsBuiltInBlocksOfItsIdsAndGivesTheBitsOfOneRank) {
  // A tile of 300 discs (a random packing of a cell 0.035 m wide, written by rank 0) copied 4 times across a
  // periodic box: each rank reads the tile and builds the rows of the box that hold its block of the copies' ids.
  SharedTempDir tmp("replicated");
  const std::string tile = (tmp.path() / "tile.csv").string();
  if (world_rank() == 0) {
    const Config cell = parse_config_text(
        random_tiles(), {"--domain.xhi=0.035", "--scene.region=0.001 0.034 0.001 0.05", "--scene.count=300"});
    std::ofstream out(tile);
    out << "id,x,y,radius,vx,vy,omega\n" << std::hexfloat;
    for (const auto& d : build_scene(SceneInputs{cell.scene, cell.domain, "", nullptr}))
      out << d.gid << "," << d.x.x << "," << d.x.y << "," << d.radius << "," << d.v.x << "," << d.v.y << "," << d.omega
          << "\n";
  }
  world_barrier();
  std::string ini = kLattice;
  ini.replace(ini.find("xhi = 0.07"), 10, "xhi = 0.14");
  ini.replace(ini.find("yhi = 0.06\n"), 11, "yhi = 0.06\nperiodic_x = true\n");
  ini.replace(ini.find("box = bottom left right"), 23, "box = bottom");
  ini.replace(ini.find("[scene]"), std::string::npos, "[scene]\ntype = csv\nfile = " + tile + "\nreplicate_x = 4\n");
  const Config c = parse_config_text(ini);
  ASSERT_TRUE(scene::in_blocks(c.scene));
  check_scene("replicated csv in blocks", ini, 4000, 500, true);
}

TEST(SetupBlocks, EachRankBuildsOnlyItsBlockAndTheBlocksMakeTheScene) {
  const Config c = parse_config_text(kLattice);
  const SceneInputs in{c.scene, c.domain, "", nullptr};
  const auto whole = build_scene(in);
  const int P = world_size();
  std::size_t total = 0;
  for (int r = 0; r < P; ++r) {
    const auto block = build_scene_block(in, r, P);
    EXPECT_LE(block.size(), whole.size() / static_cast<std::size_t>(P) + 1);
    for (const auto& d : block) {
      const auto& w = whole.at(static_cast<std::size_t>(d.gid));
      EXPECT_TRUE(d.gid == w.gid && d.x.x == w.x.x && d.x.y == w.x.y && d.radius == w.radius && d.v.x == w.v.x &&
                  d.material == w.material)
          << "disc " << d.gid << " of block " << r;
    }
    if (!block.empty()) {
      EXPECT_EQ(block.front().gid, static_cast<std::int64_t>(total)) << "blocks follow each other";
    }
    total += block.size();
  }
  EXPECT_EQ(total, whole.size());
  // Two materials: each site's from the keyed shuffle of the exact counts, the same in any block.
  const Config two =
      parse_config_text(std::string(kLattice) + "[material.a]\ndensity = 2650\n[material.b]\ndensity = 7800\n",
                        {"--scene.materials=a b", "--scene.material_fractions=0.5 0.5"});
  ASSERT_TRUE(scene::in_blocks(two.scene));
  const SceneInputs in2{two.scene, two.domain, "", nullptr};
  const auto whole2 = build_scene(in2);
  for (const auto& d : build_scene_block(in2, world_rank(), P))
    EXPECT_EQ(d.material, whole2.at(static_cast<std::size_t>(d.gid)).material) << "disc " << d.gid;
}

TEST(SetupBlocks, EveryDiscIsOnTheOwnerOfItsCellWhenTheSetUpEnds) {
  // The first rebuild moves no disc (Simulation::rebuild(true) skips its migration after distribute_discs): each
  // way of making a scene, with each partitioner, leaves every disc on the rank that owns its cell.
  std::string whole = random_tiles();
  whole.replace(whole.find("type = random_tiles"), 19, "type = random");
  const Communicator world(MPI_COMM_WORLD);
  for (const auto& [name, ini] : {std::pair<std::string, std::string>{"lattice by cells", kLattice},
                                  {"lattice in blocks", wrapping_lattice()},
                                  {"random tiles", random_tiles()},
                                  {"random, whole on every rank", whole}}) {
    for (const Variant& var : variants()) {
      const Simulation sim(parse_config_text(ini, var.overrides), world, false);
      std::size_t elsewhere = 0;
      for (std::size_t i = 0; i < sim.discs().n_owned(); ++i)
        elsewhere += sim.decomposition().owner(sim.discs().position[i]) != world.rank();
      EXPECT_EQ(world.sum(static_cast<std::int64_t>(elsewhere)), 0) << name << ", " << var.name;
    }
  }
}

TEST(SetupBlocks, InitialOverlapsAreRefusedWithTheSameMessageOnAnyRankCount) {
  // Spacing 1.8 R: every neighbour pair overlaps 0.2 R. The count and the worst pair do not depend on the blocks.
  const std::string here = refused_alike(kLattice, {"--scene.spacing=0.00171", "--scene.ny=6"});
  EXPECT_NE(here.find("initial overlaps exceed scene.max_initial_overlap"), std::string::npos) << here;
}

}  // namespace
}  // namespace rondel
