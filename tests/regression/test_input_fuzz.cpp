// Hostile input (issue 16, docs/design.md section 8): a seeded fuzz over every key of the registry
// (config_keys) and every number of the list keys, each mutation on top of a small valid scene. Every case
// either sets up and runs a few steps, or is refused with a ConfigError or InputError that names the key,
// before any file is written; never a crash, another exception (the internal-error exit 4, an instability
// after the start) or a run with a value outside the range the key declares. The real executable is run on
// a few of the cases for the exit code 1 and the output directory left unmade (InputFuzz.Executable*).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "app/Reports.hpp"
#include "app/Simulation.hpp"
#include "core/ConfigSchema.hpp"
#include "core/Errors.hpp"
#include "core/SceneBuilder.hpp"
#include "parallel/Communicator.hpp"
#include "physics/LawRegistry.hpp"
#include "support/Command.hpp"
#include "support/TempDir.hpp"

namespace rondel {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

// A: lattice, linear + coulomb + wang, box walls, a line and a segment.
const std::string kLattice = R"([run]
steps = 3
progress = false
[diagnostics]
every = 1
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
[contact]
rolling = wang
[wang]
k_r = 1e4
mu_r = 0.1
[walls]
box = bottom left right
box_region = 0 0.1 0 0.1
lines = 0 0.095 0 -1
segments = 0.06 0.05 0.09 0.05
[scene]
type = lattice_square
nx = 3
ny = 2
radius = 0.005
x0 = 0.02
y0 = 0.02
vx = 0.1
omega = 1
)";

// B: a random packing, hertz + mindlin + jiang_plastic, periodic in x, a servo-controlled top wall.
const std::string kRandom = R"([run]
steps = 3
progress = false
[diagnostics]
every = 1
[domain]
xlo = 0
xhi = 0.05
ylo = 0
yhi = 0.05
periodic_x = true
[gravity]
y = -9.81
[material]
density = 2500
youngs_modulus = 1e7
poisson_ratio = 0.3
[contact]
normal = hertz
tangential = mindlin
rolling = jiang_plastic
[hertz]
e = 0.5
[mindlin]
mu = 0.5
[jiang]
delta = 0.5
[walls]
box = bottom top
control = top:servo:1e3
[scene]
type = random
count = 12
region = 0 0.05 0.002 0.04
radius_min = 0.002
radius_max = 0.003
seed = 3
)";

// C: a CSV scene of two materials, copied twice along x, linear + coulomb + iwashita_oda, a pair block.
std::string csv_ini(const fs::path& csv) {
  return R"([run]
steps = 3
progress = false
[diagnostics]
every = 1
[domain]
xlo = 0
xhi = 0.2
ylo = 0
yhi = 0.1
periodic_x = true
[material.glass]
density = 2500
[material.steel]
density = 7800
[linear]
k_n = 1e5
zeta = 0.3
[linear.glass.steel]
k_n = 2e5
[coulomb]
k_s = 7.5e4
mu = 0.5
[contact]
rolling = iwashita_oda
[iwashita_oda]
K_r = 1
C_r = 0.001
eta = 0.001
[wall_contact]
k_n = 2e5
e = 0.6
mu = 0.3
[walls]
box = bottom
material = steel
[scene]
type = csv
replicate_x = 2
vx = 0.05
file = )" +
         csv.string() + "\n";
}
const char* kCsv =
    "id,x,y,radius,vx,vy,omega,material\n"
    "0,0.02,0.02,0.005,0,0,0,glass\n"
    "1,0.05,0.02,0.005,0.1,0,1,steel\n"
    "2,0.08,0.03,0.006,0,-0.1,0,glass\n";

// The value of `key` in an INI text ("" when absent).
std::string ini_value(const std::string& ini, const std::string& key) {
  const auto dot = key.rfind('.');
  const std::string section = key.substr(0, dot), name = key.substr(dot + 1);
  std::istringstream in(ini);
  std::string current;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line[0] == '[') current = line.substr(1, line.find(']') - 1);
    const auto eq = line.find('=');
    if (current == section && eq != std::string::npos && line.substr(0, line.find_last_not_of(" ", eq - 1) + 1) == name)
      return line.substr(line.find_first_not_of(' ', eq + 1));
  }
  return "";
}

