// Two materials in one scene (docs/validation.md section 9): the pair parameter table read, mixed and applied.
//  - A light and a heavy disc (a csv scene with a material column) in a linear head-on impact, the pair's own
//    k_n given by [linear.light.heavy]: contact time pi sqrt(m_eff/k_pair) and the elastic-collision velocities
//    ((m1 - m2) v1 + 2 m2 v2)/(m1 + m2) from the two bodies' own masses.
//  - An impact of unlike Hertz materials: the largest overlap (15 m_eff v0^2/(16 E* sqrt(R*)))^(2/5) with the
//    mixed E* of docs/physics.md section 6.
//  - A lattice scene by fractions: exact counts, and each disc's mass and inertia from its material's body.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "app/Simulation.hpp"
#include "core/Errors.hpp"
#include "physics/PairConstants.hpp"
#include "support/Format.hpp"
#include "support/TempDir.hpp"

namespace rondel {
namespace {

namespace fs = std::filesystem;
using test::num;

constexpr double kR = 0.005, kV0 = 1.0;

struct TwoDiscRun {
  double m_light = 0.0, m_heavy = 0.0, v_light = 0.0, v_heavy = 0.0, t_contact = 0.0, u_max = 0.0;
};

// Disc 0 (light) at the left moving right at v0, disc 1 (heavy) at rest; one rank.
TwoDiscRun two_discs(const std::string& ini, const std::vector<std::string>& overrides, double dt) {
  test::TempDir dir("rondel-test-materials");
  const fs::path csv = dir.path() / "pair.csv";
  {
    std::ofstream f(csv);
    f.precision(17);
    f << "id,x,y,radius,vx,vy,omega,material\n";
    f << "0," << -(kR + kV0 * dt) << ",0," << kR << "," << kV0 << ",0,0,light\n";
    f << "1," << kR << ",0," << kR << ",0,0,0,heavy\n";
  }
  std::vector<std::string> all{"--scene.file=" + csv.string(), "--run.dt=" + num(dt)};
  all.insert(all.end(), overrides.begin(), overrides.end());
  Communicator comm;
  Simulation sim(parse_config_text(ini, all), comm, false);
  const DiscStore& D = sim.discs();
  const std::size_t l = D.gid[0] == 0 ? 0 : 1, h = 1 - l;
  TwoDiscRun r;
  r.m_light = D.mass[l], r.m_heavy = D.mass[h];
  bool touched = false;
  for (int s = 0; s < 200000; ++s) {
    sim.step();
    const std::size_t a = D.gid[0] == 0 ? 0 : 1, b = 1 - a;
    const double u = 2 * kR - (D.position[b].x - D.position[a].x);
    r.u_max = std::max(r.u_max, u);
    if (u > 0.0) r.t_contact += dt, touched = true;
    if (touched && u < -2 * kV0 * dt) break;
  }
  const std::size_t a = D.gid[0] == 0 ? 0 : 1;
  r.v_light = D.velocity[a].x, r.v_heavy = D.velocity[1 - a].x;
  return r;
}

const std::string kLinear = R"(
[domain]
xlo = -0.05
xhi = 0.05
ylo = -0.05
yhi = 0.05
[material.light]
density = 2500
[material.heavy]
density = 7800
[contact]
tangential = none
[linear]
k_n = 1e7
[linear.light.heavy]
k_n = 4e7
[scene]
type = csv
)";

TEST(Materials, LightAndHeavyDiscUseThePairStiffnessAndTheirOwnMasses) {
  const double m1 = 2500 * std::numbers::pi * kR * kR, m2 = 7800 * std::numbers::pi * kR * kR;
  const double m_eff = m1 * m2 / (m1 + m2), k_pair = 4e7;
  const double t_c = std::numbers::pi * std::sqrt(m_eff / k_pair), dt = t_c / 400;
  const TwoDiscRun r = two_discs(kLinear, {}, dt);
  EXPECT_EQ(r.m_light, m1);
  EXPECT_EQ(r.m_heavy, m2);
  EXPECT_NEAR(r.t_contact, t_c, 2 * dt) << "the pair's k_n = 4e7, not the default 1e7 (t_c would be twice)";
  EXPECT_NEAR(r.v_light, (m1 - m2) / (m1 + m2) * kV0, 1e-4);
  EXPECT_NEAR(r.v_heavy, 2 * m1 / (m1 + m2) * kV0, 1e-4);
  // Without the pair block the default applies.
  std::string ini = kLinear;
  ini.erase(ini.find("[linear.light.heavy]"), std::string("[linear.light.heavy]\nk_n = 4e7\n").size());
  const TwoDiscRun d = two_discs(ini, {}, dt);
  EXPECT_NEAR(d.t_contact, std::numbers::pi * std::sqrt(m_eff / 1e7), 2 * dt);
}

TEST(Materials, ImpactOfUnlikeHertzMaterialsUsesTheMixedModulus) {
  const std::string ini = R"(
[domain]
xlo = -0.05
xhi = 0.05
ylo = -0.05
yhi = 0.05
[material.light]
density = 2650
youngs_modulus = 7e10
poisson_ratio = 0.25
[material.heavy]
density = 7800
youngs_modulus = 2e11
poisson_ratio = 0.3
[contact]
normal = hertz
tangential = mindlin
[hertz]
e = 1
[mindlin]
mu = 0.5
[scene]
type = csv
)";
  Material a, b;
  a.youngs_modulus = 7e10, a.poisson_ratio = 0.25, b.youngs_modulus = 2e11, b.poisson_ratio = 0.3;
  const double E_star = 1.0 / ((1 - 0.0625) / 7e10 + (1 - 0.09) / 2e11);
  ASSERT_NEAR(effective_modulus(a, b), E_star, 1e-12 * E_star);
  const double m1 = 2650 * std::numbers::pi * kR * kR, m2 = 7800 * std::numbers::pi * kR * kR;
  const double m_eff = m1 * m2 / (m1 + m2);
  const double u_max = std::pow(15 * m_eff * kV0 * kV0 / (16 * E_star * std::sqrt(0.5 * kR)), 0.4);
  const double t_c = 2 * u_max / kV0 * std::sqrt(std::numbers::pi) * std::tgamma(1.4) / std::tgamma(0.9);
  const TwoDiscRun r = two_discs(ini, {"--run.force_dt=true"}, t_c / 100);
  EXPECT_NEAR(r.u_max, u_max, 1e-3 * u_max);
  EXPECT_NEAR(r.v_light, (m1 - m2) / (m1 + m2) * kV0, 1e-3);
}

