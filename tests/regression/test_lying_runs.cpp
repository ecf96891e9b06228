// Runs and messages that lie, through the real executable: a checkpoint of another run put into a run directory
// is passed over by --resume (the run id of config.ini and of every checkpoint), a lock file of another host is
// taken over only with run.take_lock (and the message says so), an INI key is checked even when the command
// line sets it too, and a parameter that makes the critical step overflow is named.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "app/Checkpointing.hpp"
#include "core/ExitCodes.hpp"
#include "support/Command.hpp"
#include "support/Scenes.hpp"
#include "support/TempDir.hpp"

namespace rondel {
namespace {

namespace fs = std::filesystem;
using test::mpirun_rondel;
using test::occurrences;
using test::Outcome;
using test::read_file;
using test::TempDir;
using test::write_file;

std::string run_id(const fs::path& run) { return Checkpointing::run_id_of(run.string()); }

TEST(LyingRuns, ACheckpointOfAnotherRunIsPassedOver) {
  const TempDir dir("rondel-foreign");
  write_file(dir / "box.ini", test::moving_wall_box_ini("wang"));
  ASSERT_EQ(mpirun_rondel(dir, 1, "box.ini --run.output=mine --run.steps=20 --output.checkpoint_every=10").exit_code,
            0);
  ASSERT_EQ(
      mpirun_rondel(dir, 1, "box.ini --run.output=other --run.steps=30 --output.checkpoint_every=30 --scene.seed=99")
          .exit_code,
      0);
  const std::string mine = run_id(dir / "mine"), other = run_id(dir / "other");
  ASSERT_EQ(mine.size(), 32u);
  ASSERT_NE(mine, other);
  // Under a newer step's name each time: the run's own checkpoints would replace it under its own.
  for (int ranks : {1, 2}) {
    const std::string name = "checkpoint_000000090" + std::to_string(ranks) + ".h5";
    fs::copy_file(dir / "other" / "checkpoint_0000000030.h5", dir / "mine" / name);
    const Outcome o = mpirun_rondel(dir, ranks, "--resume mine --run.steps=" + std::to_string(20 + ranks * 20));
    EXPECT_EQ(o.exit_code, 0) << o.err;
    EXPECT_EQ(occurrences(o.err, "skipping mine/" + name + ": written by another run (run id " + other +
                                     "; this directory's config.ini names the run " + mine + ")"),
              1u)
        << o.err;
    EXPECT_EQ(occurrences(read_file(dir / "mine" / "log.txt"), "resumed at step " + std::to_string(ranks * 20)), 1u);
    EXPECT_EQ(run_id(dir / "mine"), mine);  // the resumed run keeps its id
  }
}

TEST(LyingRuns, ALockOfAnotherHostIsTakenOnlyWhenAskedTo) {
  const TempDir dir("rondel-lock");
  write_file(dir / "box.ini", test::moving_wall_box_ini("wang"));
  ASSERT_EQ(mpirun_rondel(dir, 1, "box.ini --run.output=run --run.steps=10 --output.checkpoint_every=10").exit_code, 0);
  write_file(dir / "run" / "rondel.lock", "4242 a-node-that-failed\n");
  const Outcome refused = mpirun_rondel(dir, 2, "--resume run --run.steps=20");
  EXPECT_EQ(refused.exit_code, kExitInput.code);
  EXPECT_EQ(occurrences(refused.err, "is in use by another run (process 4242 on a-node-that-failed"), 1u)
      << refused.err;
  EXPECT_EQ(occurrences(refused.err, "or, if that run is gone (its node failed), rerun with --run.take_lock=true"), 1u)
      << refused.err;
  const Outcome taken = mpirun_rondel(dir, 2, "--resume run --run.steps=20 --run.take_lock=true");
  EXPECT_EQ(taken.exit_code, 0) << taken.err;
  EXPECT_FALSE(fs::exists(dir / "run" / "rondel.lock"));
  // A live run on this host is never taken over: this test's own process holds the lock.
  char host[256] = {};
  gethostname(host, sizeof host - 1);
  write_file(dir / "run" / "rondel.lock", std::to_string(getpid()) + " " + host + "\n");
  const Outcome live = mpirun_rondel(dir, 1, "--resume run --run.steps=30 --run.take_lock=true");
  EXPECT_EQ(live.exit_code, kExitInput.code);
  EXPECT_EQ(occurrences(live.err, "or remove the lock file if no run uses the directory"), 1u) << live.err;
}

TEST(LyingRuns, AnIniKeyIsCheckedWhenTheCommandLineSetsItToo) {
  const TempDir dir("rondel-inicli");
  const std::string box = test::moving_wall_box_ini("wang");
  write_file(dir / "twice.ini", "[run]\nsteps = 10\nsteps = 20\n" + box);
  write_file(dir / "garbage.ini", "[run]\nsteps = abc\n" + box);
  for (const auto& [file, message] :
       {std::pair{"twice.ini", "in 'twice.ini': option 'run.steps' cannot be specified more than once"},
        std::pair{"garbage.ini", "in 'garbage.ini': the argument ('abc') for option 'run.steps' is invalid"}}) {
    const Outcome o = mpirun_rondel(dir, 1, std::string(file) + " --run.steps=5 --run.output=out");
    EXPECT_EQ(o.exit_code, kExitInput.code) << o.err;
    EXPECT_EQ(occurrences(o.err, message), 1u) << o.err;
    EXPECT_FALSE(fs::exists(dir / "out"));
  }
}

TEST(LyingRuns, AParameterThatOverflowsTheCriticalStepIsNamed) {
  const TempDir dir("rondel-overflow");
  write_file(dir / "box.ini", test::moving_wall_box_ini("wang"));
  const Outcome o = mpirun_rondel(dir, 1, "box.ini --linear.k_n=1e308 --run.output=out");
  EXPECT_EQ(o.exit_code, kExitInput.code) << o.err;
  EXPECT_EQ(occurrences(o.err, "not a positive finite step: made so by linear.k_n = 1e+308 (beyond 1e100"), 1u)
      << o.err;
  EXPECT_EQ(occurrences(o.err, "lower run.dt cannot help"), 1u) << o.err;
}

}  // namespace
}  // namespace rondel
