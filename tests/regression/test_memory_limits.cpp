// Memory that is not there: a scene too large for the process limit (ulimit -v) is refused before work,
// naming the limit, although the machine's physical memory would hold it (and the share of a restart's discs
// against a process limit set in-process); an allocation that fails during the
// run (injected: RONDEL_FAULT=alloc, where final.csv is formatted) ends every rank with exit code 6 and one
// message, and the files written before it (the checkpoint, diagnostics.csv) stay complete.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/Errors.hpp"
#include "core/ExitCodes.hpp"
#include "core/MemoryLimit.hpp"
#include "support/Command.hpp"
#include "support/Scenes.hpp"
#include "support/TempDir.hpp"

namespace rondel {
namespace {

namespace fs = std::filesystem;
using test::mpirun_rondel;
using test::occurrences;
using test::Outcome;
using test::quoted;
using test::read_file;
using test::TempDir;

TEST(MemoryLimits, AProcessLimitBelowTheSceneIsFoundBeforeWork) {
  const TempDir dir("rondel-ulimit");
  test::write_file(dir / "box.ini", test::moving_wall_box_ini("wang"));
  // 2,000,000 discs need about 1.2 GB by the estimate: more than 900 MB of address space, far less than this
  // machine's memory. A singleton (no mpirun) under the limit.
  const std::string scene =
      " box.ini --scene.type=lattice_square --scene.nx=2000 --scene.ny=1000 --scene.radius=1e-5 "
      "--scene.spacing=2.1e-5 --scene.x0=1e-5 --scene.y0=1e-5 --run.output=big --run.steps=1";
  const Outcome o =
      test::run_in(dir, test::without_mpi_launch(true),
                   "sh -c 'ulimit -v 900000 && exec " + test::quoted(test::rondel_executable()) + scene + "'");
  EXPECT_EQ(o.exit_code, kExitInput.code) << o.err;
  EXPECT_EQ(occurrences(o.err, "scene.nx x scene.ny: 2e+06 discs need about 1.2 GB"), 1u) << o.err;
  EXPECT_EQ(occurrences(o.err, "the process limit ulimit -v (RLIMIT_AS) of 0.922 GB"), 1u) << o.err;
  EXPECT_FALSE(fs::exists(dir / "big"));
}

TEST(MemoryLimits, TheBoundIsTheTightestLimit) {
  // Without a process limit the bound is at most the physical memory, and names what set it.
  const MemoryBound b = memory_bound();
  ASSERT_GT(b.bytes, 0u);
  EXPECT_LE(b.bytes, physical_memory());
  EXPECT_FALSE(b.source.empty());
  // This process under a soft RLIMIT_AS of what it has mapped plus 100 MB (restored after): 1e6 discs (600 MB by
  // the estimate) are refused naming the limit, 1e5 (60 MB) pass. The check a restart makes with its share.
  rlimit old{};
  ASSERT_EQ(getrlimit(RLIMIT_AS, &old), 0);
  const auto mapped = static_cast<rlim_t>(sysconf(_SC_PAGE_SIZE)) * [] {
    std::ifstream statm("/proc/self/statm");
    rlim_t pages = 0;
    statm >> pages;
    return pages;
  }();
  rlimit tight = old;
  tight.rlim_cur = mapped + (rlim_t{100} << 20);
  if (old.rlim_max != RLIM_INFINITY && tight.rlim_cur > old.rlim_max) GTEST_SKIP() << "a hard limit below the test's";
  ASSERT_EQ(setrlimit(RLIMIT_AS, &tight), 0);
  std::string refused;
  try {
    check_memory(1e6, 0.0, 0.0, "the discs of 'x.h5' over 1 rank(s), per rank");
  } catch (const ConfigError& e) {
    refused = e.what();
  }
  bool small_passes = true;
  try {
    check_memory(1e5, 0.0, 0.0, "a tenth");
  } catch (const ConfigError&) {
    small_passes = false;
  }
  const MemoryBound under = memory_bound();
  ASSERT_EQ(setrlimit(RLIMIT_AS, &old), 0);
  EXPECT_EQ(occurrences(refused, "the discs of 'x.h5' over 1 rank(s), per rank: 1e+06 discs need about 0.6 GB"), 1u)
      << refused;
  EXPECT_EQ(occurrences(refused, "but the process limit ulimit -v (RLIMIT_AS) of "), 1u) << refused;
  EXPECT_TRUE(small_passes);
  EXPECT_LT(under.bytes, std::uint64_t{110} << 20);
}

TEST(MemoryLimits, AnAllocationThatFailsEndsEveryRankWithItsOwnCode) {
  const TempDir dir("rondel-alloc");
  test::write_file(dir / "box.ini", test::moving_wall_box_ini("wang"));
  for (const char* fault : {"alloc", "alloc@1"}) {
    const fs::path run = dir / (std::string("run_") + fault);
    const Outcome o =
        mpirun_rondel(dir, 2, "box.ini --run.steps=30 --output.checkpoint_every=10 --run.output=" + quoted(run),
                      std::string("RONDEL_FAULT=") + fault);
    EXPECT_EQ(o.exit_code, kExitMemory.code) << fault << ": " << o.err;
    EXPECT_EQ(occurrences(o.err, "rondel: out of memory: an allocation failed (std::bad_alloc)"), 1u) << o.err;
    EXPECT_EQ(occurrences(o.err, "rondel: "), 1u) << o.err;
    // What was written before stays whole: the checkpoint of the last step resumes to "nothing to do", the
    // diagnostics reach the last step; no final.csv or summary claims a complete run.
    EXPECT_FALSE(fs::exists(run / "final.csv"));
    EXPECT_FALSE(fs::exists(run / "summary.json"));
    const std::string diag = read_file(run / "diagnostics.csv");
    EXPECT_EQ(diag.substr(diag.rfind('\n', diag.size() - 2) + 1, 3), "30,") << diag;
    const Outcome again = mpirun_rondel(dir, 1, "--resume " + quoted(run));
    EXPECT_EQ(again.exit_code, 0) << again.err;
    EXPECT_EQ(occurrences(again.out, "is at step 30 = run.steps already"), 1u) << again.out;
  }
}

}  // namespace
}  // namespace rondel