TEST(Materials, LatticeFractionsGiveExactCountsAndEachBodyItsMass) {
  const std::string ini = R"(
[domain]
xlo = 0
xhi = 0.2
ylo = 0
yhi = 0.2
[material.glass]
density = 2500
[material.steel]
density = 7800
body = sphere
[linear]
k_n = 1e5
[coulomb]
k_s = 7.5e4
mu = 0.5
[scene]
type = lattice_square
nx = 10
ny = 10
radius = 0.005
x0 = 0.01
y0 = 0.01
materials = glass steel
material_fractions = 0.3 0.7
)";
  Communicator comm;
  Simulation sim(parse_config_text(ini), comm, false);
  const DiscStore& D = sim.discs();
  int n[2] = {0, 0};
  for (std::size_t i = 0; i < D.n_owned(); ++i) {
    ++n[D.material[i]];
    if (D.material[i] == 0) {
      EXPECT_EQ(D.mass[i], 2500 * std::numbers::pi * kR * kR);
    } else {
      const double m = 4.0 / 3.0 * std::numbers::pi * 7800 * kR * kR * kR;
      EXPECT_NEAR(D.mass[i], m, 1e-15 * m);
      EXPECT_NEAR(D.inertia[i], 0.4 * m * kR * kR, 1e-15 * 0.4 * m * kR * kR);
    }
  }
  EXPECT_EQ(n[0], 30);
  EXPECT_EQ(n[1], 70);
  // The critical step is searched over every pair that occurs and names it.
  EXPECT_NE(sim.critical().pair.find("material "), std::string::npos) << sim.critical().pair;
}

const std::string kRandom = R"(
[run]
progress = false
[domain]
xlo = 0
xhi = 0.1
ylo = 0
yhi = 0.1
[material.glass]
density = 2500
[material.steel]
density = 7800
[linear]
k_n = 1e5
[coulomb]
k_s = 7.5e4
mu = 0.5
[walls]
box = bottom left right
rough = bottom
rough_depth = 0.004
rough_materials = bottom:steel
[scene]
type = random
count = 300
distribution = list
sizes = 0.002 0.0015
fractions = 0.25 0.75
size_materials = steel glass
)";

