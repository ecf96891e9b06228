// Refusals at set-up (docs/design.md sections 8 and 10): a bad scene, time step or output directory throws a
// ConfigError or InputError that names the key, value or file, before any file is written. The real
// executable reports it once on stderr and exits non-zero; a tiny valid run writes every output file.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

#include "app/Simulation.hpp"
#include "core/Config.hpp"
#include "core/Errors.hpp"
#include "parallel/Communicator.hpp"
#include "support/Assertions.hpp"
#include "support/Command.hpp"
#include "support/TempDir.hpp"

namespace rondel {
namespace {

namespace fs = std::filesystem;

using test::Outcome;
using test::quoted;
using test::read_file;
using test::rondel_executable;
using test::TempDir;
using test::write_file;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) out.push_back(line);
  return out;
}

// Six discs of R = 5 mm on a square lattice touching each other, above a bottom wall.
const std::string kLattice = R"(
[run]
steps = 20
[diagnostics]
every = 5
[domain]
xlo = 0
xhi = 0.1
ylo = 0
yhi = 0.1
[gravity]
y = -9.81
[linear]
k_n = 1e5
e = 0.5
[coulomb]
k_s = 7.5e4
mu = 0.5
[walls]
box = bottom left right
[scene]
type = lattice_square
nx = 3
ny = 2
radius = 0.005
x0 = 0.02
y0 = 0.02
)";

// A CSV scene in a 1 m x 0.3 m box without walls; the file comes from the test.
std::string csv_scene(const fs::path& file) {
  return R"(
[domain]
xlo = 0
xhi = 1
ylo = 0
yhi = 0.3
[linear]
k_n = 1e5
e = 0.5
[coulomb]
k_s = 7.5e4
mu = 0.5
[scene]
type = csv
file = )" +
         file.string() + "\n";
}

template <class Error>
std::string error_name() {
  return std::is_same_v<Error, ConfigError> ? "ConfigError" : "InputError";
}

// Parses and sets up a simulation; returns the message of the expected error type, or "" after recording
// a failure when set-up succeeds or throws something else.
template <class Error>
std::string setup_error(const std::string& ini, const std::vector<std::string>& overrides = {},
                        bool write_files = false) {
  Communicator comm;
  try {
    Simulation sim(parse_config_text(ini, overrides), comm, write_files);
  } catch (const Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected " << error_name<Error>() << ", got " << typeid(e).name() << ": " << e.what();
    return "";
  }
  ADD_FAILURE() << "set-up succeeded; expected " << error_name<Error>();
  return "";
}

using test::names;

TEST(SetupErrors, NonPositiveLatticeRadius) {
  for (const char* radius : {"0", "-0.005"}) {
    SCOPED_TRACE(radius);
    const std::string m = setup_error<ConfigError>(kLattice, {std::string("--scene.radius=") + radius});
    EXPECT_TRUE(names(m, "scene.radius"));
  }
}

TEST(SetupErrors, NonPositiveRadiusInACsvSceneNamesTheFile) {
  TempDir dir;
  for (const char* radius : {"0", "-0.01"}) {
    SCOPED_TRACE(radius);
    const fs::path file = dir / "bad_radius.csv";
    write_file(file, std::string("id,x,y,radius\n0,0.1,0.1,0.01\n1,0.3,0.1,") + radius + "\n");
    const std::string m = setup_error<InputError>(csv_scene(file));
    EXPECT_TRUE(names(m, file.string()));
    EXPECT_TRUE(names(m, "radius"));
    EXPECT_TRUE(names(m, "line 3"));
  }
  const fs::path short_row = dir / "short_row.csv";
  write_file(short_row, "0,0.1,0.1,0.01\n1,0.3,0.1\n");
  const std::string m = setup_error<InputError>(csv_scene(short_row));
  EXPECT_TRUE(names(m, short_row.string()));
  EXPECT_TRUE(names(m, "line 2"));
  const fs::path missing = dir / "no_such_file.csv";
  EXPECT_TRUE(names(setup_error<InputError>(csv_scene(missing)), missing.string()));
}

