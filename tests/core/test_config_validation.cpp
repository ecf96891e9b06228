// The validation pass of the configuration (docs/design.md section 8, issue 16): every key declares its type
// and range once (config_keys, the same lines as the schema and --help); every value given, and every number
// of a list, is finite and in range or the parse throws a ConfigError naming the key. No prefix guessing, the
// closest key suggested for an unknown one, no empty flag, no negative seed, no directory as the INI file.
#include <gtest/gtest.h>

#include <boost/any.hpp>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/Config.hpp"
#include "core/ConfigSchema.hpp"
#include "core/Errors.hpp"
#include "physics/LawRegistry.hpp"

namespace rondel {
namespace {

namespace po = boost::program_options;

const std::string kValid = R"(
[run]
steps = 50
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

// The ConfigError's message ("" and a failure when the parse does not throw one).
std::string refusal(const std::string& ini, const std::vector<std::string>& overrides) {
  try {
    parse_config_text(ini, overrides);
  } catch (const ConfigError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not a ConfigError: " << e.what();
    return "";
  }
  ADD_FAILURE() << "accepted";
  return "";
}

bool has(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

double number_of(const boost::any& v) {
  if (auto p = boost::any_cast<double>(&v)) return *p;
  if (auto p = boost::any_cast<std::int64_t>(&v)) return static_cast<double>(*p);
  if (auto p = boost::any_cast<int>(&v)) return *p;
  ADD_FAILURE() << "a number key of another type";
  return 0.0;
}

TEST(ConfigValidation, EveryKeyIsDeclaredOnceAndEveryDefaultIsInItsRange) {
  const auto keys = config_keys(law_catalog());
  const auto schema = config_schema();
  ASSERT_EQ(keys.size(), schema.options().size()) << "one KeySpec per key of the schema";
  for (std::size_t k = 0; k < keys.size(); ++k) {
    EXPECT_EQ(keys[k].key, schema.options()[k]->long_name());
    for (std::size_t j = 0; j < k; ++j) EXPECT_NE(keys[j].key, keys[k].key) << "declared twice";
    if (keys[k].type != KeyType::real && keys[k].type != KeyType::integer) continue;
    boost::any def;
    if (!schema.options()[k]->semantic()->apply_default(def)) continue;
    EXPECT_TRUE(keys[k].range.contains(number_of(def))) << keys[k].key << " defaults outside " << keys[k].range.text();
  }
}

TEST(ConfigValidation, HelpShowsTheRanges) {
  const std::string help = config_help();
  for (const auto& [key, range] :
       std::vector<std::pair<std::string, std::string>>{{"--run.safety", "in (0, 1]"},
                                                        {"--linear.k_n", "> 0"},
                                                        {"--scene.sizes", "each number > 0"},
                                                        {"--parallel.check_every", "in [1, 1000]"},
                                                        {"--scene.vx", "in [-2.99792e+08"}}) {
    const auto at = help.find(key + " ");
    ASSERT_NE(at, std::string::npos) << key;
    const auto next = help.find("\n  --", at + 1);
    std::string entry;  // the help lines of the key, joined (Boost wraps them)
    for (const char ch : help.substr(at, next - at))
      if (!(ch == ' ' || ch == '\n') || (!entry.empty() && entry.back() != ' ')) entry += ch == '\n' ? ' ' : ch;
    EXPECT_TRUE(has(entry, range)) << key << " should show '" << range << "': " << entry;
  }
}

TEST(ConfigValidation, NonFiniteNumbersOfEveryKeyAreRefusedNamingTheKey) {
  int checked = 0;
  for (const KeySpec& k : config_keys(law_catalog())) {
    if (k.type != KeyType::real) continue;
    for (const char* bad : {"nan", "inf", "-inf", "NaN", "-Infinity"}) {
      SCOPED_TRACE(k.key + " = " + bad);
      EXPECT_TRUE(has(refusal(kValid, {"--" + k.key + "=" + bad}), k.key));
      ++checked;
    }
  }
  EXPECT_GT(checked, 200);
}

TEST(ConfigValidation, EveryNumberOfAListIsFiniteAndInRange) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"scene.region", "0 0.1 inf 0.1"},         {"walls.box_region", "0 inf 0 0.1"},
      {"walls.segments", "0 0.05 nan 0.05"},     {"walls.segments", "0 0.05 0.1 0.05 0 1e999"},
      {"walls.lines", "0 0 0 1; 0 0.1 -inf -1"}, {"walls.control", "bottom:strain_rate:nan"},
      {"scene.sizes", "0.001 -0.002"},           {"scene.fractions", "0.5 nan"},
      {"scene.material_fractions", "inf"},
  };
  for (const auto& [key, value] : cases) {
    SCOPED_TRACE(key + " = " + value);
    EXPECT_TRUE(has(refusal(kValid, {"--" + key + "=" + value}), key));
  }
  EXPECT_TRUE(has(refusal(kValid, {"--walls.segments=0 0.05 0.1 x"}), "not a number"));
}

