// The real executable on 1 to 3 ranks: an error found on the last rank only, and an I/O error found by
// rank 0 only, stop every rank with the documented exit code (README "Exit codes") and the message printed
// exactly once on stderr, never a hang (each command runs under `timeout`).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "app/OutputNames.hpp"
#include "core/Config.hpp"
#include "core/ExitCodes.hpp"
#include "core/FaultInjection.hpp"
#include "support/BehindWall.hpp"
#include "support/Command.hpp"
#include "support/TempDir.hpp"

namespace rondel {
namespace {

namespace fs = std::filesystem;
using test::Outcome;
using test::TempDir;

const fs::path kSource = RONDEL_SOURCE_DIR;
// Seconds before `timeout` stops a command: a hang fails the test instead of the CTest timeout.
constexpr int kLimit = 120;

Outcome rondel_on(const TempDir& dir, int ranks, const std::string& args, const std::string& env = "") {
  return test::mpirun_rondel(dir, ranks, args, env, kLimit);
}

std::size_t count(const std::string& text, const std::string& what) { return test::occurrences(text, what); }

TEST(ExitCodes, ErrorOnTheLastRankOnlyIsPrintedOnceWithItsCode) {
  if (!test::have_program("mpirun")) GTEST_SKIP() << "mpirun is not installed";
  for (const int ranks : {1, 2, 3}) {
    TempDir dir("rondel-exit-behind");
    const fs::path run = dir / "run";
    const std::string ini = test::behind_wall_ini(run);
    test::write_file(dir / "behind.ini", ini);
    test::write_behind_wall_checkpoint(run, parse_config_text(ini, {}));
    const Outcome o = rondel_on(dir, ranks, "behind.ini --resume " + run.string());
    const std::string tag = std::to_string(ranks) + " rank(s)";
    EXPECT_EQ(o.exit_code, 1) << tag << "; stderr:\n" << o.err;
    EXPECT_EQ(count(o.err, "rondel: input error: " + test::behind_wall_message()), 1u) << tag << "; stderr:\n" << o.err;
    EXPECT_EQ(count(o.err, "error:"), 1u) << tag << ": one message only; stderr:\n" << o.err;
    EXPECT_EQ(o.err.find("only; stopping every rank"), std::string::npos) << tag << ": not agreed; " << o.err;
  }
}

TEST(ExitCodes, AnIoErrorOfRankZeroExitsWithFive) {
  // A text output of the run is /dev/full: its rows fail to reach the disk (log.txt and diagnostics.csv at
  // the first output step, measures.csv when it is flushed before the final files); the run stops there.
  if (!test::have_program("mpirun")) GTEST_SKIP() << "mpirun is not installed";
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  for (const char* file : {"log.txt", "diagnostics.csv", "measures.csv"}) {
    for (const int ranks : {1, 3}) {
      TempDir dir("rondel-exit-io");
      const fs::path run = dir / "run";
      fs::create_directories(run);
      fs::create_symlink("/dev/full", run / file);
      const std::string scene = (kSource / "inputs/two_disc_impact.ini").string();
      const std::string csv = (kSource / "inputs/two_disc_impact.csv").string();
      const Outcome o =
          rondel_on(dir, ranks,
                    test::quoted(scene) + " --scene.file=" + test::quoted(csv) + " --run.output=" + test::quoted(run) +
                        " --run.overwrite=true --run.steps=50 --run.progress=false");
      const std::string tag = std::string(file) + ", " + std::to_string(ranks) + " rank(s)";
      EXPECT_EQ(o.exit_code, 5) << tag << "; stderr:\n" << o.err;
      EXPECT_EQ(count(o.err, "rondel: I/O error: cannot write '" + (run / file).string() + "'"), 1u)
          << tag << "; stderr:\n"
          << o.err;
      EXPECT_EQ(count(o.err, "error:"), 1u) << tag << ": one message only; stderr:\n" << o.err;
      EXPECT_FALSE(fs::exists(run / "final.csv")) << tag << ": a failed run wrote final.csv";
      EXPECT_FALSE(fs::exists(run / "summary.json")) << tag << ": a failed run wrote summary.json";
    }
  }
}

TEST(ExitCodes, TheReadmesTableListsExactlyTheCodesOfTheRegistry) {
  std::ifstream in(kSource / "README.md");
  ASSERT_TRUE(in) << "no README.md in " << kSource;
  std::set<int> table;
  bool inside = false;
  const std::regex row(R"(^\| (\d+) \| .*)");
  for (std::string line; std::getline(in, line);) {
    if (line == "### Exit codes") inside = true;
    if (!inside) continue;
    if (line.rfind("###", 0) == 0 && line != "### Exit codes") break;
    std::smatch m;
    if (std::regex_match(line, m, row)) table.insert(std::stoi(m[1]));
  }
  std::set<int> codes;
  for (const ExitCode& c : kExitCodes) codes.insert(c.code);
  EXPECT_EQ(table, codes) << "README.md's table \"Exit codes\" and core/ExitCodes.hpp differ";
  for (const ErrorExit& e : kErrorExits)
    EXPECT_TRUE(codes.count(e.exit.code))
        << "error kind " << static_cast<int>(e.kind) << " exits with an unlisted code";
}

TEST(ExitCodes, TheFaultTableOfTheDevelopersGuideListsExactlyTheSites) {
  std::ifstream in(kSource / "docs/developing.md");
  ASSERT_TRUE(in) << "no docs/developing.md in " << kSource;
  std::set<std::string> table;
  bool inside = false;
  const std::regex row(R"(^\| `([a-z0-9_]+:?)[A-Z]*` \| .*)");
  for (std::string line; std::getline(in, line);) {
    if (line == "| SITE | fails |") inside = true;
    if (!inside) continue;
    if (line.empty()) break;
    std::smatch m;
    if (std::regex_match(line, m, row)) table.insert(m[1]);
  }
  std::set<std::string> sites;
  for (const FaultSiteInfo& f : kFaultSites) sites.insert(f.name);
  EXPECT_EQ(table, sites) << "docs/developing.md's table of fault sites and core/FaultInjection.hpp differ";
}

// A misspelt fault site used to inject nothing and let the run exit with 0 (a test of an error path then passed
// without its error). Every value that is not a fault is refused before any work, naming it and what is allowed.
TEST(ExitCodes, AFaultHookThatInjectsNothingIsRefused) {
  if (!test::have_program("mpirun")) GTEST_SKIP() << "mpirun is not installed";
  const std::string scene = (kSource / "inputs/two_disc_impact.ini").string();
  const std::string csv = (kSource / "inputs/two_disc_impact.csv").string();
  for (const auto& [value, why] : std::vector<std::pair<std::string, std::string>>{
           {"nosuchsite", "'nosuchsite' is not a fault site"},
           {"text:nosuch.csv", "'nosuch.csv' is not a text file of the output directory"},
           {"hdf5_write@x", "@RANK must be a whole number >= 0"},
           {"hdf5_write#0", "#N must be a whole number >= 1"}}) {
    for (const int ranks : {1, 2}) {
      TempDir dir("rondel-exit-fault");
      const Outcome o = rondel_on(dir, ranks,
                                  test::quoted(scene) + " --scene.file=" + test::quoted(csv) + " --run.output=" +
                                      test::quoted(dir / "run") + " --run.steps=20 --run.progress=false",
                                  "RONDEL_FAULT=" + value);
      const std::string tag = value + ", " + std::to_string(ranks) + " rank(s)";
      EXPECT_EQ(o.exit_code, kExitInput.code) << tag << "; stderr:\n" << o.err;
      EXPECT_EQ(count(o.err, "rondel: configuration error: the environment variable RONDEL_FAULT = '" + value + "'"),
                1u)
          << tag << "; stderr:\n"
          << o.err;
      for (const std::string& word :
           {why, std::string("hdf5_write, hdf5_close, reserve, text:"), std::string(output::kFinal)})
        EXPECT_NE(o.err.find(word), std::string::npos) << tag << ": '" << word << "' not in " << o.err;
      EXPECT_FALSE(fs::exists(dir / "run")) << tag << ": the output directory was created";
    }
  }
  // A valid one is taken (it fails the text file it names: exit 5).
  TempDir dir("rondel-exit-fault-ok");
  const Outcome o = rondel_on(dir, 1,
                              test::quoted(scene) + " --scene.file=" + test::quoted(csv) +
                                  " --run.output=" + test::quoted(dir / "run") + " --run.steps=20 --run.progress=false",
                              std::string("RONDEL_FAULT=text:") + output::kFinal);
  EXPECT_EQ(o.exit_code, kExitIo.code) << o.err;
}

}  // namespace
}  // namespace rondel