TEST(SetupErrors, TimeStepAboveCriticalIsRefusedUnlessForced) {
  Communicator comm;
  const Simulation automatic(parse_config_text(kLattice), comm, false);
  const CriticalStep critical = automatic.critical();
  ASSERT_GT(critical.dt, 0.0);
  ASSERT_FALSE(critical.mode.empty());
  EXPECT_DOUBLE_EQ(automatic.dt(), 0.2 * critical.dt) << "run.dt = 0 means run.safety x critical";

  std::ostringstream too_big;
  too_big.precision(17);
  too_big << "--run.dt=" << 2.0 * critical.dt;
  const std::string m = setup_error<ConfigError>(kLattice, {too_big.str()});
  EXPECT_TRUE(names(m, "run.dt"));
  EXPECT_TRUE(names(m, critical.mode + " mode")) << "the limiting mode";
  EXPECT_TRUE(names(m, "run.force_dt")) << "the way out";

  const Simulation forced(parse_config_text(kLattice, {too_big.str(), "--run.force_dt=true"}), comm, false);
  EXPECT_EQ(forced.dt(), 2.0 * critical.dt);

  std::ostringstream below;
  below.precision(17);
  below << "--run.dt=" << 0.9 * critical.dt;
  const Simulation accepted(parse_config_text(kLattice, {below.str()}), comm, false);
  EXPECT_EQ(accepted.dt(), 0.9 * critical.dt);
}

// R = 0.01 throughout: pairs (1,2) overlap 0.2 R, (4,5) 0.4 R (the worst), (7,8) 0.05 R; (9,10) overlaps
// 0.005 R, below the default limit 0.01.
const char* kOverlapping =
    "# three overlaps above 0.01 R\n"
    "id,x,y,radius\n"
    "1,0.1,0.1,0.01\n2,0.118,0.1,0.01\n"
    "4,0.3,0.1,0.01\n5,0.316,0.1,0.01\n"
    "7,0.5,0.1,0.01\n8,0.5,0.1195,0.01\n"
    "9,0.7,0.1,0.01\n10,0.71995,0.1,0.01\n";

TEST(SetupErrors, InitialOverlapsAboveTheLimitAreCountedAndTheWorstNamed) {
  TempDir dir;
  const fs::path file = dir / "overlapping.csv";
  write_file(file, kOverlapping);
  const std::string m = setup_error<InputError>(csv_scene(file));
  EXPECT_TRUE(names(m, "scene.max_initial_overlap"));
  EXPECT_EQ(m.rfind("3 initial overlaps", 0), 0u) << "the count comes first: '" << m << "'";
  EXPECT_TRUE(names(m, "0.4")) << "the worst ratio";
  EXPECT_TRUE(names(m, "discs 4 and 5")) << "the worst pair";

  const std::string one = setup_error<InputError>(csv_scene(file), {"--scene.max_initial_overlap=0.3"});
  EXPECT_EQ(one.rfind("1 initial overlap", 0), 0u) << one;
  EXPECT_TRUE(names(one, "discs 4 and 5"));

  Communicator comm;
  EXPECT_NO_THROW(Simulation(parse_config_text(csv_scene(file), {"--scene.max_initial_overlap=0.45"}), comm, false));
}

TEST(SetupErrors, InitialOverlapWithAWallIsCounted) {
  // The lattice's first row sits 1 mm below contact with the bottom wall: overlap 0.2 R.
  const std::string m = setup_error<InputError>(kLattice, {"--scene.y0=0.004"});
  EXPECT_EQ(m.rfind("3 initial overlaps", 0), 0u) << m;
  EXPECT_TRUE(names(m, "scene.max_initial_overlap"));
  EXPECT_TRUE(names(m, "wall 0"));
}

TEST(SetupErrors, DiscOutsideTheDomainIsRefused) {
  TempDir dir;
  const fs::path file = dir / "outside.csv";
  write_file(file, "id,x,y,radius\n1,0.1,0.1,0.01\n3,1.5,0.1,0.01\n");
  const std::string m = setup_error<InputError>(csv_scene(file));
  EXPECT_TRUE(names(m, "disc 3"));
  EXPECT_TRUE(names(m, "1.5"));
  EXPECT_TRUE(names(m, "outside the domain"));
  // A lattice running past the box (30 discs of 1 cm spacing from x = 0.02 in a 0.1 m box).
  const std::string lattice = setup_error<InputError>(kLattice, {"--scene.nx=30"});
  EXPECT_TRUE(names(lattice, "outside the domain"));
  // A disc behind a line wall (the line y = 0.2 faces down).
  write_file(dir / "inside.csv", "1,0.1,0.1,0.01\n2,0.5,0.25,0.01\n");
  const std::string behind = setup_error<InputError>(csv_scene(dir / "inside.csv") + "[walls]\nlines = 0 0.2 0 -1\n");
  EXPECT_TRUE(names(behind, "disc 2"));
  EXPECT_TRUE(names(behind, "wall 0"));
  // A disc outside a circle wall (a drum of radius 0.3 about (0.1, 0.1) holds disc 1, not disc 2).
  const std::string outside =
      setup_error<InputError>(csv_scene(dir / "inside.csv") + "[walls]\ncircles = 0.1 0.1 0.3 2\n");
  EXPECT_TRUE(names(outside, "disc 2"));
  EXPECT_TRUE(names(outside, "wall 0"));
  EXPECT_TRUE(names(outside, "outside the circle"));
}