// Every mutation of a number: NaN, infinities, huge, tiny, negative, zero, empty, garbage, overflowing text.
const std::vector<std::string> kMutations = {"nan",
                                             "inf",
                                             "-inf",
                                             "1e300",
                                             "-1e300",
                                             "1e-300",
                                             "-1",
                                             "0",
                                             "",
                                             "garbage",
                                             "1e400",
                                             "4e-320",
                                             "0.5",
                                             "-0.5",
                                             "1e9",
                                             "2147483647",
                                             "9223372036854775807"};

// A valid list for a list key the base leaves empty, so that one of its numbers can be mutated.
std::string list_template(const std::string& key) {
  static const std::map<std::string, std::string> kTemplates = {
      {"scene.region", "0 0.05 0 0.05"},     {"walls.box_region", "0 0.1 0 0.1"},
      {"scene.sizes", "0.004 0.005"},        {"scene.fractions", "0.5 0.5"},
      {"walls.lines", "0 0.095 0 -1"},       {"walls.segments", "0.06 0.05 0.09 0.05"},
      {"scene.material_fractions", "1"},     {"scene.material_radius_min", "0.002"},
      {"scene.material_radius_max", "0.003"}};
  const auto it = kTemplates.find(key);
  return it == kTemplates.end() ? "1" : it->second;
}

std::vector<std::string> tokens_of(const std::string& text) {
  std::vector<std::string> out;
  std::string current;
  for (char ch : text) {
    if (ch == ' ' || ch == ';') {
      if (!current.empty()) out.push_back(current), current.clear();
      out.push_back(std::string(1, ch));
    } else {
      current += ch;
    }
  }
  if (!current.empty()) out.push_back(current);
  return out;
}

// Whether `token` is a number inside `range` (a whole number for an integer key).
bool in_range(const std::string& token, const Range& range, bool integer) {
  if (token.empty()) return false;
  char* end = nullptr;
  const double v = std::strtod(token.c_str(), &end);
  if (end != token.c_str() + token.size() || !range.contains(v)) return false;
  return !integer || v == std::floor(v);
}

struct Case {
  std::string base;  // the scene's name
  std::string key;
  std::string value;
  bool documented = false;  // every number of the value is inside the key's declared range
  bool numeric = false;     // the key holds numbers (its range applies)
};

struct Outcome {
  enum Kind { ran, refused, other } kind = other;
  std::string message;
};

Outcome run_case(const std::string& ini, const Case& c) {
  Communicator comm;
  Outcome o;
  try {
    Simulation sim(parse_config_text(ini, {"--" + c.key + "=" + c.value, "--run.steps=3"}), comm, false);
    for (int k = 0; k < 3; ++k) sim.step();
    double d_other_peak = -HUGE_VAL;
    Reports(sim.state()).check_stability(sim.diagnostics(), d_other_peak);
    o.kind = Outcome::ran;
  } catch (const ConfigError& e) {
    o.kind = Outcome::refused, o.message = e.what();
  } catch (const InputError& e) {
    o.kind = Outcome::refused, o.message = e.what();
  } catch (const std::exception& e) {
    o.message = std::string("other exception: ") + e.what();
  }
  return o;
}

