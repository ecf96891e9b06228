// The same run twice gives the same bits (docs/design.md section 5).
#include <gtest/gtest.h>

#include "app/Simulation.hpp"
#include "support/Scenes.hpp"

namespace rondel {
namespace {

const std::string kScene = R"(
[run]
steps = 400
[domain]
xlo = 0
xhi = 0.2
ylo = 0
yhi = 0.3
)" + test::falling_contacts_ini() +
                           R"([walls]
box = bottom left right
[scene]
type = random
count = 300
radius_min = 0.002
radius_max = 0.005
seed = 7
)";

TEST(Repeatability, SameRunTwiceGivesSameBits) {
  Communicator comm;
  std::string first, second;
  for (std::string* out : {&first, &second}) {
    Simulation sim(parse_config_text(kScene), comm, false);
    for (int s = 0; s < 400; ++s) sim.step();
    *out = sim.state_text();
  }
  EXPECT_EQ(first, second);
  EXPECT_GT(first.size(), 300u * 20u);
}

TEST(Repeatability, DifferentSeedGivesDifferentScene) {
  Communicator comm;
  Simulation a(parse_config_text(kScene), comm, false);
  Simulation b(parse_config_text(kScene, {"--scene.seed=8"}), comm, false);
  EXPECT_NE(a.state_text(), b.state_text());
}

}  // namespace
}  // namespace rondel
