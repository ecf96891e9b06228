#pragma once
#include <mpi.h>

#include <cstdint>
#include <vector>

#include "core/ExactSum.hpp"
#include "parallel/ByteBuffer.hpp"

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
  // This process alone (e.g. to read a whole file on every rank).
  static Communicator self() { return Communicator(MPI_COMM_SELF); }
  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }
  double max(double local) const;
  double sum(double local) const;
  std::int64_t sum(std::int64_t local) const;
  bool any(bool local) const;
  std::int64_t max(std::int64_t local) const;
  // Order-independent exact sum over ranks: the same bits on any rank count.
  double exact_sum(ExactSum local) const;
  void exact_sum_in_place(ExactSum& local) const;
  // Sends out[r] to rank r and returns what each rank sent here (in[r] from rank r).
  std::vector<ByteBuffer> all_to_all(const std::vector<ByteBuffer>& out) const;
  // Sends `out` to each rank in `to` and receives from each rank in `from` (point to point).
  std::vector<ByteBuffer> exchange(const std::vector<int>& to, const std::vector<ByteBuffer>& out,
                                   const std::vector<int>& from, const std::vector<std::size_t>& sizes) const;
  // Every rank gets root's bytes.
  void broadcast(std::vector<char>& bytes, int root = 0) const;
  // Every rank gets every rank's bytes, in rank order.
  std::vector<ByteBuffer> all_gather(const ByteBuffer& mine) const;
  // Root gets every rank's bytes, in rank order (others get an empty vector).
  std::vector<ByteBuffer> gather(const ByteBuffer& mine, int root = 0) const;
  void barrier() const;
  MPI_Comm comm() const { return comm_; }

 private:
  MPI_Comm comm_;
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace rondel
