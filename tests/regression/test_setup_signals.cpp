// A stop signal during set-up (RONDEL_FAULT=setup_pause holds set-up before its first write until the signal
// comes): every rank exits 10 with one message and nothing written; a fresh run leaves no directory (the same
// command then runs), a resumed one leaves its directory byte for byte (a --resume then ends in the bits of an
// uninterrupted run). SIGUSR1 through mpirun on 2 ranks, SIGTERM to a singleton.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/ExitCodes.hpp"
#include "support/Command.hpp"
#include "support/Scenes.hpp"
#include "support/TempDir.hpp"

namespace rondel {
namespace {

namespace fs = std::filesystem;
using test::occurrences;
using test::Outcome;
using test::quoted;
using test::read_file;
using test::TempDir;

// `rondel ARGS` held in set-up (RONDEL_FAULT=setup_pause), sent `signal` after a second: under mpirun on
// `ranks` ranks (the launcher passes SIGUSR1 on), or as a singleton when `ranks` is 0.
Outcome signalled_in_setup(const TempDir& dir, int ranks, const std::string& signal, const std::string& args) {
  std::string env = test::without_mpi_launch(true) + " RONDEL_FAULT=setup_pause";
  std::string launch = quoted(test::rondel_executable()) + " " + args;
  if (ranks > 0) {
    env += " OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1";
    launch = "mpirun -n " + std::to_string(ranks) + " --oversubscribe " + launch;
  }
  return test::run_in(dir, env, "sh -c \"" + launch + " & p=\\$!; sleep 1.5; kill -" + signal + " \\$p; wait \\$p\"");
}

TEST(SetupSignals, AFreshRunStoppedInSetUpWritesNothingAndRunsAgain) {
  const TempDir dir("rondel-sigsetup");
  test::write_file(dir / "box.ini", test::moving_wall_box_ini("wang"));
  for (const auto& [ranks, signal] : {std::pair{2, "USR1"}, std::pair{0, "TERM"}}) {
    const Outcome o = signalled_in_setup(dir, ranks, signal, "box.ini --run.output=fresh --run.steps=20");
    EXPECT_EQ(o.exit_code, kExitStopped.code) << signal << ": " << o.err;
    EXPECT_EQ(occurrences(o.err, std::string("rondel: stopped by SIG") + signal +
                                     " during set-up, before anything was written to 'fresh': run the same command "
                                     "again to start the run"),
              1u)
        << o.err;
    EXPECT_FALSE(fs::exists(dir / "fresh"));
  }
  const Outcome again = test::mpirun_rondel(dir, 2, "box.ini --run.output=fresh --run.steps=20");
  EXPECT_EQ(again.exit_code, 0) << again.err;
}

TEST(SetupSignals, AResumeStoppedInSetUpLeavesItsDirectoryAsItWas) {
  const TempDir dir("rondel-sigresume");
  test::write_file(dir / "box.ini", test::moving_wall_box_ini("wang"));
  ASSERT_EQ(test::mpirun_rondel(dir, 2, "box.ini --run.output=whole --run.steps=40").exit_code, 0);
  ASSERT_EQ(
      test::mpirun_rondel(dir, 2, "box.ini --run.output=run --run.steps=20 --output.checkpoint_every=10").exit_code, 0);
  const auto before = test::read_tree(dir / "run");
  const Outcome o = signalled_in_setup(dir, 2, "USR1", "--resume run --run.steps=40");
  EXPECT_EQ(o.exit_code, kExitStopped.code) << o.err;
  EXPECT_EQ(occurrences(o.err,
                        "rondel: stopped by SIGUSR1 during set-up, before anything was written to 'run': resume "
                        "with --resume run (the checkpoint 'run/checkpoint_0000000020.h5' is as it was)"),
            1u)
      << o.err;
  EXPECT_TRUE(test::read_tree(dir / "run") == before) << "the run directory changed";
  const Outcome resumed = test::mpirun_rondel(dir, 2, "--resume run --run.steps=40");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_EQ(read_file(dir / "run" / "final.csv"), read_file(dir / "whole" / "final.csv"));
}

}  // namespace
}  // namespace rondel
