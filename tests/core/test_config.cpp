// Configuration refusals (docs/design.md section 8): an unknown key, a missing required one, a value out of
// range, or a parameter block for a law that is not selected raises ConfigError naming the key, before
// any work starts. Valid input parses, the command line wins over the file, and --help lists every key
// with its unit.
#include <gtest/gtest.h>

#include <boost/program_options.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "core/Config.hpp"
#include "core/ConfigSchema.hpp"
#include "core/Errors.hpp"
#include "core/SceneTypes.hpp"
#include "physics/LawRegistry.hpp"

namespace rondel {
namespace {

// A minimal valid configuration; each test adds, removes or overrides one thing.
const std::string kValid = R"(
[run]
steps = 50
dt = 0
[domain]
xlo = 0
xhi = 0.2
ylo = 0
yhi = 0.1
[linear]
k_n = 1e5
e = 0.8
[coulomb]
k_s = 7.5e4
mu = 0.5
[walls]
box = bottom left right
[scene]
type = lattice_square
nx = 4
ny = 3
radius = 0.005
x0 = 0.01
y0 = 0.01
)";

// `ini` without the line `key = ...` of the given section.
std::string without(const std::string& ini, const std::string& section, const std::string& key) {
  std::istringstream in(ini);
  std::string line, current, out;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] == '[') current = line.substr(1, line.find(']') - 1);
    if (current == section && line.rfind(key + " ", 0) == 0) continue;
    out += line + "\n";
  }
  return out;
}
std::string without(const std::string& section, const std::string& key) { return without(kValid, section, key); }

// Runs the parser and returns the ConfigError's message; fails the test when it does not throw one.
std::string config_error(const std::string& ini, const std::vector<std::string>& overrides = {}) {
  try {
    parse_config_text(ini, overrides);
  } catch (const ConfigError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw something other than ConfigError: " << e.what();
    return "";
  }
  ADD_FAILURE() << "accepted; expected a ConfigError";
  return "";
}