TEST(ConfigValidation, AbsurdValuesAreRefused) {
  // A finite box whose length is not, a speed faster than light, a gravity beyond any star's.
  EXPECT_TRUE(has(refusal(kValid, {"--domain.xlo=-1e308", "--domain.xhi=1e308"}), "domain.xhi"));
  EXPECT_TRUE(has(refusal(kValid, {"--scene.vy=3e8"}), "scene.vy"));
  EXPECT_TRUE(has(refusal(kValid, {"--walls.box=bottom top", "--walls.control=top:shear:1e9"}), "walls.control"));
  EXPECT_TRUE(has(refusal(kValid, {"--gravity.y=-1e13"}), "gravity.y"));
  EXPECT_TRUE(has(refusal(kValid, {"--run.steps=9223372036854775807"}), "run.steps"));
  EXPECT_TRUE(has(refusal(kValid, {"--scene.seed=-1"}), "scene.seed"));
  EXPECT_TRUE(has(refusal(kValid, {"--scene.max_attempts=0"}), "scene.max_attempts"));
  EXPECT_EQ(parse_config_text(kValid, {"--scene.seed=9"}).scene.seed, 9u);
}

TEST(ConfigValidation, NoPrefixGuessingAndTheClosestKeyIsSuggested) {
  const std::string x = refusal(kValid, {"--scene.x=0.03"});
  EXPECT_TRUE(has(x, "scene.x")) << x;
  EXPECT_TRUE(has(x, "did you mean 'scene.x0'?")) << x;
  EXPECT_TRUE(has(refusal(kValid, {"--run.step=5"}), "did you mean 'run.steps'?"));
  const std::string in_file = refusal(kValid + "cuont = 3\n", {});
  EXPECT_TRUE(has(in_file, "scene.cuont")) << in_file;
  EXPECT_TRUE(has(in_file, "did you mean 'scene.count'?")) << in_file;
  EXPECT_FALSE(has(refusal(kValid, {"--run.bogus_key_far_from_all=1"}), "did you mean")) << "nothing close";
}

TEST(ConfigValidation, AnEmptyFlagIsRefused) {
  EXPECT_TRUE(has(refusal(kValid + "[run]\noverwrite =\n", {}), "run.overwrite"));
  EXPECT_TRUE(has(refusal(kValid, {"--run.progress="}), "run.progress"));
  EXPECT_TRUE(has(refusal(kValid, {"--run.progress=maybe"}), "run.progress"));
  EXPECT_FALSE(parse_config_text(kValid, {"--run.progress=false"}).progress);
}

TEST(ConfigValidation, ADirectoryIsNotAConfigurationFile) {
  const std::string dir = ::testing::TempDir() + "rondel_config_dir.ini";
  std::filesystem::create_directories(dir);
  const char* argv[] = {"rondel", dir.c_str()};
  try {
    parse_config(2, argv);
    ADD_FAILURE() << "accepted a directory";
  } catch (const ConfigError& e) {
    EXPECT_TRUE(has(e.what(), dir)) << e.what();
    EXPECT_TRUE(has(e.what(), "is a directory")) << e.what();
  }
  std::filesystem::remove(dir);
}

}  // namespace
}  // namespace rondel
