#pragma once
// Test support: INI snippets shared by several tests' scenes. The text is what the tests wrote before,
// so the parsed configurations (and every result) are unchanged.
#include <string>

namespace rondel::test {

// Gravity and the contact set of the falling-disc scenes: k_n = 1e7, e = 0.5, k_s = 7.5e6, mu = 0.5.
inline std::string falling_contacts_ini() {
  return R"([gravity]
y = -9.81
[linear]
k_n = 1e7
e = 0.5
[coulomb]
k_s = 7.5e6
mu = 0.5
)";
}

// contact.rolling = `law` and its parameter block: wang (k_r = 2e6, mu_r = 0.1) or a Jiang law (delta 0.5).
inline std::string rolling_law_ini(const std::string& law) {
  const std::string block = law == "wang" ? "[wang]\nk_r = 2e6\nmu_r = 0.1\n" : "[jiang]\ndelta = 0.5\n";
  return "[contact]\nrolling = " + law + "\n" + block;
}

// 130 discs dropped into a 5 cm box (bottom and right walls) whose left wall is a line moving into the pile
// at 0.4 m/s, with gravity, Coulomb friction and a rolling law with history. `extra`: more sections
// (placed after [run]).
inline std::string moving_wall_box_ini(const std::string& law, const std::string& extra = "") {
  return "\n[run]\nprogress = false\n" + extra + R"([domain]
xlo = 0
xhi = 0.05
ylo = 0
yhi = 0.05
)" + falling_contacts_ini() +
         rolling_law_ini(law) + R"(
[walls]
box = bottom right
lines = 0 0 1 0 0.4 0
[scene]
type = random
count = 130
region = 0.0005 0.05 0 0.04
radius_min = 0.001
radius_max = 0.0018
seed = 7
vy = -0.5
omega = 30
)";
}

}  // namespace rondel::test
