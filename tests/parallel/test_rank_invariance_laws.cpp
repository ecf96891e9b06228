// Rank invariance of the normal laws other than linear (docs/validation.md sections 8, 9 and 14): a run on N ranks
// gives the bits of the 1-rank run with every partitioner and with forced rebalancing (check_scene,
// ParallelTestUtil.hpp), with per-pair parameters of two materials.
#include <gtest/gtest.h>

#include <string>

#include "ParallelTestUtil.hpp"

namespace rondel {
namespace {

using namespace partest;

// 1. (d) Two materials with Hertz-Mindlin contacts and the Wang rolling law with per-pair parameters: a
// bidisperse deposition (glass and heavier steel discs, each with its own radius range) onto steel walls.
TEST(RankInvariance, TwoMaterialHertzMindlinDepositionBitwiseEqualToOneRank) {
  const std::string ini = R"(
[domain]
xlo = 0
xhi = 0.06
ylo = 0
yhi = 0.12
[gravity]
y = -9.81
[material.glass]
density = 2500
youngs_modulus = 1e10
poisson_ratio = 0.25
[material.steel]
density = 7800
youngs_modulus = 2e10
poisson_ratio = 0.3
[contact]
normal = hertz
tangential = mindlin
rolling = wang
[hertz]
e = 0.6
[hertz.glass.steel]
e = 0.4
[mindlin]
mu = 0.5
[mindlin.glass.wall.steel]
mu = 0.2
[wang]
k_r = 2e5
mu_r = 0.1
[wang.steel.steel]
mu_r = 0.02
[walls]
box = bottom left right
material = steel
[scene]
type = random
count = 200
materials = glass steel
material_fractions = 0.5 0.5
material_by = area
material_radius_min = 0.0015 0.002
material_radius_max = 0.0025 0.003
seed = 11
vy = -0.5
)";
  check_scene("two-material hertz", ini, 8000, 500, true);
}

// 1. (d') Walton-Braun contacts, whose rows carry their largest overlap u_max through builds, migrations and
// ghosts, with per-pair unloading (e, or K2 given) and jiang_plastic rolling (K_m from K1): a bidisperse deposition
// onto steel walls.
TEST(RankInvariance, WaltonBraunDepositionBitwiseEqualToOneRank) {
  const std::string ini = R"(
[domain]
xlo = 0
xhi = 0.06
ylo = 0
yhi = 0.12
[gravity]
y = -9.81
[material.glass]
density = 2500
[material.steel]
density = 7800
[contact]
normal = walton_braun
rolling = jiang_plastic
[walton_braun]
K1 = 2e6
e = 0.6
[walton_braun.glass.steel]
K2 = 1.2e7
[walton_braun.glass.wall.steel]
e = 0.3
[coulomb]
k_s = 1.5e6
mu = 0.5
[jiang]
delta = 0.4
[walls]
box = bottom left right
material = steel
[scene]
type = random
count = 200
materials = glass steel
material_fractions = 0.5 0.5
material_by = area
material_radius_min = 0.0015 0.002
material_radius_max = 0.0025 0.003
seed = 12
vy = -0.5
)";
  check_scene("walton-braun", ini, 6000, 500, true);
}

}  // namespace
}  // namespace rondel