// Success when parsing throws a ConfigError whose message contains `key`.
::testing::AssertionResult refused_naming(const std::string& ini, const std::vector<std::string>& overrides,
                                          const std::string& key) {
  const std::string message = config_error(ini, overrides);
  if (message.find(key) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "the message does not name " << key << ": '" << message << "'";
}

TEST(Config, ValidInputParses) {
  const Config c = parse_config_text(kValid);
  EXPECT_EQ(c.steps, 50);
  EXPECT_EQ(c.dt, 0.0);
  EXPECT_EQ(c.domain.xhi, 0.2);
  EXPECT_EQ(c.domain.yhi, 0.1);
  EXPECT_FALSE(c.domain.periodic_x);
  EXPECT_EQ(c.normal_law, "linear");
  EXPECT_EQ(c.tangential_law, "coulomb");
  EXPECT_EQ(c.rolling_law, "none");
  ASSERT_EQ(c.params.n_materials(), 1u);
  EXPECT_EQ(c.params.pair(0, 0).k_n, 1e5);
  EXPECT_EQ(c.params.pair(0, 0).e_n, 0.8);
  EXPECT_EQ(c.params.pair(0, 0).k_s, 7.5e4);
  EXPECT_EQ(c.params.pair(0, 0).mu, 0.5);
  EXPECT_EQ(c.params.wall(0).k_n, 1e5) << "walls default to the disc-disc parameters";
  EXPECT_EQ(c.walls.size(), 3u);
  EXPECT_EQ(c.box_walls, (std::vector<std::string>{"bottom", "left", "right"}));
  EXPECT_STREQ(c.scene.type->name, "lattice_square");
  EXPECT_EQ(c.scene.nx, 4);
  EXPECT_EQ(c.scene.spacing, 0.01) << "spacing 0 means 2 x radius";
  EXPECT_EQ(c.materials.front().density, 2650.0) << "default density";
  EXPECT_NE(c.resolved_text.find("k_n = 100000"), std::string::npos) << c.resolved_text;
}

TEST(Config, CommandLineOverridesWinOverTheFile) {
  const Config c = parse_config_text(
      kValid, {"--run.steps=7", "--linear.k_n=2e5", "--scene.nx=2", "--domain.periodic_x=true", "--walls.box=bottom"});
  EXPECT_EQ(c.steps, 7);
  EXPECT_EQ(c.params.pair(0, 0).k_n, 2e5);
  EXPECT_EQ(c.scene.nx, 2);
  EXPECT_TRUE(c.domain.periodic_x);
  EXPECT_EQ(c.walls.size(), 1u);
  EXPECT_NE(c.resolved_text.find("steps = 7"), std::string::npos) << "the resolved text shows the override";
  // An override may also supply a key missing from the file.
  const Config d = parse_config_text(without("linear", "k_n"), {"--linear.k_n=3e5"});
  EXPECT_EQ(d.params.pair(0, 0).k_n, 3e5);
}

TEST(Config, UnknownKeyIsRefused) {
  EXPECT_TRUE(refused_naming(kValid + "[run]\nbogus = 1\n", {}, "run.bogus"));
  EXPECT_TRUE(refused_naming(kValid + "[nonsense]\nk = 1\n", {}, "nonsense.k"));
  EXPECT_TRUE(refused_naming(kValid, {"--run.bogus=1"}, "run.bogus"));
  EXPECT_TRUE(refused_naming(kValid, {"--linear.kn=1"}, "linear.kn"));
}

TEST(Config, MissingRequiredKeyIsRefused) {
  const std::vector<std::pair<std::string, std::string>> required = {{"linear", "k_n"},  {"domain", "xlo"},
                                                                     {"domain", "yhi"},  {"scene", "type"},
                                                                     {"coulomb", "k_s"}, {"coulomb", "mu"}};
  for (const auto& [section, key] : required) {
    SCOPED_TRACE(section + "." + key);
    const std::string ini = without(section, key);
    ASSERT_NE(ini, kValid) << "the test did not remove the key";
    EXPECT_TRUE(refused_naming(ini, {}, section + "." + key));
  }
}

TEST(Config, NonPositiveDensityIsRefused) {
  EXPECT_TRUE(refused_naming(kValid, {"--material.density=0"}, "material.density"));
  EXPECT_TRUE(refused_naming(kValid, {"--material.density=-2650"}, "material.density"));
  EXPECT_TRUE(refused_naming(kValid, {"--material.thickness=0"}, "material.thickness"));
}

TEST(Config, NonPositiveStiffnessIsRefused) {
  EXPECT_TRUE(refused_naming(kValid, {"--linear.k_n=0"}, "linear.k_n"));
  EXPECT_TRUE(refused_naming(kValid, {"--linear.k_n=-1e5"}, "linear.k_n"));
  EXPECT_TRUE(refused_naming(kValid, {"--coulomb.k_s=0"}, "coulomb.k_s"));
  EXPECT_TRUE(refused_naming(kValid, {"--coulomb.k_s=-3"}, "coulomb.k_s"));
  EXPECT_TRUE(refused_naming(kValid, {"--wall_contact.k_n=0"}, "wall_contact.k_n"));
}

TEST(Config, RestitutionOutsideZeroOneIsRefused) {
  EXPECT_TRUE(refused_naming(kValid, {"--linear.e=0"}, "linear.e"));
  EXPECT_TRUE(refused_naming(kValid, {"--linear.e=1.5"}, "linear.e"));
  EXPECT_TRUE(refused_naming(kValid, {"--linear.e=-0.5"}, "linear.e"));
  EXPECT_NO_THROW(parse_config_text(kValid, {"--linear.e=1"})) << "e = 1 (elastic) is allowed";
  EXPECT_TRUE(refused_naming(kValid, {"--wall_contact.e=0"}, "wall_contact.e"));
}

TEST(Config, NegativeFrictionIsRefused) {
  EXPECT_TRUE(refused_naming(kValid, {"--coulomb.mu=-0.1"}, "coulomb.mu"));
  EXPECT_TRUE(refused_naming(kValid, {"--wall_contact.mu=-0.1"}, "wall_contact.mu"));
  EXPECT_NO_THROW(parse_config_text(kValid, {"--coulomb.mu=0"})) << "frictionless is allowed";
}

TEST(Config, NegativeDampingIsRefused) {
  EXPECT_TRUE(refused_naming(without("linear", "e"), {"--linear.zeta=-0.1"}, "linear.zeta"));
  EXPECT_TRUE(refused_naming(without("linear", "e"), {"--linear.c_n=-1"}, "linear.c_n"));
  EXPECT_TRUE(refused_naming(kValid, {"--coulomb.zeta_t=-0.1"}, "coulomb.zeta_t"));
}

// run.local_damping: alpha in [0, 1); NaN, infinite, negative and >= 1 refused, naming the key and the range.
TEST(Config, LocalDampingOutsideZeroOneIsRefused) {
  for (const char* bad : {"-0.1", "1", "1.5", "nan", "inf", "-inf", "1e300"}) {
    const std::string message = config_error(kValid, {std::string("--run.local_damping=") + bad});
    EXPECT_NE(message.find("run.local_damping"), std::string::npos) << bad << ": " << message;
    EXPECT_NE(message.find("[0, 1)"), std::string::npos) << bad << ": " << message;
  }
  EXPECT_EQ(parse_config_text(kValid).local_damping, 0.0) << "off by default";
  EXPECT_EQ(parse_config_text(kValid, {"--run.local_damping=0"}).local_damping, 0.0);
  EXPECT_EQ(parse_config_text(kValid, {"--run.local_damping=0.7"}).local_damping, 0.7);
  EXPECT_EQ(parse_config_text(kValid, {"--run.local_damping=0.999"}).local_damping, 0.999);
}

TEST(Config, LawBlockForALawNotSelectedIsRefused) {
  // kValid has a [coulomb] block: with contact.tangential = none it must be refused, naming a coulomb key.
  const std::string message = config_error(kValid, {"--contact.tangential=none"});
  EXPECT_NE(message.find("coulomb."), std::string::npos) << message;
  EXPECT_NE(message.find("contact.tangential"), std::string::npos) << message;
  EXPECT_TRUE(refused_naming(without("coulomb", "mu"), {"--contact.tangential=none"}, "coulomb.k_s"));
  EXPECT_TRUE(refused_naming(without("coulomb", "k_s"), {"--contact.tangential=none"}, "coulomb.mu"));
  // Without the block the same selection is valid, and any single coulomb key is refused.
  const std::string no_coulomb = without(without("coulomb", "k_s"), "coulomb", "mu");
  ASSERT_EQ(no_coulomb.find("k_s"), std::string::npos);
  ASSERT_EQ(no_coulomb.find("mu ="), std::string::npos);
  const Config c = parse_config_text(no_coulomb, {"--contact.tangential=none"});
  EXPECT_EQ(c.tangential_law, "none");
  EXPECT_EQ(c.params.pair(0, 0).k_s, 0.0);
  for (const char* key : {"coulomb.k_s", "coulomb.mu", "coulomb.zeta_t"})
    EXPECT_TRUE(refused_naming(no_coulomb, {"--contact.tangential=none", std::string("--") + key + "=0.3"}, key));
  EXPECT_TRUE(refused_naming(no_coulomb, {"--contact.tangential=none", "--wall_contact.mu=0.3"}, "wall_contact.mu"));
  EXPECT_TRUE(refused_naming(no_coulomb, {"--contact.tangential=none", "--wall_contact.k_s=1e4"}, "wall_contact.k_s"));
}

TEST(Config, TwoDampingKeysAtOnceAreRefused) {
  // kValid gives linear.e.
  const std::string both = config_error(kValid, {"--linear.zeta=0.1"});
  EXPECT_NE(both.find("linear.zeta"), std::string::npos) << both;
  EXPECT_NE(both.find("linear.e"), std::string::npos) << both;
  EXPECT_TRUE(refused_naming(kValid, {"--linear.c_n=3"}, "linear.c_n"));
  EXPECT_TRUE(refused_naming(without("linear", "e"), {"--linear.c_n=3", "--linear.zeta=0.1"}, "linear.c_n"));
  EXPECT_TRUE(refused_naming(kValid, {"--wall_contact.zeta=0.1", "--wall_contact.e=0.5"}, "wall_contact.zeta"));
  EXPECT_NO_THROW(parse_config_text(without("linear", "e"), {"--linear.zeta=0.1"}));
}

TEST(Config, UnknownLawNameIsRefused) {
  EXPECT_TRUE(refused_naming(kValid, {"--contact.normal=bogus_law"}, "contact.normal"));
  EXPECT_TRUE(refused_naming(kValid, {"--contact.tangential=bogus_law"}, "contact.tangential"));
  EXPECT_TRUE(refused_naming(kValid, {"--contact.rolling=bogus_law"}, "contact.rolling"));
  const std::string message = config_error(kValid, {"--contact.tangential=bogus_law"});
  EXPECT_NE(message.find("bogus_law"), std::string::npos) << "the message shows the value: " << message;
  EXPECT_NE(message.find("coulomb"), std::string::npos) << "the message lists what is allowed: " << message;
}

TEST(Config, BadWallsBoxSideIsRefused) {
  EXPECT_TRUE(refused_naming(kValid, {"--walls.box=bottom floor"}, "walls.box"));
  const std::string message = config_error(kValid, {"--walls.box=bottom floor"});
  EXPECT_NE(message.find("floor"), std::string::npos) << message;
  // A box wall across a periodic direction.
  EXPECT_TRUE(refused_naming(kValid, {"--domain.periodic_x=true"}, "walls.box"));
  EXPECT_TRUE(refused_naming(kValid, {"--domain.periodic_y=true", "--walls.box=top"}, "walls.box"));
}

TEST(Config, BadWallRecordsAreRefused) {
  EXPECT_TRUE(refused_naming(kValid, {"--walls.lines=0 0 0"}, "walls.lines"));
  EXPECT_TRUE(refused_naming(kValid, {"--walls.lines=0 0 0 0"}, "walls.lines"));
  EXPECT_TRUE(refused_naming(kValid, {"--walls.segments=0 0 x 1"}, "walls.segments"));
  EXPECT_TRUE(refused_naming(kValid, {"--walls.segments=0.1 0.1 0.1 0.1"}, "walls.segments"));
  // Numbers that are not finite, a rotation record of the wrong length or with omega = 0.
  EXPECT_TRUE(refused_naming(kValid, {"--walls.lines=0 0 0 1 nan 0"}, "walls.lines"));
  EXPECT_TRUE(refused_naming(kValid, {"--walls.segments=0 0 1 inf"}, "walls.segments"));
  EXPECT_TRUE(refused_naming(kValid, {"--walls.segments=0 0 1 0 2 0 0 0"}, "walls.segments"));
  EXPECT_TRUE(refused_naming(kValid, {"--walls.segments=0 0 1 0 0 0.5 0.5"}, "walls.segments"));
}

TEST(Config, CircleAndRotatingWalls) {
  // walls.lines, then walls.segments, then walls.circles, then the box sides.
  const Config c = parse_config_text(
      kValid, {"--walls.segments=0 0 0.1 0 3 0.05 0.05", "--walls.circles=0.05 0.05 0.04 -2", "--walls.box=bottom"});
  ASSERT_EQ(c.walls.size(), 3u);
  const Wall& seg = c.walls[0];
  EXPECT_EQ(seg.kind, Wall::Kind::segment);
  EXPECT_EQ(seg.omega, 3.0);
  EXPECT_EQ(seg.centre.x, 0.05);
  EXPECT_EQ(seg.centre.y, 0.05);
  EXPECT_DOUBLE_EQ(seg.lever, std::hypot(0.05, 0.05));  // its farthest end from the centre
  EXPECT_EQ(seg.velocity.x, 0.0);
  const Wall& drum = c.walls[1];
  EXPECT_EQ(drum.kind, Wall::Kind::circle);
  EXPECT_EQ(drum.radius, 0.04);
  EXPECT_EQ(drum.omega, -2.0);
  EXPECT_EQ(drum.lever, 0.0);  // rotation leaves a circle in place
  EXPECT_EQ(c.walls[2].box_side, 0);
  // A circle: n from the disc to the rim, dist = R_c - |x - c| (u_n = |x - c| + R - R_c).
  const Wall::Proximity p = drum.proximity({0.05, 0.02});
  EXPECT_DOUBLE_EQ(p.dist, 0.04 - 0.03);
  EXPECT_DOUBLE_EQ(p.n.x, 0.0);
  EXPECT_DOUBLE_EQ(p.n.y, -1.0);
  // Refused: a bad record length, R_c <= 0, numbers that are not finite.
  EXPECT_TRUE(refused_naming(kValid, {"--walls.circles=0 0"}, "walls.circles"));
  EXPECT_TRUE(refused_naming(kValid, {"--walls.circles=0 0 1 2 3"}, "walls.circles"));
  EXPECT_TRUE(refused_naming(kValid, {"--walls.circles=0 0 0"}, "walls.circles"));
  EXPECT_TRUE(refused_naming(kValid, {"--walls.circles=0 0 -0.1"}, "walls.circles"));
  EXPECT_TRUE(refused_naming(kValid, {"--walls.circles=0 0 nan"}, "walls.circles"));
  EXPECT_TRUE(refused_naming(kValid, {"--walls.circles=0 0 0.1 inf"}, "walls.circles"));
  const std::string message = config_error(kValid, {"--walls.circles=0 0 0"});
  EXPECT_NE(message.find("R_c > 0"), std::string::npos) << message;
}

TEST(Config, RoughWallsAndShearControls) {
  // Parsed: a servo and a shear velocity on one wall, and a rough wall.
  const Config c = parse_config_text(kValid, {"--walls.box=bottom top", "--walls.control=top:servo:1e5 top:shear:0.02",
                                              "--walls.rough=bottom top", "--walls.rough_depth=0.003"});
  ASSERT_EQ(c.walls.size(), 2u);
  EXPECT_EQ(c.walls[1].control, Wall::Control::servo);
  EXPECT_EQ(c.walls[1].target_stress, 1e5);
  EXPECT_EQ(c.walls[1].shear_velocity, 0.02);
  EXPECT_TRUE(c.walls[0].rough && c.walls[1].rough);
  EXPECT_EQ(c.rough_depth, 0.003);
  // Refused, naming the key: a side that is not a box wall, two normal controls on one wall, an unknown
  // mode, a negative depth.
  EXPECT_TRUE(refused_naming(kValid, {"--walls.box=bottom", "--walls.rough=top"}, "walls.rough"));
  EXPECT_TRUE(refused_naming(kValid, {"--walls.box=bottom top", "--walls.control=top:servo:1e5 top:strain_rate:0.1"},
                             "walls.control"));
  EXPECT_TRUE(refused_naming(kValid, {"--walls.box=bottom top", "--walls.control=top:slide:0.1"}, "walls.control"));
  EXPECT_TRUE(refused_naming(kValid, {"--walls.box=bottom top", "--walls.rough_depth=-1"}, "walls.rough_depth"));
  const std::string message = config_error(kValid, {"--walls.box=bottom", "--walls.rough=top"});
  EXPECT_NE(message.find("'top'"), std::string::npos) << message;
}

TEST(Config, SceneFractionsMustSumToOne) {
  const std::vector<std::string> random = {"--scene.type=random", "--scene.count=10", "--scene.distribution=list",
                                           "--scene.sizes=0.004 0.005"};
  auto with = [&](const std::string& fractions) {
    auto v = random;
    v.push_back("--scene.fractions=" + fractions);
    return v;
  };
  EXPECT_TRUE(refused_naming(kValid, with("0.5 0.4"), "scene.fractions"));
  EXPECT_TRUE(refused_naming(kValid, with("0.7 0.4"), "scene.fractions"));
  EXPECT_TRUE(refused_naming(kValid, with("1"), "scene.fractions")) << "one fraction per size";
  EXPECT_TRUE(refused_naming(kValid, with("1.5 -0.5"), "scene.fractions"));
  const Config c = parse_config_text(kValid, with("0.25 0.75"));
  EXPECT_EQ(c.scene.fractions, (std::vector<double>{0.25, 0.75}));
}

TEST(Config, OtherOutOfRangeValuesNameTheirKey) {
  EXPECT_TRUE(refused_naming(kValid, {"--scene.type=hexagonal"}, "scene.type"));
  EXPECT_TRUE(refused_naming(kValid, {"--scene.radius=0"}, "scene.radius"));
  EXPECT_TRUE(refused_naming(kValid, {"--domain.xhi=-1"}, "domain.xhi"));
  EXPECT_TRUE(refused_naming(kValid, {"--run.safety=1.5"}, "run.safety"));
  EXPECT_TRUE(refused_naming(kValid, {"--run.dt=-1e-5"}, "run.dt"));
  EXPECT_TRUE(refused_naming(kValid, {"--neighbour.skin=-0.001"}, "neighbour.skin"));
  EXPECT_TRUE(refused_naming(kValid, {"--diagnostics.every=0"}, "diagnostics.every"));
  EXPECT_TRUE(refused_naming(kValid, {"--run.steps=1.5"}, "run.steps")) << "not an integer";
  EXPECT_TRUE(refused_naming(kValid, {"--linear.k_n=stiff"}, "linear.k_n")) << "not a number";
  EXPECT_TRUE(refused_naming(kValid, {"--scene.type=csv"}, "scene.file"));
}

TEST(Config, HelpListsEveryKeyWithItsUnit) {
  const std::string help = config_help();
  const auto schema = config_schema();
  ASSERT_GT(schema.options().size(), 40u);
  for (const auto& opt : schema.options()) {
    const std::string name = opt->long_name();
    EXPECT_NE(help.find("--" + name), std::string::npos) << name << " is missing from --help";
    const std::string& text = opt->description();
    EXPECT_TRUE(text.size() > 2 && text[0] == '[' && text.find(']') != std::string::npos)
        << name << " has no [unit] at the start of its description: '" << text << "'";
  }
  // A few keys with their unit on the same help line.
  const std::vector<std::pair<std::string, std::string>> units = {
      {"--linear.k_n", "[N/m]"},  {"--run.dt", "[s]"},     {"--material.density", "[kg/m^3]"},
      {"--gravity.y", "[m/s^2]"}, {"--coulomb.mu", "[-]"}, {"--scene.omega", "[rad/s]"}};
  for (const auto& [key, unit] : units) {
    const auto at = help.find(key);
    ASSERT_NE(at, std::string::npos) << key;
    const auto end = help.find('\n', help.find('[', at));
    const std::string entry = help.substr(at, end - at);
    EXPECT_NE(entry.find(unit), std::string::npos) << key << " should show " << unit << ": '" << entry << "'";
  }
}

TEST(Config, HelpIsRequestedWithDashDashHelp) {
  const char* argv[] = {"rondel", "--help"};
  try {
    parse_config(2, argv);
    ADD_FAILURE() << "--help did not throw HelpRequested";
  } catch (const HelpRequested& h) {
    EXPECT_EQ(h.text, config_help());
  }
}

TEST(Config, CommandLineWithAFileAndOverrides) {
  const std::string file = ::testing::TempDir() + "rondel_test_config_cli.ini";
  std::ofstream(file) << kValid;
  {
    const char* argv[] = {"rondel", file.c_str(), "--run.steps=3", "--coulomb.mu=0.25"};
    const Config c = parse_config(4, argv);
    EXPECT_EQ(c.steps, 3);
    EXPECT_EQ(c.params.pair(0, 0).mu, 0.25);
    EXPECT_EQ(c.source_file, file);
  }
  const char* bogus[] = {"rondel", file.c_str(), "--run.bogus=1"};
  try {
    parse_config(3, bogus);
    ADD_FAILURE() << "accepted --run.bogus";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("run.bogus"), std::string::npos) << e.what();
  }
  std::ofstream(file) << kValid << "[linear]\nbogus = 2\n";
  const char* plain[] = {"rondel", file.c_str()};
  try {
    parse_config(2, plain);
    ADD_FAILURE() << "accepted linear.bogus in the file";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("linear.bogus"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << "names the file: " << e.what();
  }
  std::remove(file.c_str());
}

TEST(Config, MissingFileIsAConfigErrorNamingIt) {
  const char* argv[] = {"rondel", "/nonexistent/dir/scene.ini"};
  try {
    parse_config(2, argv);
    ADD_FAILURE() << "accepted a missing file";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/scene.ini"), std::string::npos) << e.what();
  }
}

// An unknown scene type used to fall through to the CSV builder (and fail there, or read a file it was not meant
// to): scene.type is a choice of the scene registry, refused naming the value and every type the registry has.
TEST(Config, AnUnknownSceneTypeIsRefusedListingTheRegistrysTypes) {
  std::string message;
  try {
    parse_config_text(kValid, {"--scene.type=hexagonal"});
  } catch (const ConfigError& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("scene.type"), std::string::npos) << message;
  EXPECT_NE(message.find("hexagonal"), std::string::npos) << message;
  for (const SceneType* type : scene_types()) EXPECT_NE(message.find(type->name), std::string::npos) << message;
  // Without the key: missing, with the same list.
  std::string without = kValid;
  without.erase(without.find("type = lattice_square"), std::string("type = lattice_square").size());
  try {
    parse_config_text(without);
    ADD_FAILURE() << "a configuration without scene.type was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("missing required key 'scene.type'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rondel
