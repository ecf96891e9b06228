// Inputs that lie, through the real executable on 1 and 2 ranks: a CSV scene is read by its header's names
// (columns in any order, final.csv as a scene; unknown, repeated or missing names, a trailing comma and a number
// with a space refused naming the file and line; CR-only line ends and a byte order mark read), a repeated id
// names both lines; a device, a FIFO or a directory given as the INI, a CSV scene or an HDF5 scene is refused
// before anything is read (never read forever, never blocking), an INI above its size bound too; and in a run
// directory a symbolic-link loop, a FIFO or a directory named like a newer checkpoint is passed over by
// --resume, named, and never pruned in place of the run's own checkpoints.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <sstream>
#include <string>

#include "support/Command.hpp"
#include "support/Scenes.hpp"
#include "support/TempDir.hpp"

namespace rondel {
namespace {

namespace fs = std::filesystem;
using test::mpirun_rondel;
using test::occurrences;
using test::Outcome;
using test::quoted;
using test::read_file;
using test::TempDir;
using test::write_file;

// Two discs in a 10 cm box, no gravity, from scene.file = `csv` (written into `dir`), 5 steps.
Outcome run_csv(const TempDir& dir, const std::string& csv, const std::string& out, int ranks = 1,
                const std::string& extra = "") {
  write_file(dir / "scene.ini", R"(
[run]
dt = 2e-7
steps = 5
progress = false
[domain]
xlo = 0
xhi = 0.1
ylo = 0
yhi = 0.1
[linear]
k_n = 2e8
e = 0.5
[coulomb]
k_s = 1.5e8
mu = 0.5
[scene]
type = csv
)");
  write_file(dir / (out + ".csv"), csv);
  return mpirun_rondel(dir, ranks, "scene.ini --scene.file=" + out + ".csv --run.output=" + out + extra);
}

// The refusal of a CSV scene on each of `rank_counts`: exit 1, the message once, naming `what`, and no output
// directory.
void expect_csv_refused(const TempDir& dir, const std::string& csv, const std::string& name, const std::string& what,
                        std::initializer_list<int> rank_counts = {1}) {
  for (int ranks : rank_counts) {
    const Outcome o = run_csv(dir, csv, name, ranks);
    EXPECT_EQ(o.exit_code, 1) << name << ", " << ranks << " ranks: " << o.err;
    EXPECT_EQ(occurrences(o.err, "scene.file '" + name + ".csv' " + what), 1u) << ranks << " ranks: " << o.err;
    EXPECT_EQ(occurrences(o.err, "rondel: "), 1u) << o.err;
    EXPECT_FALSE(fs::exists(dir / name)) << name;
  }
}

constexpr const char* kRows = "0,0.02,0.03,0.005,1,0,0\n1,0.06,0.07,0.004,0,-1,2\n";

TEST(LyingInputs, CsvColumnsAreReadByTheirHeaderNames) {
  const TempDir dir("rondel-csvhead");
  ASSERT_EQ(run_csv(dir, std::string("id,x,y,radius,vx,vy,omega\n") + kRows, "plain").exit_code, 0);
  // The same discs with the columns in another order, and a header-less file by position.
  const Outcome swapped =
      run_csv(dir, "omega,y,radius,id,vy,x,vx\n0,0.03,0.005,0,0,0.02,1\n2,0.07,0.004,1,-1,0.06,0\n", "swapped");
  ASSERT_EQ(swapped.exit_code, 0) << swapped.err;
  EXPECT_EQ(read_file(dir / "swapped" / "final.csv"), read_file(dir / "plain" / "final.csv"));
  ASSERT_EQ(run_csv(dir, kRows, "bare").exit_code, 0);
  EXPECT_EQ(read_file(dir / "bare" / "final.csv"), read_file(dir / "plain" / "final.csv"));
  // CR-only and CR LF line ends, a byte order mark, spaces around the fields: the same discs.
  const Outcome cr =
      run_csv(dir, "id,x,y,radius,vx,vy,omega\r0,0.02,0.03,0.005,1,0,0\r1,0.06,0.07,0.004,0,-1,2\r", "cr");
  ASSERT_EQ(cr.exit_code, 0) << cr.err;
  EXPECT_EQ(read_file(dir / "cr" / "final.csv"), read_file(dir / "plain" / "final.csv"));
  const Outcome bom = run_csv(
      dir,
      "\xEF\xBB\xBFid, x, y, radius, vx, vy, omega\r\n0, 0.02, 0.03, 0.005, 1, 0, 0\r\n1,0.06,0.07,0.004,0,-1,2\r\n",
      "bom");
  ASSERT_EQ(bom.exit_code, 0) << bom.err;
  EXPECT_EQ(read_file(dir / "bom" / "final.csv"), read_file(dir / "plain" / "final.csv"));
  // A final.csv (gid, theta, hexadecimal floats) is a scene: after 0 steps its discs come back bit for bit
  // (theta, the accumulated angle, starts again at 0).
  const Outcome again = run_csv(dir, read_file(dir / "plain" / "final.csv"), "again", 2, " --run.steps=0");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  const auto without_theta = [](const std::string& csv) {
    std::string out, line;
    std::istringstream in(csv);
    while (std::getline(in, line)) {  // gid,x,y,vx,vy,theta,omega,radius: the sixth field goes
      std::size_t at = 0;
      for (int k = 0; k < 5; ++k) at = line.find(',', at) + 1;
      out += line.substr(0, at) + line.substr(line.find(',', at) + 1) + "\n";
    }
    return out;
  };
  EXPECT_EQ(without_theta(read_file(dir / "again" / "final.csv")),
            without_theta(read_file(dir / "plain" / "final.csv")));
}

TEST(LyingInputs, CsvHeadersThatDoNotNameTheColumnsAreRefused) {
  const TempDir dir("rondel-csvbad");
  expect_csv_refused(dir, std::string("a,b,c,d,e,f,g\n") + kRows, "unknown",
                     "line 1: the header names a column 'a', which a CSV scene does not have (allowed: id (or gid), x, "
                     "y, radius, vx, vy, omega, material, theta)",
                     {1, 2});
  expect_csv_refused(dir, std::string("id,x,x,radius,vx,vy,omega\n") + kRows, "twice",
                     "line 1: the header names the column 'x' twice");
  expect_csv_refused(dir, "id,x,radius\n0,0.02,0.005\n", "missing", "line 1: the header has no column 'y'");
  expect_csv_refused(dir, "id,x,y,radius,\n0,0.02,0.03,0.005,\n", "trailing",
                     "line 1: column 5 of the header has no name (a trailing comma?)");
  expect_csv_refused(dir, "id,x,y,radius\n0,0.02,0.03,0.005,\n", "trailing_row",
                     "line 2: 5 fields, but the file has 4");
  expect_csv_refused(dir, "id,x,y,radius\n0,0.0 05,0.03,0.005\n", "space", "line 2: x = '0.0 05' is not a number");
  expect_csv_refused(dir, "id,x,y,radius\n# a comment\n4,0.02,0.03,0.005\n1,0.06,0.07,0.004\n4,0.02,0.08,0.005\n",
                     "repeated", "lines 3 and 5: disc id 4 appears twice", {1, 2});
}

// `rondel ARGS` on 1 and 2 ranks, under a time limit: exit 1, `message` once on stderr.
void expect_refused(const TempDir& dir, const std::string& args, const std::string& message) {
  for (int ranks : {1, 2}) {
    const Outcome o = mpirun_rondel(dir, ranks, args, "", 60);
    EXPECT_EQ(o.exit_code, 1) << args << ", " << ranks << " ranks: " << o.err;
    EXPECT_EQ(occurrences(o.err, message), 1u) << args << ", " << ranks << " ranks: " << o.err;
  }
}

TEST(LyingInputs, DevicesFifosAndDirectoriesAreNotRead) {
  const TempDir dir("rondel-devices");
  ASSERT_EQ(mkfifo((dir / "pipe").c_str(), 0600), 0);
  write_file(dir / "box.ini", test::moving_wall_box_ini("wang"));
  expect_refused(dir, "/dev/zero", "the configuration file '/dev/zero' is a character device, not a regular file");
  expect_refused(dir, "pipe", "the configuration file 'pipe' is a FIFO (named pipe), not a regular file");
  expect_refused(dir, "box.ini --scene.type=csv --scene.file=/dev/urandom --run.output=o",
                 "scene.file '/dev/urandom' is a character device, not a regular file");
  expect_refused(dir, "box.ini --scene.type=csv --scene.file=pipe --run.output=o",
                 "scene.file 'pipe' is a FIFO (named pipe), not a regular file");
  expect_refused(dir, "box.ini --scene.type=file --scene.file=pipe --run.output=o",
                 "the HDF5 file 'pipe' is a FIFO (named pipe), not a regular file");
  // An INI larger than 16 MiB is no configuration.
  write_file(dir / "huge.ini", test::moving_wall_box_ini("wang") + std::string(17 << 20, '#'));
  expect_refused(dir, "huge.ini", "the configuration file 'huge.ini' has 17826");
  EXPECT_FALSE(fs::exists(dir / "o"));
}

TEST(LyingInputs, ThingsNamedLikeANewerCheckpointArePassedOverAndNeverPruned) {
  const TempDir dir("rondel-loop");
  write_file(dir / "box.ini", test::moving_wall_box_ini("wang"));
  ASSERT_EQ(mpirun_rondel(dir, 1, "box.ini --run.output=run --run.steps=20 --output.checkpoint_every=10").exit_code, 0);
  const fs::path run = dir / "run";
  fs::create_symlink("checkpoint_0000009000.h5", run / "checkpoint_0000009000.h5");  // a loop
  ASSERT_EQ(mkfifo((run / "checkpoint_0000009500.h5").c_str(), 0600), 0);
  fs::create_directory(run / "checkpoint_0000009900.h5");
  for (int ranks : {1, 2}) {
    const Outcome o = mpirun_rondel(
        dir, ranks, "--resume run --run.steps=" + std::to_string(30 + 10 * ranks) + " --output.checkpoint_keep=1", "",
        60);
    EXPECT_EQ(o.exit_code, 0) << ranks << " ranks: " << o.err;
    EXPECT_EQ(
        occurrences(o.err, "skipping run/checkpoint_0000009000.h5: a symbolic link, not a file that Rondel wrote"), 1u)
        << o.err;
    EXPECT_EQ(occurrences(o.err, "skipping run/checkpoint_0000009500.h5: a FIFO (named pipe)"), 1u) << o.err;
    EXPECT_EQ(occurrences(o.err, "skipping run/checkpoint_0000009900.h5: a directory"), 1u) << o.err;
    // The run's newest checkpoint is kept (output.checkpoint_keep = 1), the strangers are left as they were.
    EXPECT_TRUE(fs::exists(run / ("checkpoint_00000000" + std::to_string(30 + 10 * ranks) + ".h5")));
    EXPECT_TRUE(fs::is_symlink(run / "checkpoint_0000009000.h5"));
    EXPECT_TRUE(fs::is_fifo(run / "checkpoint_0000009500.h5"));
    EXPECT_TRUE(read_file(run / "summary.json").find("\"status\": \"complete\"") != std::string::npos);
  }
}

}  // namespace
}  // namespace rondel