TEST(SetupErrors, PeriodicLengthBelowTwiceTheInteractionRange) {
  // R = 5 mm, default skin R/4: range 11.25 mm, so a periodic length must be at least 22.5 mm.
  const std::vector<std::string> narrow_x = {"--domain.periodic_x=true", "--walls.box=bottom", "--domain.xhi=0.02",
                                             "--scene.nx=1", "--scene.x0=0.01"};
  const std::string m = setup_error<ConfigError>(kLattice, narrow_x);
  EXPECT_TRUE(names(m, "domain.xhi - domain.xlo"));
  EXPECT_TRUE(names(m, "interaction range"));
  const std::vector<std::string> narrow_y = {"--domain.periodic_y=true", "--walls.box=left right", "--domain.yhi=0.021",
                                             "--scene.ny=1", "--scene.y0=0.01"};
  EXPECT_TRUE(names(setup_error<ConfigError>(kLattice, narrow_y), "domain.yhi - domain.ylo"));
  // A little wider is accepted.
  Communicator comm;
  std::vector<std::string> wide_x = narrow_x;
  wide_x[2] = "--domain.xhi=0.023";
  EXPECT_NO_THROW(Simulation(parse_config_text(kLattice, wide_x), comm, false));
  // The skin counts: a skin of 5 mm makes range 15 mm, so 0.023 m is refused.
  wide_x.push_back("--neighbour.skin=0.005");
  EXPECT_TRUE(names(setup_error<ConfigError>(kLattice, wide_x), "domain.xhi - domain.xlo"));
}

TEST(SetupErrors, EmptyCsvSceneIsRefusedNamingTheFile) {
  TempDir dir;
  const fs::path file = dir / "empty.csv";
  write_file(file, "# no discs here\nid,x,y,radius\n\n");
  const std::string m = setup_error<InputError>(csv_scene(file));
  EXPECT_TRUE(names(m, "no discs"));
  // docs/design.md section 10: an input error names the key or file; for a CSV scene that is the file.
  EXPECT_TRUE(names(m, file.string()));
}

TEST(SetupErrors, ExistingNonEmptyOutputDirectoryIsRefusedAndLeftUntouched) {
  TempDir dir;
  const fs::path out = dir / "previous-run";
  fs::create_directories(out);
  write_file(out / "final.csv", "precious results\n");
  write_file(out / "notes.txt", "keep me\n");
  const std::vector<std::string> to_out = {"--run.output=" + out.string()};
  const std::string m = setup_error<ConfigError>(kLattice, to_out, true);
  EXPECT_TRUE(names(m, "run.output"));
  EXPECT_TRUE(names(m, out.string()));
  EXPECT_TRUE(names(m, "run.overwrite"));
  EXPECT_EQ(read_file(out / "final.csv"), "precious results\n");
  EXPECT_EQ(read_file(out / "notes.txt"), "keep me\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(out), fs::directory_iterator()), 2) << "nothing was added";

  Communicator comm;
  {
    std::vector<std::string> overwrite = to_out;
    overwrite.push_back("--run.overwrite=true");
    Simulation sim(parse_config_text(kLattice, overwrite), comm, true);
    EXPECT_TRUE(fs::exists(out / "config.ini"));
  }
  // An existing but empty directory is fine.
  const fs::path empty = dir / "empty-dir";
  fs::create_directories(empty);
  EXPECT_NO_THROW(Simulation(parse_config_text(kLattice, {"--run.output=" + empty.string()}), comm, true));
  EXPECT_TRUE(fs::exists(empty / "config.ini"));
}

TEST(SetupErrors, NoOutputDirectoryIsCreatedWhenSetUpFails) {
  TempDir dir;
  const fs::path overlapping = dir / "overlapping.csv", empty = dir / "empty.csv";
  write_file(overlapping, kOverlapping);
  write_file(empty, "id,x,y,radius\n");
  struct Case {
    const char* what;
    std::string ini;
    std::vector<std::string> overrides;
    bool config_error;
  };
  const std::vector<Case> cases = {
      {"time step", kLattice, {"--run.dt=1"}, true},
      {"periodic length",
       kLattice,
       {"--domain.periodic_x=true", "--walls.box=bottom", "--domain.xhi=0.02", "--scene.nx=1", "--scene.x0=0.01"},
       true},
      {"overlap", csv_scene(overlapping), {}, false},
      {"outside", kLattice, {"--scene.nx=30"}, false},
      {"empty scene", csv_scene(empty), {}, false},
  };
  int k = 0;
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    const fs::path out = dir / ("out-" + std::to_string(k++));
    std::vector<std::string> overrides = c.overrides;
    overrides.push_back("--run.output=" + out.string());
    const std::string m = c.config_error ? setup_error<ConfigError>(c.ini, overrides, true)
                                         : setup_error<InputError>(c.ini, overrides, true);
    EXPECT_FALSE(m.empty());
    EXPECT_FALSE(fs::exists(out)) << out << " was created by a failed set-up";
  }
}

