// What each rank needs to build its own block of a lattice (core/SceneBuilder.hpp): a keyed permutation that is a
// bijection, and material slots with the exact counts of the fractions, each computed for one site alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/Config.hpp"
#include "core/SceneBuilder.hpp"
#include "core/SceneTypes.hpp"
#include "physics/LawRegistry.hpp"

namespace rondel {
namespace {

TEST(SceneBlocks, TheKeyedPermutationIsABijectionOfEverySize) {
  for (std::uint64_t n : {1u, 2u, 3u, 5u, 64u, 100u, 1000u, 4097u, 65536u}) {
    std::vector<std::uint64_t> image(n);
    for (std::uint64_t k = 0; k < n; ++k) image[k] = scene::keyed_permutation(k, n, 12345);
    std::vector<std::uint64_t> sorted = image;
    std::sort(sorted.begin(), sorted.end());
    for (std::uint64_t k = 0; k < n; ++k) ASSERT_EQ(sorted[k], k) << "n = " << n;
    if (n >= 100) {
      std::uint64_t fixed = 0;
      for (std::uint64_t k = 0; k < n; ++k) fixed += image[k] == k;
      EXPECT_LT(fixed, n / 10) << "n = " << n << ": hardly a shuffle";
      EXPECT_NE(image, [&] {
        std::vector<std::uint64_t> other(n);
        for (std::uint64_t k = 0; k < n; ++k) other[k] = scene::keyed_permutation(k, n, 54321);
        return other;
      }()) << "another key, the same order";
    }
  }
}

TEST(SceneBlocks, ALatticesMaterialsHaveTheExactCountsOfTheirFractions) {
  const Config c = parse_config_text(R"(
[domain]
xlo = 0
xhi = 1
ylo = 0
yhi = 1
[linear]
k_n = 1e6
[coulomb]
k_s = 7.5e5
mu = 0.5
[material.a]
density = 2650
[material.b]
density = 7800
[material.c]
density = 1000
[scene]
type = lattice_square
nx = 37
ny = 23
radius = 0.005
spacing = 0.02
x0 = 0.01
y0 = 0.01
materials = a b c
material_fractions = 0.5 0.3 0.2
)");
  const SceneInputs in{c.scene, c.domain, "", nullptr};
  const auto whole = build_scene(in);
  ASSERT_EQ(whole.size(), 851u);
  std::vector<int> count(3, 0);
  for (const auto& d : whole) ++count[static_cast<std::size_t>(d.material)];
  EXPECT_EQ(count, (std::vector<int>{426, 255, 170})) << "851 x (0.5, 0.3, 0.2), largest remainder";
  // Any cut into blocks gives the same discs.
  for (int ranks : {2, 3, 7}) {
    std::size_t k = 0;
    for (int r = 0; r < ranks; ++r)
      for (const auto& d : build_scene_block(in, r, ranks)) {
        ASSERT_EQ(d.gid, whole[k].gid);
        EXPECT_EQ(d.material, whole[k].material) << "disc " << d.gid << " in " << ranks << " blocks";
        ++k;
      }
    EXPECT_EQ(k, whole.size());
  }
}

}  // namespace
}  // namespace rondel