TEST(InputFuzz, EveryKeyAndListNumberRunsOrIsRefusedNamingTheKey) {
  TempDir dir("rondel-fuzz");
  const fs::path csv = dir / "scene.csv";
  test::write_file(csv, kCsv);
  const std::map<std::string, std::string> bases = {{"lattice", kLattice}, {"random", kRandom}, {"csv", csv_ini(csv)}};
  // Each base as it is runs.
  for (const auto& [name, ini] : bases) {
    Communicator comm;
    SCOPED_TRACE(name);
    ASSERT_NO_THROW({
      Simulation sim(parse_config_text(ini), comm, false);
      for (int k = 0; k < 3; ++k) sim.step();
    });
  }
  // The keys of every base (the dynamic sections of C among them), each with the bases that have it.
  std::map<std::string, std::vector<std::string>> where;
  std::map<std::string, KeySpec> spec;
  for (const auto& [name, ini] : bases) {
    const DynamicSections dynamic = dynamic_sections(law_catalog(), ini_keys(ini));
    for (const KeySpec& k : config_keys(law_catalog(), dynamic)) {
      if (k.key == "run.output" || k.key == "run.steps") continue;  // in-process: no files, three steps
      where[k.key].push_back(name);
      spec.emplace(k.key, k);
    }
  }
  ASSERT_GT(spec.size(), 100u);
  // Seeded: the same cases every run (RONDEL_FUZZ_SEED and RONDEL_FUZZ_CASES explore others). Every key once
  // with a mutation chosen by the generator, then random (key, base, mutation) triples up to 400 cases.
  const char* seed_text = std::getenv("RONDEL_FUZZ_SEED");
  const char* cases_text = std::getenv("RONDEL_FUZZ_CASES");
  SceneRandom rng(seed_text ? std::strtoull(seed_text, nullptr, 10) : 20261202);
  const std::size_t n_cases = cases_text ? std::strtoull(cases_text, nullptr, 10) : 400;
  std::vector<std::string> keys;
  for (const auto& [key, bases_of] : where) keys.push_back(key);
  std::vector<Case> cases;
  for (std::size_t n = 0; n < n_cases; ++n) {
    const std::string& key = n < keys.size() ? keys[n] : keys[rng.next() % keys.size()];
    const KeySpec& k = spec.at(key);
    const auto& bases_of = where.at(key);
    Case c{bases_of[rng.next() % bases_of.size()], key, kMutations[rng.next() % kMutations.size()]};
    c.numeric = k.type == KeyType::real || k.type == KeyType::integer || k.type == KeyType::numbers ||
                k.type == KeyType::records;
    c.documented = c.numeric && in_range(c.value, k.range, k.type == KeyType::integer);
    const bool list = k.type == KeyType::numbers || k.type == KeyType::records || key == "walls.control";
    if (list) {
      // One number of the base's list (or of a valid template) replaced.
      std::string text = ini_value(bases.at(c.base), key);
      if (text.empty()) text = key == "walls.control" ? "top:servo:1e3" : list_template(key);
      if (key == "walls.control") {
        c.value = text.substr(0, text.rfind(':') + 1) + c.value;
        c.numeric = false;
      } else {
        auto parts = tokens_of(text);
        std::vector<std::size_t> numbers;
        for (std::size_t t = 0; t < parts.size(); ++t)
          if (parts[t] != " " && parts[t] != ";") numbers.push_back(t);
        const std::size_t t = numbers[rng.next() % numbers.size()];
        parts[t] = c.value;
        c.value.clear();
        bool documented = true;
        for (std::size_t u = 0; u < parts.size(); ++u) {
          c.value += parts[u];
          if (!parts[u].empty() && parts[u] != " " && parts[u] != ";")
            documented = documented && in_range(parts[u], k.range, false);
        }
        c.documented = documented;
      }
    }
    cases.push_back(c);
  }
  int ran = 0, refused = 0;
  for (const Case& c : cases) {
    const std::string what = c.base + ": --" + c.key + "='" + c.value + "'";
    const Outcome o = run_case(bases.at(c.base), c);
    if (o.kind == Outcome::other) {
      ADD_FAILURE() << what << " ended in " << o.message;
    } else if (o.kind == Outcome::refused) {
      ++refused;
      EXPECT_NE(o.message.find(c.key), std::string::npos)
          << what << " was refused without naming the key: " << o.message;
    } else {
      ++ran;
      EXPECT_TRUE(!c.numeric || c.documented) << what << " ran with a value outside the key's documented range";
    }
  }
  std::cout << "[ fuzz    ] " << cases.size() << " cases: " << ran << " ran, " << refused << " refused\n";
  EXPECT_GT(ran, static_cast<int>(n_cases / 20)) << "most mutations are refused, but some must run";
  EXPECT_GT(refused, static_cast<int>(n_cases / 2));
}

// ---- the real executable: exit code 1, the key on stderr once, no output directory ----

