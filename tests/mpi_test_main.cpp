// GoogleTest main for tests that need MPI: initialises MPI once, prints results on rank 0 only.
#include <gtest/gtest.h>

#include <cstdio>

#include "parallel/Communicator.hpp"

int main(int argc, char** argv) {
  rondel::MpiEnvironment mpi(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  const bool root = rondel::Communicator().rank() == 0;
  if (!root) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  const int status = RUN_ALL_TESTS();
  // A CTest entry runs one case by --gtest_filter: a case renamed since the list was made must fail, not
  // pass by running nothing.
  const auto* unit = ::testing::UnitTest::GetInstance();
  if (status == 0 && unit->test_to_run_count() == 0 && unit->total_test_count() > 0) {
    if (root) std::fprintf(stderr, "no test case matches the filter\n");
    return 1;
  }
  return status;
}
