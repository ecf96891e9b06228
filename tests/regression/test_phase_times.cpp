// Phase times (app/PhaseTimes.hpp): every phase of a run is booked, comm_seconds() is the communication
// phase, and the summary of a run with files carries the phase line.
#include <gtest/gtest.h>

#include <string>

#include "app/Simulation.hpp"
#include "support/TempDir.hpp"

namespace rondel {
namespace {

const char* kScene = R"(
[run]
steps = 60
[diagnostics]
every = 20
[domain]
xlo = 0
xhi = 0.1
ylo = 0
yhi = 0.1
[gravity]
y = -9.81
[linear]
k_n = 1e6
e = 0.5
[coulomb]
k_s = 7.5e5
mu = 0.5
[walls]
box = bottom left right
[scene]
type = random
count = 40
radius_min = 0.004
radius_max = 0.006
seed = 3
)";

TEST(PhaseTimes, StepsBookForceNeighbourCommunicationAndIntegrate) {
  Communicator comm;
  Simulation sim(parse_config_text(kScene), comm, false);
  const PhaseTimes before = sim.phases();
  for (int s = 0; s < 50; ++s) sim.step();
  const PhaseTimes& after = sim.phases();
  for (auto p : {PhaseTimes::force, PhaseTimes::neighbour, PhaseTimes::communication, PhaseTimes::integrate})
    EXPECT_GT(after.seconds(p), before.seconds(p)) << PhaseTimes::name(p);
  EXPECT_EQ(after.seconds(PhaseTimes::output), before.seconds(PhaseTimes::output)) << "step() writes nothing";
  EXPECT_EQ(sim.comm_seconds(), after.seconds(PhaseTimes::communication));
}

TEST(PhaseTimes, LineNamesEveryPhaseWithItsShare) {
  PhaseTimes start, t;
  t.restart();
  t.lap(PhaseTimes::force);
  const std::string line = t.line_since(start);
  EXPECT_EQ(line.rfind("phases: force ", 0), 0u) << line;
  for (const char* name : {"neighbour", "communication", "integrate", "output", "other"})
    EXPECT_NE(line.find(std::string(", ") + name + " "), std::string::npos) << line;
  EXPECT_NE(line.find("force 100 %"), std::string::npos) << line;
}

TEST(PhaseTimes, SummaryOfARunCarriesThePhaseLine) {
  Communicator comm;
  test::TempDir dir("rondel-phases");
  const std::string out = (dir / "run").string();
  Simulation sim(parse_config_text(kScene, {"--run.output=" + out, "--run.progress=false"}), comm, true);
  sim.run();
  const std::string summary = test::read_file(dir / "run" / "summary.txt");
  EXPECT_NE(summary.find("\nphases: force "), std::string::npos) << summary;
  EXPECT_NE(summary.find("status: complete"), std::string::npos) << summary;
  EXPECT_NE(test::read_file(dir / "run" / "log.txt").find("\nphases: force "), std::string::npos);
}

}  // namespace
}  // namespace rondel
