// Files read in blocks of their bytes (parallel/TextBlocks.hpp) and CSV scenes read that way (app/CsvScene.cpp): the
// blocks are whole lines and make the file, on 1 to 4 ranks, whatever the lines' lengths; a CSV scene's discs, and
// its refusals, are those of the whole file read on one process (core/SceneCsv.cpp), line numbers included.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

#include "ParallelTestUtil.hpp"
#include "app/Restart.hpp"
#include "core/Config.hpp"
#include "core/Errors.hpp"
#include "core/SceneCsv.hpp"
#include "core/SceneTypes.hpp"
#include "parallel/TextBlocks.hpp"

namespace rondel {
namespace {

using namespace partest;

TEST(TextBlocks, TheBlocksAreWholeLinesThatMakeTheFileInOrder) {
  const Communicator world;
  const std::string long_line(9000, 'x');
  std::string many;
  for (int k = 0; k < 700; ++k) many += std::to_string(k * 7919) + (k % 3 ? ",a\n" : "\n");
  const std::vector<std::string> files{"",
                                       "a",
                                       "\n",
                                       "\n\n\n",
                                       "ab\ncd",
                                       "ab\ncd\n",
                                       "one line without an end, longer than a few ranks' blocks",
                                       many,
                                       many.substr(0, many.size() - 1),
                                       "short\n" + long_line + "\nend\n",
                                       long_line + "\n" + long_line,
                                       "a\r\nb\rc\n"};
  for (std::size_t f = 0; f < files.size(); ++f) {
    const std::string& content = files[f];
    const std::string path = write_temp("rondel-blocks", content);
    const std::string mine = read_line_blocks(path, "test.file", world);
    std::int64_t lines = std::count(mine.begin(), mine.end(), '\n');
    const std::int64_t first = first_line_number(lines, world);
    const std::vector<std::string> blocks = all_gather(mine);
    std::string joined;
    for (const auto& b : blocks) {
      if (!b.empty() && !joined.empty()) {
        EXPECT_EQ(joined.back(), '\n') << "file " << f << ": a block starts inside a line";
      }
      joined += b;
    }
    EXPECT_EQ(joined, content) << "file " << f << ": the blocks do not make the file";
    std::int64_t before = 1;
    for (int q = 0; q < world_rank(); ++q) before += std::count(blocks[q].begin(), blocks[q].end(), '\n');
    EXPECT_EQ(first, before) << "file " << f;
  }
  EXPECT_THROW(read_line_blocks("/nonexistent/rondel-blocks.csv", "test.file", world), InputError);
}

const char* kIni = R"(
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
[material.sand]
density = 2650
[material.steel]
density = 7800
[scene]
type = csv
file = SCENE
)";

Config csv_config(const std::string& path) {
  std::string ini = kIni;
  ini.replace(ini.find("SCENE"), 5, path);
  return parse_config_text(ini);
}

// Every disc of the file in the blocks of the ranks (gid order), as "gid x y radius vx vy omega material" lines.
std::string discs_text(const std::vector<SceneDisc>& discs) {
  std::string out;
  for (const auto& d : discs)
    out += std::to_string(d.gid) + " " + std::to_string(d.x.x) + " " + std::to_string(d.x.y) + " " +
           std::to_string(d.radius) + " " + std::to_string(d.v.x) + " " + std::to_string(d.v.y) + " " +
           std::to_string(d.omega) + " " + std::to_string(d.material) + "\n";
  return out;
}

// The discs read in blocks (on the world) and the whole file read by one process: the same discs, or the same message.
std::string check_csv(const std::string& what, const std::string& content, bool has_discs = true) {
  // One file that every rank reads (as a run's scene.file is).
  SharedTempDir tmp("csv-blocks");
  const std::string path = (tmp.path() / "scene.csv").string();
  if (world_rank() == 0) std::ofstream(path, std::ios::binary) << content;
  world_barrier();
  const Config c = csv_config(path);
  EXPECT_TRUE(scene::in_blocks(c.scene));
  std::string whole, whole_error, blocks, blocks_error;
  try {
    whole = discs_text(build_scene(SceneInputs{c.scene, c.domain, "", nullptr}));
  } catch (const InputError& e) {
    whole_error = e.what();
  }
  const Communicator world;
  WallSet walls;
  Domain cell = c.domain;
  const FileScene files(c, walls, cell, world);
  try {
    const std::vector<std::string> all =
        all_gather(discs_text(build_scene(SceneInputs{c.scene, c.domain, "", &files})));
    for (const auto& b : all) blocks += b;
  } catch (const InputError& e) {
    blocks_error = e.what();
  }
  EXPECT_EQ(blocks_error, whole_error) << what;
  EXPECT_EQ(blocks, whole) << what;
  EXPECT_EQ(whole_error.empty() && !whole.empty(), has_discs) << what << ": " << whole_error;
  return blocks_error;
}

std::string rows(int first, int count, const std::string& end = "\n") {
  std::string out;
  for (int k = first; k < first + count; ++k)
    out += std::to_string(k) + "," + std::to_string(0.001 * (k % 900) + 0.01) + ",0.5,0.0004" +
           (k % 2 ? ",steel" : ",sand") + end;
  return out;
}

TEST(CsvBlocks, TheDiscsOfEachBlockAreThoseOfTheWholeFile) {
  check_csv("plain rows", rows(0, 500));
  check_csv("a header, comments, CR LF and a byte order mark",
            "\xEF\xBB\xBF# a scene\r\n\r\nid,x,y,radius,material\r\n" + rows(0, 200, "\r\n") + "# more\r\n" +
                rows(200, 200, "\r\n"));
  check_csv("lone CRs (one line of the file's LF pieces)", "id x y radius\r0 0.1 0.1 0.01\r1 0.2 0.1 0.01\r");
  check_csv("the header in a later rank's block",
            "#" + std::string(6000, '-') + "\n" + "\n# x\n" +
                "id,radius,y,x,vx,vy,omega,material\n3,0.01,0.5,0.5,1,2,3,steel\n");
  check_csv("no line with content", "# nothing\n\n#\n", false);
  check_csv("no line at all", "", false);
}

TEST(CsvBlocks, TheFirstBadLineIsNamedAsTheWholeFileNamesIt) {
  check_csv("a bad row near the end", rows(0, 400) + "400,0.5,oops,0.0004,sand\n" + rows(401, 10), false);
  check_csv("two bad rows, the first in an early block", rows(0, 3) + "3,0.5\n" + rows(4, 400) + "x\n", false);
  check_csv("a header that names an unknown column", "id,x,y,radius,colour\n" + rows(0, 50), false);
  check_csv("an unknown material on the last line", rows(0, 300) + "300,0.5,0.5,0.0004,glass", false);
}

TEST(CsvBlocks, TwoDiscsOfOneIdAreNamedByTheirLinesOnAnyRankCount) {
  // The id 5 on lines 6 and 408, the id 2 on lines 3, 199 and 409: the smallest id's first two lines.
  const std::string content = rows(0, 198) + rows(2, 1) + rows(300, 208) + rows(5, 1) + rows(2, 1);
  EXPECT_NE(check_csv("ids twice, far apart", content, false).find("lines 3 and 199: disc id 2 appears twice"),
            std::string::npos);
  EXPECT_NE(check_csv("an id twice, at the file's ends", rows(0, 1) + rows(7, 500) + rows(0, 1), false)
                .find("lines 1 and 502: disc id 0 appears twice"),
            std::string::npos);
}

}  // namespace
}  // namespace rondel
