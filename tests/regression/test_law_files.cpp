// The conformance harness's checkpoint round trip (tests/physics/test_law_conformance.cpp has the rest): every law
// of the registry, with its example parameters, in a small falling pile; a checkpoint written in the middle of the
// run restarts to the same bits as the uninterrupted run, so the law's history slots travel through the file
// exactly. A law added to the registry is run here without an edit of this file.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "app/Checkpointing.hpp"
#include "app/Simulation.hpp"
#include "physics/LawRegistry.hpp"
#include "support/Assertions.hpp"
#include "support/Quiet.hpp"
#include "support/TempDir.hpp"

namespace rondel {
namespace {

namespace fs = std::filesystem;

// A law of the registry, by kind.
struct Law {
  const LawKind* kind;
  const LawInfo* info;
};
void PrintTo(const Law& law, std::ostream* os) { *os << law.kind->kind << " " << law.info->keyword; }

std::vector<Law> every_law() {
  std::vector<Law> out;
  for (const LawKind* kind : law_catalog().kinds())
    for (const LawInfo& info : kind->laws) out.push_back({kind, &info});
  return out;
}

// 50 touching discs of 5 mm stacked in a box, spun and pushed sideways (1200 steps, a checkpoint at 600), with the
// reference contact of the laws' examples (docs/developing.md), and `law` selected with its examples (and the normal
// law and elastic constants it needs).
std::vector<std::string> overrides_for(const Law& law) {
  const LawCatalog& catalog = law_catalog();
  std::vector<std::string> out{"--contact." + std::string(law.kind->kind) + "=" + law.info->keyword};
  const LawInfo* normal =
      law.kind == &catalog.normal ? law.info : catalog.normal.find(catalog.normal.laws.front().keyword);
  if (law.info->needs_normal) {
    out.push_back("--contact.normal=" + std::string(law.info->needs_normal));
    normal = catalog.normal.find(law.info->needs_normal);
  }
  const LawBlock* tangential = law.kind == &catalog.tangential ? nullptr : catalog.tangential.laws.front().block;
  for (const LawBlock* block : {normal->block, normal == law.info ? nullptr : law.info->block, tangential})
    if (block)
      for (const std::string& o : block->example_options()) out.push_back(o);
  if (normal->elastic || law.info->elastic)
    out.insert(out.end(), {"--material.youngs_modulus=1e9", "--material.poisson_ratio=0.25"});  // soft: the pile stays
  return out;
}

const char* const kPile = R"(
[run]
steps = 1200
progress = false
[domain]
xlo = 0
xhi = 0.12
ylo = 0
yhi = 0.12
[gravity]
y = -9.81
[walls]
box = bottom left right
[scene]
type = lattice_hex
nx = 10
ny = 5
radius = 0.005
spacing = 0.00999
x0 = 0.006
y0 = 0.005
vx = 0.2
omega = 40
)";

class LawFiles : public ::testing::TestWithParam<Law> {};

TEST_P(LawFiles, ACheckpointInTheMiddleRestartsToTheSameBits) {
  const Law law = GetParam();
  const Communicator self(MPI_COMM_SELF);
  const test::TempDir dir("rondel-law-files");
  std::vector<std::string> overrides = overrides_for(law);
  std::string uninterrupted;
  {
    Simulation sim(parse_config_text(kPile, overrides), self, false);
    for (int s = 0; s < 1200; ++s) sim.step();
    uninterrupted = sim.state_text();
  }
  {
    std::vector<std::string> first_half = overrides;
    first_half.insert(first_half.end(), {"--run.steps=600", "--run.output=" + (dir / "run").string()});
    test::QuietCout quiet;
    Simulation first(parse_config_text(kPile, first_half), self, true);
    first.run();
  }
  const fs::path checkpoint = dir / "run" / Checkpointing::file_name("checkpoint", 600);
  ASSERT_TRUE(fs::is_regular_file(checkpoint)) << checkpoint;
  overrides.push_back("--run.output=" + (dir / "resumed").string());
  Simulation resumed(parse_config_text(kPile, overrides), self, true, checkpoint.string());
  // The pile touches at the checkpoint: the round trip carries contacts with their history.
  std::size_t loaded = 0;
  for (std::size_t r = 0; r < resumed.pairs().size(); ++r) loaded += resumed.pairs().F_n[r] > 0.0 ? 1 : 0;
  EXPECT_GE(loaded, 10u) << "contacts at the checkpoint";
  for (int s = 0; s < 600; ++s) resumed.step();
  EXPECT_EQ(test::first_difference(uninterrupted, resumed.state_text(), "uninterrupted", "restarted"), "");
}

INSTANTIATE_TEST_SUITE_P(EveryLaw, LawFiles, ::testing::ValuesIn(every_law()),
                         [](const ::testing::TestParamInfo<Law>& i) {
                           return std::string(i.param.kind->kind) + "_" + i.param.info->keyword;
                         });

}  // namespace
}  // namespace rondel
