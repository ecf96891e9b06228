// Wall kinds through a Rondel file (core/WallKinds.hpp, FORMAT.md): every kind written reads back as itself, the
// file carries the kinds' names in code order (/walls/kind_names, which the Python reader decodes with), and a
// code that no kind has is refused naming the file, the wall, the code and the kinds (it used to read back as a
// circle).
#include <gtest/gtest.h>
#include <hdf5.h>

#include <string>
#include <vector>

#include "ParallelTestUtil.hpp"
#include "core/Errors.hpp"
#include "core/WallKinds.hpp"
#include "parallel/Hdf5File.hpp"
#include "parallel/StateFile.hpp"

namespace rondel {
namespace {

// A file with one disc and the walls `walls`.
std::string file_with(const WallSet& walls, const std::string& dir) {
  static const Communicator world(MPI_COMM_WORLD);
  DiscStore discs;
  if (world.root()) discs.add(0, 0, 0.01, 2650.0, 1.0, {0.5, 0.5});
  StateHeader h;
  h.kind = "checkpoint";
  const std::string path = dir + "/walls.h5";
  write_state_file(path, h, discs, ContactTable{}, ContactTable{}, walls, world, {}, 0.0);
  return path;
}

TEST(WallKindsFile, EveryKindReadsBackAsItselfWithTheNamesOfTheCodes) {
  static const Communicator world(MPI_COMM_WORLD);
  const Domain domain{0.0, 1.0, 0.0, 1.0, false, false};
  WallSet walls;
  WallKinds::each([&]<class K>() { walls.push_back(K::read({K::example.begin(), K::example.end()}, domain)); });
  const partest::SharedTempDir dir("wallkinds");
  const std::string path = file_with(walls, dir.path().string());
  const WallSet back = read_state_walls(path, world);
  ASSERT_EQ(back.size(), walls.size());
  for (std::size_t w = 0; w < walls.size(); ++w) {
    EXPECT_EQ(back[w].kind, walls[w].kind) << "wall " << w;
    EXPECT_EQ(back[w].p0.x, walls[w].p0.x) << "wall " << w;
    EXPECT_EQ(back[w].p1.y, walls[w].p1.y) << "wall " << w;
    EXPECT_EQ(back[w].centre.x, walls[w].centre.x) << "wall " << w;
    EXPECT_EQ(back[w].radius, walls[w].radius) << "wall " << w;
    EXPECT_EQ(back[w].omega, walls[w].omega) << "wall " << w;
    EXPECT_EQ(back[w].velocity.y, walls[w].velocity.y) << "wall " << w;
  }
  std::string names;
  for (const std::string& n : WallKinds::names_by_code()) names += (names.empty() ? "" : " ") + n;
  const Hdf5File f(path, Hdf5File::Mode::read, world);
  EXPECT_EQ(f.read_string_attribute("/walls", "kind_names"), names);
}

TEST(WallKindsFile, ACodeNoKindHasIsRefusedNamingIt) {
  static const Communicator world(MPI_COMM_WORLD);
  WallSet walls(2);
  walls[1].kind = static_cast<Wall::Kind>(WallKinds::size);  // what a newer writer's kind would be here
  const partest::SharedTempDir dir("wallkinds-bad");
  const std::string path = file_with(walls, dir.path().string());
  try {
    read_state_walls(path, world);
    ADD_FAILURE() << "a wall of kind " << WallKinds::size << " was read";
  } catch (const InputError& e) {
    const std::string m = e.what();
    for (const std::string& word : {path, std::string("wall 1"), "kind " + std::to_string(WallKinds::size),
                                    std::string("0 line, 1 segment, 2 circle")})
      EXPECT_NE(m.find(word), std::string::npos) << word << " not in: " << m;
  }
}

}  // namespace
}  // namespace rondel
