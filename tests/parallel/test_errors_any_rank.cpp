// An error found on one rank only stops every rank with the same kind and message, never a hang
// (docs/design.md section 6). The case: a resume whose checkpoint has one disc behind a wall, the disc of
// the highest gid, so that only the last rank's block of the file holds it (support/BehindWall.hpp). Every
// rank must throw InputError naming that disc, marked as agreed, and the ranks must still meet in the
// collectives after it. A hang is caught by the CTest timeout. Collective (mpi.np1 ... mpi.np4).
#include <gtest/gtest.h>
#include <mpi.h>

#include <filesystem>
#include <string>

#include "ParallelTestUtil.hpp"
#include "parallel/Agreement.hpp"
#include "support/BehindWall.hpp"

namespace rondel {
namespace {

using namespace partest;
namespace fs = std::filesystem;

TEST(ErrorsOnAnyRank, ResumeWithADiscBehindAWallOnTheLastRankOnly) {
  const SharedTempDir scratch("any-rank");
  const fs::path& dir = scratch.path();
  const Config config = parse_config_text(test::behind_wall_ini(dir / "run"), {});
  std::string checkpoint;
  if (world_rank() == 0) checkpoint = test::write_behind_wall_checkpoint(dir / "run", config).string();
  checkpoint = broadcast(checkpoint);

  ErrorKind kind = ErrorKind::none;
  std::string message;
  bool agreed = false;
  try {
    Simulation sim(config, Communicator(), false, checkpoint);
  } catch (...) {
    kind = error_kind(std::current_exception());
    message = error_message(std::current_exception());
    agreed = is_agreed(std::current_exception());
  }
  const bool ok = kind == ErrorKind::input && message.find(test::behind_wall_message()) != std::string::npos;
  EXPECT_TRUE(all_ranks(ok)) << "rank " << world_rank() << " caught kind " << static_cast<int>(kind) << ": '" << message
                             << "'";
  EXPECT_TRUE(all_ranks(agreed || world_size() == 1)) << "rank " << world_rank() << ": the error is not agreed";
  const auto all = all_gather(message);
  for (const auto& m : all) EXPECT_EQ(m, all.front()) << "the ranks report different messages";
  // The ranks are still in step: a reduction after the error matches.
  int sum = 1;
  MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  EXPECT_EQ(sum, world_size());
}

}  // namespace
}  // namespace rondel
