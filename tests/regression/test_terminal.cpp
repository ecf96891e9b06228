// What the real executable prints and writes around the numbers: a short terminal (header, thermo lines,
// summary) in a pipe, under mpirun and in a pseudo-terminal, no carriage return outside a terminal;
// rondel --version; summary.json; the version and commit in log.txt and /run_metadata; the --resume
// notices; final.csv with its radius column, in hexadecimal and in decimal floats that read back the same.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "core/Config.hpp"
#include "core/Errors.hpp"
#include "parallel/Communicator.hpp"
#include "parallel/Hdf5File.hpp"
#include "physics/LawRegistry.hpp"
#include "rondel/Version.hpp"
#include "support/Assertions.hpp"
#include "support/Command.hpp"
#include "support/TempDir.hpp"

namespace rondel {
namespace {

namespace fs = std::filesystem;
using test::lines_of;
using test::names;
using test::Outcome;
using test::read_file;
using test::rondel_executable;
using test::TempDir;

const fs::path kSource = RONDEL_SOURCE_DIR;
// The default scene for a few hundred steps, its thermo interval scaled from 5000 of 45,000 steps so that
// it prints as many lines (steps 0, 40, ..., 400).
const std::string kDefaultScene = [] {
  std::string s(1, '\'');  // in steps: GCC 12 warns (-Wrestrict, a false positive) on "'" + s + "'"
  s += (kSource / "inputs/deposition.ini").string();
  return s + "' --run.steps=400 --diagnostics.every=40 --output.thermo_every=40";
}();
constexpr std::size_t kThermoRows = 11;

// Runs `COMMAND` (where RONDEL stands for the executable) in `dir` with a clean MPI environment (this test
// may itself run under mpirun; the run-as-root permissions stay), stdout and stderr into files.
Outcome run(const TempDir& dir, std::string command) {
  std::string env = test::without_mpi_launch(true);
  const std::string exe = test::quoted(test::rondel_executable());
  for (std::size_t at; (at = command.find("RONDEL")) != std::string::npos;) command.replace(at, 6, exe);
  // As root (a container), Open MPI's mpirun refuses to start without its two permissions.
  if (geteuid() == 0) env += " OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1";
  return test::run_in(dir, env, "sh -c \"" + command + "\"");
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// The commit the executable reports (rondel --version). The files it writes must name the same one; this
// test binary's own kRondelCommit differs when one of the two was rebuilt after a commit.
std::string executable_commit() {
  TempDir dir;
  const std::string out = run(dir, "RONDEL --version").out;
  const std::size_t at = out.find("(commit "), end = out.find(')', at);
  return at == std::string::npos || end == std::string::npos ? "?" : out.substr(at + 8, end - at - 8);
}

// The terminal of the default scene: the header names the discs, the time step and its limit, the output;
// then the thermo rows and the summary; never the resolved configuration.
void expect_short_terminal(const std::string& out, const fs::path& run_dir) {
  const auto lines = lines_of(out);
  EXPECT_LT(lines.size(), 30u) << out;
  EXPECT_TRUE(
      names(out, std::string("Rondel ") + kRondelVersion + " (commit " + executable_commit() + "): 5000 discs"));
  EXPECT_TRUE(names(out, "x critical"));
  EXPECT_TRUE(names(out, "limited by the normal mode"));
  EXPECT_TRUE(names(out, "output in " + run_dir.string()));
  EXPECT_TRUE(names(out, "summary: 400 steps of 5000 discs"));
  EXPECT_FALSE(names(out, "resolved configuration:")) << "the configuration belongs to config.ini and log.txt";
  EXPECT_FALSE(names(out, "k_n = "));
  EXPECT_EQ(count(out, "residual    steps/s"), 1u) << "one thermo header";
  std::size_t rows = 0;
  for (std::string l : lines) {
    // A thermo row: six numbers (on a terminal it may follow the erased progress line, "\r\033[K").
    if (const auto erased = l.rfind("\033[K"); erased != std::string::npos) l = l.substr(erased + 3);
    long long step = 0, contacts = 0;
    double time = 0, ke = 0, residual = 0, rate = 0;
    if (std::sscanf(l.c_str(), "%lld %lf %lf %lld %lf %lf", &step, &time, &ke, &contacts, &residual, &rate) == 6)
      ++rows;
  }
  EXPECT_EQ(rows, kThermoRows) << out;
}

TEST(Terminal, DefaultSceneInAPipeIsShortWithoutCarriageReturns) {
  ASSERT_TRUE(fs::exists(rondel_executable())) << rondel_executable();
  TempDir dir;
  const fs::path out = dir / "run";
  const Outcome o = run(dir, "RONDEL " + kDefaultScene + " --run.output=" + out.string() + " | cat");
  ASSERT_EQ(o.exit_code, 0) << o.err << o.out;
  EXPECT_EQ(o.out.find('\r'), std::string::npos) << "a carriage return in a pipe";
  expect_short_terminal(o.out, out);
  EXPECT_TRUE(names(o.out, "step 400/400 (100%)")) << "the progress line's last plain line";
  // log.txt holds all of it and the resolved configuration.
  const std::string log = read_file(out / "log.txt");
  EXPECT_TRUE(names(log, "(commit " + executable_commit() + ")"));
  EXPECT_TRUE(names(log, "resolved configuration:"));
  EXPECT_TRUE(names(log, "k_n = "));
  EXPECT_EQ(count(log, "residual    steps/s"), 1u);
  EXPECT_TRUE(o.err.empty()) << o.err;
}

TEST(Terminal, UnderMpirunInAPipeNoCarriageReturn) {
  // Open MPI gives each rank a pseudo-terminal even when mpirun writes to a pipe: the line must not redraw.
  if (!test::have_program("mpirun")) GTEST_SKIP() << "mpirun is not installed";
  TempDir dir;
  const fs::path out = dir / "run";
  const Outcome o = run(dir, "(mpirun -n 2 --oversubscribe RONDEL " + kDefaultScene + " --run.output=" + out.string() +
                                 "; echo \\$? > mpirun_rc.txt) | cat");
  ASSERT_EQ(o.exit_code, 0) << o.err << o.out;
  // The pipe hides mpirun's exit code: it is in a file.
  ASSERT_EQ(read_file(dir / "mpirun_rc.txt"), "0\n") << "mpirun failed; stderr: " << o.err << "\nstdout: " << o.out;
  EXPECT_EQ(o.out.find('\r'), std::string::npos) << "a carriage return under mpirun in a pipe";
  EXPECT_TRUE(names(o.out, "2 rank(s)"));
  EXPECT_TRUE(names(o.out, "step 400/400 (100%)"));
  EXPECT_LT(lines_of(o.out).size(), 30u) << o.out;
}

TEST(Terminal, DefaultSceneInAPseudoTerminalIsShort) {
  if (!test::have_program("script"))
    GTEST_SKIP() << "script (util-linux) is not installed: no pseudo-terminal to test in";
  TempDir dir;
  const fs::path out = dir / "run";
  const Outcome o =
      run(dir, "script -qec \\\"RONDEL " + kDefaultScene + " --run.output=" + out.string() + "\\\" /dev/null");
  ASSERT_EQ(o.exit_code, 0) << o.err << o.out;
  expect_short_terminal(o.out, out);
  // On a terminal the progress line is redrawn in place (a carriage return, then the erase to the end).
  EXPECT_TRUE(names(o.out, "\rstep 400/400 (100%)")) << o.out;
}

TEST(Terminal, ThermoEveryZeroPrintsNoThermoLines) {
  TempDir dir;
  const fs::path out = dir / "run";
  const Outcome o = run(dir, "RONDEL '" + (kSource / "inputs/deposition.ini").string() +
                                 "' --output.thermo_every=0 --run.steps=40 --run.output=" + out.string() + " | cat");
  ASSERT_EQ(o.exit_code, 0) << o.err << o.out;
  EXPECT_FALSE(names(o.out, "steps/s\n")) << o.out;
  EXPECT_TRUE(names(o.out, "summary: 40 steps"));
}

TEST(Terminal, VersionPrintsVersionAndCommit) {
  TempDir dir;
  const Outcome o = run(dir, "RONDEL --version");
  EXPECT_EQ(o.exit_code, 0);
  EXPECT_EQ(o.out, std::string("rondel ") + kRondelVersion + " (commit " + executable_commit() + ")\n");
  // 12 hex digits, "-dirty" when the tree had changes; "unknown" outside a git checkout.
  const std::string commit = executable_commit();
  const std::string hex = commit.substr(0, commit.find('-'));
  EXPECT_TRUE(commit == "unknown" ||
              (hex.size() == 12 && hex.find_first_not_of("0123456789abcdef") == std::string::npos &&
               (commit.size() == 12 || commit.substr(12) == "-dirty")))
      << commit;
  EXPECT_NE(std::string(kRondelVersion), "");
}

// A short default-scene run in `dir`/run with extra options; fails the test unless it completes.
fs::path short_run(const TempDir& dir, const std::string& name, const std::string& options) {
  const fs::path out = dir / name;
  const Outcome o =
      run(dir, "RONDEL '" + (kSource / "inputs/deposition.ini").string() +
                   "' --run.steps=30 --diagnostics.every=10 --run.output=" + out.string() + " " + options);
  EXPECT_EQ(o.exit_code, 0) << o.err << o.out;
  return out;
}

TEST(Terminal, SummaryJsonParsesAndHoldsTheRun) {
  if (!test::have_program("python3")) GTEST_SKIP() << "python3 is not installed";
  TempDir dir;
  const fs::path out = short_run(dir, "run", "");
  const std::string check =
      "python3 -c 'import json, sys; s = json.load(open(sys.argv[1])); "
      "keys = [\\\"status\\\", \\\"steps\\\", \\\"discs\\\", \\\"ranks\\\", \\\"wall_seconds\\\", "
      "\\\"disc_steps_per_second\\\", \\\"dt\\\", \\\"critical_dt\\\", \\\"critical_mode\\\", \\\"critical_pair\\\", "
      "\\\"ledger_residual\\\", \\\"phase_seconds_rank0\\\", \\\"rondel_version\\\", \\\"rondel_commit\\\", "
      "\\\"output_files\\\"]; missing = [k for k in keys if k not in s]; assert not missing, missing; "
      "print(s[\\\"status\\\"], s[\\\"steps\\\"], s[\\\"discs\\\"], s[\\\"ranks\\\"], s[\\\"critical_mode\\\"], "
      "s[\\\"rondel_commit\\\"], s[\\\"dt\\\"] < s[\\\"critical_dt\\\"], len(s[\\\"phase_seconds_rank0\\\"]), "
      "\\\" \\\".join(s[\\\"output_files\\\"]))' " +
      (out / "summary.json").string();
  const Outcome o = run(dir, check);
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_EQ(o.out, "complete 30 5000 1 normal " + executable_commit() +
                       " True 6 checkpoint_0000000030.h5 config.ini diagnostics.csv final.csv log.txt measures.csv "
                       "summary.json summary.txt\n");
}

TEST(Terminal, EveryHdf5FileCarriesVersionAndCommit) {
  TempDir dir;
  const fs::path out = short_run(dir, "run", "--output.snapshot_every=10");
  const Communicator self(MPI_COMM_SELF);
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(out))
    if (e.path().extension() == ".h5") files.push_back(e.path());
  ASSERT_GE(files.size(), 2u) << "snapshots and a checkpoint";
  const std::string commit = executable_commit();
  for (const fs::path& p : files) {
    SCOPED_TRACE(p.string());
    Hdf5File f(p.string(), Hdf5File::Mode::read, self);
    EXPECT_EQ(f.read_string_attribute("/run_metadata", "rondel_version"), kRondelVersion);
    EXPECT_EQ(f.read_string_attribute("/run_metadata", "rondel_commit"), commit);
  }
}

TEST(Terminal, ResumeWithNothingToDoSaysSoAndBelowTheCheckpointNamesRunSteps) {
  TempDir dir;
  const fs::path out = short_run(dir, "run", "");
  const std::string final_before = read_file(out / "final.csv");
  const Outcome same = run(dir, "RONDEL --resume " + out.string());
  EXPECT_EQ(same.exit_code, 0) << same.err;
  EXPECT_TRUE(names(same.out, "nothing to do")) << same.out;
  EXPECT_TRUE(names(same.out, "checkpoint_0000000030.h5"));
  EXPECT_TRUE(names(same.out, "run.steps"));
  EXPECT_EQ(read_file(out / "final.csv"), final_before) << "a resume with nothing to do leaves the results";

  const Outcome below = run(dir, "RONDEL --resume " + out.string() + " --run.steps=20");
  EXPECT_EQ(below.exit_code, 1);
  EXPECT_TRUE(names(below.err, "run.steps = 20")) << below.err;
  EXPECT_TRUE(names(below.err, "step 30")) << below.err;
  EXPECT_EQ(read_file(out / "final.csv"), final_before);

  const Outcome more = run(dir, "RONDEL --resume " + out.string() + " --run.steps=40");
  EXPECT_EQ(more.exit_code, 0) << more.err;
  EXPECT_TRUE(names(more.out, "resumed at step 30"));
  EXPECT_TRUE(names(more.out, "summary: 10 steps"));
}

std::vector<std::vector<std::string>> rows_of(const std::string& csv) {
  std::vector<std::vector<std::string>> rows;
  for (const auto& line : lines_of(csv)) {
    std::vector<std::string> cells;
    std::size_t from = 0;
    for (std::size_t comma; (comma = line.find(',', from)) != std::string::npos; from = comma + 1)
      cells.push_back(line.substr(from, comma - from));
    cells.push_back(line.substr(from));
    rows.push_back(cells);
  }
  return rows;
}

TEST(Terminal, FinalCsvHasTheRadiusLastAndItsDecimalFormReadsBackTheSameBits) {
  TempDir dir;
  const auto hex = rows_of(read_file(short_run(dir, "hex", "") / "final.csv"));
  const auto dec = rows_of(read_file(short_run(dir, "dec", "--output.final_format=decimal") / "final.csv"));
  ASSERT_EQ(hex.size(), 5001u);
  ASSERT_EQ(dec.size(), hex.size());
  const std::vector<std::string> header{"gid", "x", "y", "vx", "vy", "theta", "omega", "radius"};
  EXPECT_EQ(hex[0], header);
  EXPECT_EQ(dec[0], header);
  bool decimal_seen = false;
  for (std::size_t r = 1; r < hex.size(); ++r) {
    ASSERT_EQ(hex[r].size(), 8u) << "row " << r;
    ASSERT_EQ(dec[r].size(), 8u) << "row " << r;
    EXPECT_EQ(hex[r][0], dec[r][0]);
    for (std::size_t c = 1; c < 8; ++c) {
      EXPECT_NE(hex[r][c].find("0x"), std::string::npos) << hex[r][c];
      EXPECT_EQ(dec[r][c].find("0x"), std::string::npos) << dec[r][c];
      decimal_seen = decimal_seen || dec[r][c].find('.') != std::string::npos;
      ASSERT_TRUE(test::same_bits(std::strtod(hex[r][c].c_str(), nullptr), std::strtod(dec[r][c].c_str(), nullptr)))
          << "row " << r << " column " << header[c];
    }
    const double radius = std::strtod(hex[r][7].c_str(), nullptr);
    EXPECT_GE(radius, 0.001) << "row " << r;  // the scene's radius_min and radius_max
    EXPECT_LE(radius, 0.002) << "row " << r;
  }
  EXPECT_TRUE(decimal_seen);
}

TEST(Terminal, BadOutputKeysNameTheKey) {
  const std::string ini = read_file(kSource / "inputs/deposition.ini");
  for (const auto& [arg, key] :
       std::vector<std::pair<std::string, std::string>>{{"--output.final_format=octal", "output.final_format"},
                                                        {"--output.thermo_every=-1", "output.thermo_every"}}) {
    SCOPED_TRACE(arg);
    try {
      parse_config_text(ini, {arg});
      ADD_FAILURE() << "accepted";
    } catch (const ConfigError& e) {
      EXPECT_TRUE(names(e.what(), key));
    }
  }
}

}  // namespace
}  // namespace rondel
