// GoogleTest main for tests that need MPI: initialises MPI once, prints results on rank 0 only.
#include <gtest/gtest.h>

#include "parallel/Communicator.hpp"

int main(int argc, char** argv) {
  rondel::MpiEnvironment mpi(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  if (rondel::Communicator().rank() != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  return RUN_ALL_TESTS();
}