// ---- the real executable ----

// Runs `rondel ARGS` from `dir` with a clean MPI environment (a singleton, even when this test runs under
// mpirun), capturing stdout and stderr.
Outcome run_rondel(const TempDir& dir, const std::string& args) {
  return test::run_in(dir, test::without_mpi_launch(false), quoted(rondel_executable()) + " " + args);
}

TEST(Executable, BadConfigurationExitsNonZeroNamingTheKey) {
  ASSERT_TRUE(fs::exists(rondel_executable())) << rondel_executable();
  TempDir dir;
  const fs::path out = dir / "out";
  write_file(dir / "bad.ini", kLattice + "[run]\nbogus = 1\n");
  const Outcome unknown = run_rondel(dir, "bad.ini --run.output=" + quoted(out));
  EXPECT_EQ(unknown.exit_code, 1) << unknown.err;
  EXPECT_TRUE(names(unknown.err, "run.bogus"));
  EXPECT_FALSE(fs::exists(out));

  // Parsed fine, refused at set-up (after the output directory's name is known).
  write_file(dir / "good.ini", kLattice + "[run]\noutput = " + out.string() + "\n");
  const Outcome dt = run_rondel(dir, "good.ini --run.dt=1");
  EXPECT_EQ(dt.exit_code, 1) << dt.err;
  EXPECT_TRUE(names(dt.err, "run.dt"));
  EXPECT_EQ(lines_of(dt.err).size(), 1u) << "reported once: " << dt.err;
  EXPECT_EQ(dt.err.rfind("rondel: configuration error: ", 0), 0u) << dt.err;
  EXPECT_FALSE(fs::exists(out)) << "a failed set-up left " << out;
}

TEST(Executable, TinyValidRunWritesEveryOutputFile) {
  ASSERT_TRUE(fs::exists(rondel_executable())) << rondel_executable();
  TempDir dir;
  const fs::path out = dir / "run";
  write_file(dir / "tiny.ini", kLattice + "[run]\noutput = " + out.string() + "\n");
  const Outcome o = run_rondel(dir, "tiny.ini");
  ASSERT_EQ(o.exit_code, 0) << "stderr: " << o.err << "\nstdout: " << o.out;
  for (const char* name : {"config.ini", "log.txt", "diagnostics.csv", "final.csv", "summary.txt"})
    EXPECT_TRUE(fs::is_regular_file(out / name)) << name << " is missing";

  const std::string config = read_file(out / "config.ini");
  EXPECT_TRUE(names(config, "[linear]"));
  EXPECT_TRUE(names(config, "steps = 20"));
  EXPECT_FALSE(read_file(out / "log.txt").empty());

  const auto diag = lines_of(read_file(out / "diagnostics.csv"));
  ASSERT_GE(diag.size(), 2u) << "a header and at least one row";
  EXPECT_EQ(diag[0].rfind("step,time,", 0), 0u) << diag[0];
  EXPECT_EQ(diag.size(), 1u + 5u) << "rows at steps 0, 5, 10, 15, 20";
  EXPECT_EQ(diag.back().rfind("20,", 0), 0u) << diag.back();

  const auto final_rows = lines_of(read_file(out / "final.csv"));
  ASSERT_EQ(final_rows.size(), 1u + 6u) << "a header and the six discs";
  EXPECT_EQ(final_rows[0], "gid,x,y,vx,vy,theta,omega,radius");
  EXPECT_TRUE(names(read_file(out / "summary.txt"), "status: complete"));
  EXPECT_TRUE(o.err.empty()) << o.err;
}

}  // namespace
}  // namespace rondel