TEST(InputFuzz, ExecutableRefusesBadInputWithExitOneBeforeWritingAnything) {
  ASSERT_TRUE(fs::exists(test::rondel_executable())) << test::rondel_executable();
  TempDir dir("rondel-fuzz-exe");
  test::write_file(dir / "lattice.ini", kLattice);
  test::write_file(dir / "empty_flag.ini", kLattice + "[run]\noverwrite =\n");
  test::write_file(dir / "ids.csv", "id,x,y,radius\n0,0.02,0.02,0.005\n0.5,0.05,0.02,0.005\n");
  test::write_file(dir / "big_ids.csv", "0,0.02,0.02,0.005\n1e30,0.05,0.02,0.005\n");
  test::write_file(dir / "nan_velocity.csv", "0,0.02,0.02,0.005,0,0,0\n1,0.05,0.02,0.005,nan,0,0\n");
  fs::create_directories(dir / "a_directory.ini");
  const std::string csv_scene = " --scene.type=csv --scene.file=";
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"lattice.ini --scene.vx=nan", {"scene.vx"}},
      {"lattice.ini --gravity.y=inf", {"gravity.y"}},
      {"lattice.ini --scene.omega=-inf", {"scene.omega"}},
      {"lattice.ini --domain.xhi=inf", {"domain.xhi"}},
      {"lattice.ini '--walls.segments=0.06 0.05 nan 0.05'", {"walls.segments"}},
      {"lattice.ini '--walls.box_region=0 inf 0 0.1'", {"walls.box_region"}},
      {"lattice.ini --scene.type=random '--scene.region=0 0.1 0 inf' --scene.count=5 --scene.radius_min=0.002 "
       "--scene.radius_max=0.002",
       {"scene.region"}},
      {"lattice.ini --scene.type=random --scene.count=1000000000000 --scene.radius_min=0.001 "
       "--scene.radius_max=0.001",
       {"scene.count", "GB"}},
      {"lattice.ini --scene.nx=1000000 --scene.ny=1000000", {"scene.nx", "GB"}},
      {"lattice.ini --scene.radius=1e-150 --scene.spacing=0.01", {"scene.radius", "cells", "GB"}},
      {"lattice.ini --wall_contact.k_s=1e300", {"critical time step", "wall_contact.k_s"}},
      {"lattice.ini --material.density=1e-300 --material.thickness=1e-300", {"material.density"}},
      {"lattice.ini --scene.x=0.03", {"scene.x", "did you mean 'scene.x0'"}},
      {"lattice.ini --scene.cuont=5", {"scene.cuont", "did you mean 'scene.count'"}},
      {"lattice.ini --run.overwrite=", {"run.overwrite"}},
      {"empty_flag.ini", {"run.overwrite", "empty"}},
      {"lattice.ini --scene.seed=-1", {"scene.seed"}},
      {"a_directory.ini", {"a_directory.ini", "is a directory"}},
      {"lattice.ini" + csv_scene + "ids.csv", {"ids.csv", "line 3", "id"}},
      {"lattice.ini" + csv_scene + "big_ids.csv", {"big_ids.csv", "line 2", "id"}},
      {"lattice.ini" + csv_scene + "nan_velocity.csv", {"nan_velocity.csv", "line 2", "vx"}},
  };
  int k = 0;
  for (const auto& [args, words] : cases) {
    SCOPED_TRACE(args);
    const fs::path out = dir / ("out-" + std::to_string(k++));
    const test::Outcome o =
        test::run_in(dir, test::without_mpi_launch(false),
                     test::quoted(test::rondel_executable()) + " " + args + " --run.output=" + test::quoted(out));
    EXPECT_EQ(o.exit_code, 1) << o.err;
    EXPECT_TRUE(o.err.rfind("rondel: configuration error: ", 0) == 0 || o.err.rfind("rondel: input error: ", 0) == 0)
        << o.err;
    for (const std::string& w : words) EXPECT_NE(o.err.find(w), std::string::npos) << "no '" << w << "' in: " << o.err;
    EXPECT_FALSE(fs::exists(out)) << "a refused run created " << out;
  }
}

TEST(InputFuzz, RefusalsAreAgreedOnThreeRanks) {
  // Every rank finds the same error (a key's value, a derived quantity): each exits 1, the message once.
  if (!test::have_program("mpirun")) GTEST_SKIP() << "mpirun is not installed";
  TempDir dir("rondel-fuzz-ranks");
  test::write_file(dir / "lattice.ini", kLattice);
  std::string env = test::without_mpi_launch(true);
  if (geteuid() == 0) env += " OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1";
  for (const auto& [args, key] : std::vector<std::pair<std::string, std::string>>{
           {"--scene.vx=nan", "scene.vx"}, {"--material.density=1e-300", "material.density"}}) {
    SCOPED_TRACE(args);
    const fs::path out = dir / "out";
    const test::Outcome o =
        test::run_in(dir, env,
                     "timeout 120 mpirun -n 3 --oversubscribe " + test::quoted(test::rondel_executable()) +
                         " lattice.ini " + args + " --run.output=" + test::quoted(out));
    EXPECT_EQ(o.exit_code, 1) << o.err;
    const auto first = o.err.find("rondel: configuration error:");
    ASSERT_NE(first, std::string::npos) << o.err;
    EXPECT_EQ(o.err.find("rondel: configuration error:", first + 1), std::string::npos) << "printed twice: " << o.err;
    EXPECT_NE(o.err.find(key), std::string::npos) << o.err;
    EXPECT_FALSE(fs::exists(out));
  }
}

}  // namespace
}  // namespace rondel
