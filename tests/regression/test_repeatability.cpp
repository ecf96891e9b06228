// The same run twice gives the same bits (docs/design.md section 5).
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>

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

// Every term of a ledger, as bits.
std::string ledger_bits(const EnergyLedger& L) {
  std::string out;
  L.for_each_term([&out](const LedgerTermInfo& t, double v) {
    out += std::string(t.name) + "=" + std::to_string(std::bit_cast<std::uint64_t>(v)) + " ";
  });
  return out + "W_g=" + std::to_string(std::bit_cast<std::uint64_t>(L.W_g));
}

// Simulation::advance defers each step's closing kick into the next step's drift: the same bits as step()
// after step(), in the state and in every ledger term, with local damping (whose kicks book work) and without,
// whatever the chunks; a stop agreed in a step ends the advance there with the state complete.
TEST(Repeatability, AdvanceGivesTheBitsOfSingleSteps) {
  Communicator comm;
  for (const char* damping : {"0", "0.3"}) {
    const std::vector<std::string> overrides{std::string("--run.local_damping=") + damping};
    Simulation ref(parse_config_text(kScene, overrides), comm, false);
    Simulation fused(parse_config_text(kScene, overrides), comm, false);
    const auto no_stop = [] { return std::int64_t{0}; };
    for (const std::int64_t n : {137, 1, 0, 262}) {
      for (std::int64_t s = 0; s < n; ++s) ref.step();
      EXPECT_EQ(fused.advance(n, no_stop), n);
      ASSERT_EQ(fused.step_count(), ref.step_count());
      EXPECT_EQ(fused.state_text(), ref.state_text()) << "local_damping " << damping << ", step " << ref.step_count();
      EXPECT_EQ(ledger_bits(fused.ledger()), ledger_bits(ref.ledger())) << "local_damping " << damping;
    }
    EXPECT_GT(fused.ledger().D_damping, std::string(damping) == "0" ? -1.0 : 0.0);
    // A stop request (a signal: 2 x its number) is agreed in the first step's reduction (one rank reduces
    // every step): the advance returns after it, with the full-step state.
    ref.step();
    EXPECT_EQ(fused.advance(50, [] { return std::int64_t{2 * 15}; }), 1);
    EXPECT_EQ(fused.agreed_stop(), 2 * 15);
    EXPECT_EQ(fused.state_text(), ref.state_text());
    EXPECT_EQ(ledger_bits(fused.ledger()), ledger_bits(ref.ledger()));
  }
}

TEST(Repeatability, DifferentSeedGivesDifferentScene) {
  Communicator comm;
  Simulation a(parse_config_text(kScene), comm, false);
  Simulation b(parse_config_text(kScene, {"--scene.seed=8"}), comm, false);
  EXPECT_NE(a.state_text(), b.state_text());
}

}  // namespace
}  // namespace rondel
