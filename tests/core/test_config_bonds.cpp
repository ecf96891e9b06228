// [bonds] and its pair blocks (docs/bonds.md): any key of [bonds] bonds every pair of discs with its parameters; a
// pair block [bonds.A.B] changes its pair's, or without [bonds] bonds its pair alone (then it gives every required
// key); the refusals name the key: a required key missing, a value that is not finite or not in its range, a pair
// block at a wall. A configuration without [bonds] has no bonds and its resolved text no [bonds] block, so that it
// reads back without bonds; one with them reads back with the same bonds.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/Config.hpp"
#include "core/Errors.hpp"
#include "physics/LawRegistry.hpp"

namespace rondel {
namespace {

const std::string kTwo = R"(
[domain]
xlo = 0
xhi = 0.2
ylo = 0
yhi = 0.1
[material.cement]
density = 2650
[material.grain]
density = 2650
[linear]
k_n = 1e6
[coulomb]
k_s = 7.5e5
mu = 0.5
[scene]
type = lattice_square
nx = 4
ny = 2
radius = 0.005
x0 = 0.01
y0 = 0.01
materials = cement grain
material_fractions = 0.5 0.5
)";

const std::vector<std::string> kAllPairs{"--bonds.kb_n=1e9", "--bonds.kb_s=5e8", "--bonds.sigma_c=1e6",
                                         "--bonds.tau_c=2e6"};

std::string error_of(const std::vector<std::string>& overrides) {
  try {
    parse_config_text(kTwo, overrides);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

bool has(const std::string& message, const std::string& part) { return message.find(part) != std::string::npos; }

TEST(ConfigBonds, WithoutBondsKeysNoPairIsBondedAndTheResolvedTextHasNoBondsBlock) {
  const Config c = parse_config_text(kTwo);
  EXPECT_FALSE(c.bonds);
  for (const ContactParams& p : c.params.pairs()) EXPECT_EQ(p.kb_n, 0.0);
  EXPECT_EQ(c.resolved_text.find("[bonds]"), std::string::npos) << c.resolved_text;
  EXPECT_FALSE(parse_config_text(c.resolved_text).bonds);
}

TEST(ConfigBonds, TheBondsBlockBondsEveryPairAndPairBlocksChangeTheirPair) {
  std::vector<std::string> o = kAllPairs;
  o.insert(o.end(), {"--bonds.gap=0.05", "--bonds.sigma_spread=0.2", "--bonds.cement.grain.sigma_c=3e5"});
  const Config c = parse_config_text(kTwo, o);
  ASSERT_TRUE(c.bonds);
  EXPECT_EQ(c.bond_gap, 0.05);
  const ContactParams& cc = c.params.pair(0, 0);  // materials in name order: cement 0, grain 1
  EXPECT_EQ(cc.kb_n, 1e9);
  EXPECT_EQ(cc.kb_s, 5e8);
  EXPECT_EQ(cc.sigma_c, 1e6);
  EXPECT_EQ(cc.tau_c, 2e6);
  EXPECT_EQ(cc.sigma_spread, 0.2);
  EXPECT_EQ(cc.tau_spread, 0.0);
  EXPECT_EQ(cc.bond_lambda, 1.0);
  EXPECT_EQ(c.params.pair(0, 1).sigma_c, 3e5);
  EXPECT_EQ(c.params.pair(1, 0).sigma_c, 3e5);
  EXPECT_EQ(c.params.pair(1, 1).sigma_c, 1e6);
  EXPECT_EQ(c.params.wall(0).kb_n, 1e9);  // unused at walls: bonds join discs only
  // The resolved text reads back to the same bonds.
  const Config again = parse_config_text(c.resolved_text);
  ASSERT_TRUE(again.bonds);
  EXPECT_EQ(again.bond_gap, 0.05);
  EXPECT_EQ(again.params.pair(0, 1).sigma_c, 3e5);
  EXPECT_EQ(again.params.pair(1, 1).sigma_spread, 0.2);
}

TEST(ConfigBonds, APairBlockAloneBondsItsPairOnly) {
  const Config c = parse_config_text(kTwo, {"--bonds.cement.cement.kb_n=1e9", "--bonds.cement.cement.kb_s=5e8",
                                            "--bonds.cement.cement.sigma_c=1e6", "--bonds.cement.cement.tau_c=1e6"});
  ASSERT_TRUE(c.bonds);
  EXPECT_EQ(c.params.pair(0, 0).kb_n, 1e9);
  EXPECT_EQ(c.params.pair(0, 1).kb_n, 0.0);
  EXPECT_EQ(c.params.pair(1, 1).kb_n, 0.0);
  EXPECT_TRUE(has(error_of({"--bonds.cement.cement.kb_n=1e9"}), "missing required key 'bonds.cement.cement.kb_s'"));
}

TEST(ConfigBonds, RefusalsNameTheKey) {
  auto with = [](std::string extra) {
    std::vector<std::string> o = kAllPairs;
    o.push_back(std::move(extra));
    return error_of(o);
  };
  EXPECT_TRUE(has(error_of({"--bonds.kb_n=1e9"}), "missing required key 'bonds.kb_s'"));
  EXPECT_TRUE(has(error_of({"--bonds.gap=0.1"}), "missing required key 'bonds.kb_n'"));
  EXPECT_TRUE(has(with("--bonds.kb_n=0"), "bonds.kb_n"));
  EXPECT_TRUE(has(with("--bonds.kb_s=-1"), "bonds.kb_s"));
  EXPECT_TRUE(has(with("--bonds.sigma_c=nan"), "bonds.sigma_c"));
  EXPECT_TRUE(has(with("--bonds.tau_c=inf"), "bonds.tau_c"));
  EXPECT_TRUE(has(with("--bonds.sigma_spread=1"), "bonds.sigma_spread"));
  EXPECT_TRUE(has(with("--bonds.tau_spread=-0.1"), "bonds.tau_spread"));
  EXPECT_TRUE(has(with("--bonds.lambda=0"), "bonds.lambda"));
  EXPECT_TRUE(has(with("--bonds.gap=-0.01"), "bonds.gap"));
  EXPECT_TRUE(has(with("--bonds.cement.grain.kb_n=-5"), "bonds.cement.grain.kb_n"));
  EXPECT_TRUE(has(with("--bonds.cement.wall.grain.kb_n=1e9"), "bonds join discs, not a disc and a wall"));
  EXPECT_TRUE(has(with("--bonds.cement.stone.kb_n=1e9"), "stone"));
  EXPECT_TRUE(has(with("--bonds.kbn=1"), "bonds.kbn"));
}

}  // namespace
}  // namespace rondel
