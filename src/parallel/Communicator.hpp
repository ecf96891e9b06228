#pragma once
#include <mpi.h>

#include <cstdint>

namespace rondel {

// Initialises and finalises MPI for the process (one object, in main or the test runner).
class MpiEnvironment {
 public:
  MpiEnvironment(int* argc, char*** argv);
  ~MpiEnvironment();
  MpiEnvironment(const MpiEnvironment&) = delete;
  MpiEnvironment& operator=(const MpiEnvironment&) = delete;
};

// The only door to MPI for code outside src/parallel: rank, size and the reductions the time loop needs.
class Communicator {
 public:
  explicit Communicator(MPI_Comm comm = MPI_COMM_WORLD);
  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }
  double max(double local) const;
  double sum(double local) const;
  std::int64_t sum(std::int64_t local) const;
  bool any(bool local) const;
  void barrier() const;
  MPI_Comm comm() const { return comm_; }

 private:
  MPI_Comm comm_;
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace rondel