// A random scene by a size list with a material per size, and the discs glued to a rough wall taking that
// wall's material.
TEST(Materials, SizeListAndRoughWallAssignMaterials) {
  Communicator comm;
  Simulation sim(parse_config_text(kRandom), comm, false);
  const DiscStore& D = sim.discs();
  int glued = 0, glued_steel = 0;
  for (std::size_t i = 0; i < D.n_owned(); ++i) {
    if (is_attached(D.flags[i])) {
      ++glued;
      glued_steel += D.material[i] == 1;
      EXPECT_EQ(D.mass[i], 7800 * std::numbers::pi * D.radius[i] * D.radius[i]);
    } else {
      EXPECT_EQ(D.material[i], D.radius[i] == 0.002 ? 1 : 0) << "the material of its size";
    }
  }
  EXPECT_GT(glued, 0);
  EXPECT_EQ(glued_steel, glued) << "walls.rough_materials = bottom:steel";
}

// Area fractions with a radius range per material: counts n_k proportional to f_k / <R^2>_k.
TEST(Materials, AreaFractionsWithRadiusRangesPerMaterial) {
  std::string ini = kRandom;
  ini = ini.substr(0, ini.find("distribution = list")) +
        "materials = glass steel\nmaterial_fractions = 0.5 0.5\nmaterial_by = area\n"
        "material_radius_min = 0.001 0.002\nmaterial_radius_max = 0.002 0.003\n";
  for (const char* line : {"rough = bottom\n", "rough_depth = 0.004\n", "rough_materials = bottom:steel\n"})
    ini.erase(ini.find(line), std::string(line).size());
  Communicator comm;
  Simulation sim(parse_config_text(ini), comm, false);
  const DiscStore& D = sim.discs();
  const double g = (1 + 2 + 4) / 3.0, s = (4 + 6 + 9) / 3.0;  // <R^2> in mm^2 (uniform radius)
  const double n_glass = 300 * (0.5 / g) / (0.5 / g + 0.5 / s);
  int n[2] = {0, 0};
  for (std::size_t i = 0; i < D.n_owned(); ++i) {
    ++n[D.material[i]];
    const double lo = D.material[i] == 0 ? 0.001 : 0.002;
    EXPECT_GE(D.radius[i], lo);
    EXPECT_LE(D.radius[i], lo + 0.001);
  }
  EXPECT_NEAR(n[0], n_glass, 0.5 + 1e-9) << "exact counts by largest remainder";
  EXPECT_EQ(n[0] + n[1], 300);
}

// A restart refuses a material table that differs from the checkpoint's, unless run.accept_materials; then the
// discs keep their material index and take mass and inertia from the new table.
TEST(Materials, RestartRefusesADifferentMaterialTableUnlessAsked) {
  test::TempDir dir("rondel-test-materials-restart");
  const std::string out = "--run.output=" + (dir.path() / "run").string();
  std::string checkpoint;
  Communicator comm;
  {
    Simulation sim(parse_config_text(kRandom, {out, "--run.steps=10"}), comm, true);
    for (int s = 0; s < 10; ++s) sim.step();
    checkpoint = sim.write_checkpoint();
  }
  const std::vector<std::string> same{out, "--run.overwrite=true"};
  EXPECT_NO_THROW(Simulation(parse_config_text(kRandom, same), comm, true, checkpoint));
  std::vector<std::string> denser = same;
  denser.push_back("--material.glass.density=2600");
  try {
    Simulation(parse_config_text(kRandom, denser), comm, true, checkpoint);
    ADD_FAILURE() << "a different material table was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("material table"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("run.accept_materials"), std::string::npos) << e.what();
  }
  denser.push_back("--run.accept_materials=true");
  Simulation sim(parse_config_text(kRandom, denser), comm, true, checkpoint);
  const DiscStore& D = sim.discs();
  for (std::size_t i = 0; i < D.n_owned(); ++i)
    if (D.material[i] == 0) {
      EXPECT_EQ(D.mass[i], 2600 * std::numbers::pi * D.radius[i] * D.radius[i]);
    }
}

}  // namespace
}  // namespace rondel
