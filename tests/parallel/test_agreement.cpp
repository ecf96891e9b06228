// Errors agreed among the ranks (parallel/Agreement.hpp, docs/design.md section 6): agree() with an error on
// rank 0 only, on the last rank only, on several ranks (the lowest wins, kind and message), every kind
// kept, a nested agree that is one agreement with the outer one, and main's last resort (settle_at_exit)
// that gives up, without a hang, when a rank does not come. Every case is collective (mpi.np1 ... mpi.np4).
#include <gtest/gtest.h>
#include <mpi.h>

#include <chrono>
#include <stdexcept>
#include <string>

#include "ParallelTestUtil.hpp"
#include "core/Config.hpp"
#include "parallel/Agreement.hpp"

namespace rondel {
namespace {

using namespace partest;

// What agree() left on this rank: the kind and message of what it threw (none: it returned).
struct Caught {
  ErrorKind kind = ErrorKind::none;
  std::string message;
  bool agreed = false;
};

template <class F>
Caught run_agree(F&& f) {
  Caught c;
  try {
    agree(Communicator(), f);
  } catch (...) {
    c.kind = error_kind(std::current_exception());
    c.message = error_message(std::current_exception());
    c.agreed = is_agreed(std::current_exception());
  }
  return c;
}

// Every rank caught `kind` with `message`, marked as agreed (the verdict is checked on every rank).
void expect_everywhere(const Caught& c, ErrorKind kind, const std::string& message) {
  const bool ok = c.kind == kind && c.message == message && c.agreed;
  const auto all = all_gather(std::to_string(static_cast<int>(c.kind)) + ":" + c.message);
  EXPECT_TRUE(all_ranks(ok)) << "rank " << world_rank() << " caught kind " << static_cast<int>(c.kind) << " '"
                             << c.message << "' (agreed " << c.agreed << "), expected kind " << static_cast<int>(kind)
                             << " '" << message << "'";
  for (const auto& a : all) EXPECT_EQ(a, all.front()) << "the ranks disagree";
}

TEST(Agreement, NoErrorReturnsOnEveryRank) {
  const Caught c = run_agree([] {});
  EXPECT_TRUE(all_ranks(c.kind == ErrorKind::none));
}

TEST(Agreement, ErrorOnRankZeroOnlyReachesEveryRank) {
  const Caught c = run_agree([] {
    if (world_rank() == 0) throw InputError("rank 0 found it");
  });
  expect_everywhere(c, ErrorKind::input, "rank 0 found it");
}

TEST(Agreement, ErrorOnTheLastRankOnlyReachesEveryRank) {
  const int last = world_size() - 1;
  const Caught c = run_agree([&] {
    if (world_rank() == last) throw IoError("rank " + std::to_string(last) + " cannot write");
  });
  expect_everywhere(c, ErrorKind::io, "rank " + std::to_string(last) + " cannot write");
}

TEST(Agreement, OfSeveralFailingRanksTheLowestWins) {
  // Every rank but 0 fails (rank 0 too on one rank), each with its own kind: the lowest failing rank's
  // kind and message reach every rank.
  const int lowest = world_size() > 1 ? 1 : 0;
  const Caught c = run_agree([&] {
    const int r = world_rank();
    if (r == 0 && world_size() > 1) return;
    if (r % 2 == 1) throw ConfigError("config on rank " + std::to_string(r));
    throw InstabilityError("instability on rank " + std::to_string(r));
  });
  expect_everywhere(c, lowest % 2 == 1 ? ErrorKind::config : ErrorKind::instability,
                    (lowest % 2 == 1 ? "config on rank " : "instability on rank ") + std::to_string(lowest));
}

TEST(Agreement, EveryKindIsKeptAndOthersBecomeInternal) {
  const int last = world_size() - 1;
  struct Case {
    ErrorKind kind;
    std::function<void()> raise;
  };
  const std::vector<Case> cases{
      {ErrorKind::config, [] { throw ConfigError("c"); }},
      {ErrorKind::input, [] { throw InputError("c"); }},
      {ErrorKind::instability, [] { throw InstabilityError("c"); }},
      {ErrorKind::io, [] { throw IoError("c"); }},
      {ErrorKind::help, [] { throw HelpRequested{"c"}; }},
      {ErrorKind::internal, [] { throw std::logic_error("c"); }},
  };
  for (const Case& k : cases) {
    const Caught c = run_agree([&] {
      if (world_rank() == last) k.raise();
    });
    expect_everywhere(c, k.kind, "c");
  }
  // The rebuilt exceptions are caught by their own type (main's handlers), with the message.
  try {
    agree(Communicator(), [&] {
      if (world_rank() == last) throw IoError("typed");
    });
    ADD_FAILURE() << "no exception";
  } catch (const IoError& e) {
    EXPECT_STREQ(e.what(), "typed");
  }
}

TEST(Agreement, ANestedAgreeIsOneAgreementWithTheOuterOne) {
  // The last rank fails before the inner agree that the others enter: its outer agreement meets their
  // inner one, and the outer agree of the others passes the agreed error on without a second reduction.
  // The collectives after it still match (a sum of the ranks).
  const int last = world_size() - 1;
  const Caught c = run_agree([&] {
    if (world_rank() == last) throw InputError("before the inner agree");
    agree(Communicator(), [] {});
  });
  expect_everywhere(c, ErrorKind::input, "before the inner agree");
  int sum = world_rank();
  MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_INT, MPI_SUM, MPI_COMM_WORLD);
  EXPECT_EQ(sum, world_size() * (world_size() - 1) / 2);
}

TEST(Agreement, ThrowErrorAloneIsNotMarkedAsAgreed) {
  try {
    throw_error(ErrorKind::io, "mine");
  } catch (...) {
    EXPECT_FALSE(is_agreed(std::current_exception()));
    EXPECT_EQ(error_kind(std::current_exception()), ErrorKind::io);
  }
}

TEST(Agreement, SettleAtExitTakesRankZerosErrorWhenEveryRankFails) {
  MPI_Comm exit_comm = MPI_COMM_NULL;
  MPI_Comm_dup(MPI_COMM_WORLD, &exit_comm);
  std::exception_ptr error = std::make_exception_ptr(InputError("on rank " + std::to_string(world_rank())));
  const bool agreed = settle_at_exit(exit_comm, error, 30.0);
  EXPECT_TRUE(all_ranks(agreed));
  EXPECT_EQ(error_message(error), "on rank 0");
  EXPECT_EQ(error_kind(error), ErrorKind::input);
  MPI_Comm_free(&exit_comm);
}

TEST(Agreement, SettleAtExitGivesUpWhenARankDoesNotCome) {
  // Only the last rank fails; the others do not come within the deadline: it gives up (main then aborts
  // the job) instead of waiting for good. Afterwards the others join the barrier so that it completes.
  if (world_size() == 1) GTEST_SKIP() << "needs two ranks";
  MPI_Comm exit_comm = MPI_COMM_NULL;
  MPI_Comm_dup(MPI_COMM_WORLD, &exit_comm);
  const int last = world_size() - 1;
  if (world_rank() == last) {
    std::exception_ptr error = std::make_exception_ptr(IoError("alone"));
    const auto start = std::chrono::steady_clock::now();
    EXPECT_FALSE(settle_at_exit(exit_comm, error, 0.3));
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
    EXPECT_EQ(error_message(error), "alone");  // its own error, to print before the abort
  }
  MPI_Barrier(MPI_COMM_WORLD);
  if (world_rank() != last) {  // completes the last rank's barrier (a nonblocking one: blocking ones never match it)
    MPI_Request request = MPI_REQUEST_NULL;
    MPI_Ibarrier(exit_comm, &request);
    MPI_Wait(&request, MPI_STATUS_IGNORE);
  }
  MPI_Barrier(MPI_COMM_WORLD);
  MPI_Comm_free(&exit_comm);
}

}  // namespace
}  // namespace rondel
