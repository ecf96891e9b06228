// Materials and pair parameters in the configuration (docs/physics.md section 7): [material.NAME] sections,
// pair blocks [BLOCK.A.B] and [BLOCK.A.wall.W] over the run's defaults, the per-pair rolling switch, wall
// materials, the scene's material keys, and the refusals that name the key.
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
[material.steel]
density = 7800
body = sphere
[material.glass]
density = 2500
[linear]
k_n = 1e5
e = 0.8
[coulomb]
k_s = 7.5e4
mu = 0.5
[contact]
rolling = wang
[wang]
k_r = 1e3
mu_r = 0.1
[linear.steel.glass]
k_n = 3e5
zeta = 0.2
[coulomb.glass.wall.steel]
mu = 0.2
[contact.steel.steel]
rolling = false
[walls]
box = bottom left right
material = steel
[scene]
type = lattice_square
nx = 4
ny = 2
radius = 0.005
x0 = 0.01
y0 = 0.01
materials = glass steel
material_fractions = 0.25 0.75
)";

std::string error_of(const std::string& ini, const std::vector<std::string>& overrides = {}) {
  try {
    parse_config_text(ini, overrides);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(ConfigMaterials, NamedMaterialsInNameOrderWithTheirBodies) {
  const Config c = parse_config_text(kTwo);
  ASSERT_EQ(c.materials.size(), 2u);
  EXPECT_EQ(c.materials[0].name, "glass");
  EXPECT_EQ(c.materials[1].name, "steel");
  EXPECT_EQ(c.materials[1].body, Material::Body::sphere);
  EXPECT_EQ(c.materials[0].density, 2500.0);
  EXPECT_EQ(c.walls.at(0).material, 1);
  EXPECT_EQ(c.scene.materials, (std::vector<int>{0, 1}));
}

TEST(ConfigMaterials, PairBlocksOverrideTheDefaultForTheirPairOnly) {
  const Config c = parse_config_text(kTwo);
  const ContactParamTable& t = c.params;
  EXPECT_EQ(t.pair(0, 0).k_n, 1e5) << "glass-glass: the default";
  EXPECT_EQ(t.pair(1, 1).k_n, 1e5);
  EXPECT_EQ(t.pair(0, 1).k_n, 3e5) << "[linear.steel.glass]";
  EXPECT_EQ(t.pair(1, 0).k_n, 3e5) << "a pair is unordered";
  EXPECT_EQ(t.pair(0, 1).zeta_n, 0.2);
  EXPECT_LT(t.pair(0, 1).e_n, 0.0) << "the pair's zeta replaces the default's e";
  EXPECT_EQ(t.pair(0, 0).e_n, 0.8);
  EXPECT_EQ(t.pair(0, 1).mu, 0.5) << "keys not in the pair block keep the default";
  EXPECT_EQ(t.wall(0, 1).mu, 0.2) << "[coulomb.glass.wall.steel]";
  EXPECT_EQ(t.wall(1, 1).mu, 0.5);
  EXPECT_EQ(t.wall(0, 0).mu, 0.5);
  EXPECT_FALSE(t.pair(1, 1).rolling) << "[contact.steel.steel] rolling = false";
  EXPECT_TRUE(t.pair(0, 1).rolling);
  EXPECT_EQ(t.pair(1, 1).k_r, 1e3);
}

TEST(ConfigMaterials, OldSingleMaterialKeysGiveOneDefaultMaterial) {
  std::string ini = kTwo;
  ini = ini.substr(0, ini.find("[material.steel]")) + "[material]\ndensity = 3000\n" +
        ini.substr(ini.find("[linear]"), ini.find("[linear.steel.glass]") - ini.find("[linear]")) +
        "[walls]\nbox = bottom\n[scene]\ntype = lattice_square\nnx = 2\nny = 1\nradius = 0.005\nx0 = 0.01\ny0 = "
        "0.01\n";
  const Config c = parse_config_text(ini);
  ASSERT_EQ(c.materials.size(), 1u);
  EXPECT_EQ(c.materials[0].name, "default");
  EXPECT_EQ(c.materials[0].density, 3000.0);
  EXPECT_EQ(c.params.n_materials(), 1u);
  // The resolved text reads back to the same configuration (checkpoints and --resume use it).
  EXPECT_EQ(parse_config_text(c.resolved_text).resolved_text, c.resolved_text);
}

TEST(ConfigMaterials, ResolvedTextOfSeveralMaterialsReadsBack) {
  const Config c = parse_config_text(kTwo);
  EXPECT_NE(c.resolved_text.find("[material.glass]\ndensity = 2500"), std::string::npos) << c.resolved_text;
  EXPECT_NE(c.resolved_text.find("[linear.steel.glass]\n"), std::string::npos);
  EXPECT_EQ(c.resolved_text.find("[material]\n"), std::string::npos) << "no stale single-material section";
  const Config back = parse_config_text(c.resolved_text);
  EXPECT_EQ(back.resolved_text, c.resolved_text);
  EXPECT_EQ(back.params.pair(0, 1).k_n, 3e5);
}

TEST(ConfigMaterials, RefusalsNameTheKeyOrSection) {
  EXPECT_NE(error_of(kTwo, {"--linear.glass.wood.k_n=1"}).find("section [linear.glass.wood] names the material 'wood'"),
            std::string::npos);
  EXPECT_NE(error_of(kTwo, {"--linear.glass.steel.k_n=1"}).find("the pair is given twice"), std::string::npos);
  EXPECT_NE(error_of(kTwo, {"--material.density=1"}).find("key 'material.density'"), std::string::npos);
  EXPECT_NE(error_of(kTwo, {"--walls.material=wood"}).find("key 'walls.material' names the material 'wood'"),
            std::string::npos);
  EXPECT_NE(error_of(kTwo, {"--scene.materials=glass wood"}).find("key 'scene.materials'"), std::string::npos);
  EXPECT_NE(error_of(kTwo, {"--scene.material_fractions=0.5 0.6"}).find("must sum to 1"), std::string::npos);
  EXPECT_NE(error_of(kTwo, {"--material.glass.body=cube"}).find("key 'material.glass.body'"), std::string::npos);
  EXPECT_NE(error_of(kTwo, {"--material.steel.thickness=2"}).find("key 'material.steel.thickness'"), std::string::npos);
  EXPECT_NE(error_of(kTwo, {"--linear.glass.glass.k_n=-1"}).find("key 'linear.glass.glass.k_n'"), std::string::npos);
  EXPECT_NE(error_of(kTwo, {"--linear.glass.glass.kn=1"}).find("linear.glass.glass.kn"), std::string::npos);
  EXPECT_NE(error_of(kTwo, {"--jiang.glass.glass.delta=1"}).find("jiang.glass.glass.delta"), std::string::npos)
      << "a pair block of a law that is not selected";
  std::string no_coulomb = kTwo;
  no_coulomb.erase(no_coulomb.find("[coulomb]\n"), std::string("[coulomb]\nk_s = 7.5e4\nmu = 0.5\n").size());
  no_coulomb.erase(no_coulomb.find("[coulomb.glass"), std::string("[coulomb.glass.wall.steel]\nmu = 0.2\n").size());
  EXPECT_NE(
      error_of(no_coulomb, {"--contact.tangential=mindlin", "--mindlin.mu=0.5"}).find("needs contact.normal = hertz"),
      std::string::npos);
}

TEST(ConfigMaterials, HertzNeedsTheElasticConstantsOfEveryMaterial) {
  std::string ini = kTwo;
  for (const char* block : {"[linear]\nk_n = 1e5\ne = 0.8\n", "[linear.steel.glass]\nk_n = 3e5\nzeta = 0.2\n"})
    ini.erase(ini.find(block), std::string(block).size());
  const std::vector<std::string> hertz{"--contact.normal=hertz", "--hertz.e=0.5"};
  EXPECT_NE(error_of(ini, hertz).find("missing required key 'material.glass.youngs_modulus'"), std::string::npos);
  std::vector<std::string> all = hertz;
  for (const char* m : {"glass", "steel"})
    all.insert(all.end(), {std::string("--material.") + m + ".youngs_modulus=7e10",
                           std::string("--material.") + m + ".poisson_ratio=0.25"});
  EXPECT_EQ(error_of(ini, all), "accepted");
  all.back() = "--material.steel.poisson_ratio=0.5";
  EXPECT_NE(error_of(ini, all).find("key 'material.steel.poisson_ratio'"), std::string::npos);
}

TEST(ConfigMaterials, HelpListsTheMaterialAndPairKeys) {
  const std::string help = config_help();
  for (const char* key :
       {"material.NAME.density", "material.NAME.body", "material.NAME.youngs_modulus", "material.poisson_ratio",
        "contact.A.B.rolling", "walls.material", "walls.materials", "walls.rough_materials", "scene.materials",
        "scene.material_fractions", "scene.material_by", "scene.material_radius_min", "scene.size_materials",
        "run.accept_materials", "hertz.e", "mindlin.mu"})
    EXPECT_NE(help.find(key), std::string::npos) << key;
}

}  // namespace
}  // namespace rondel
