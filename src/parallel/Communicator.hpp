#pragma once
#include <mpi.h>

#include <cstdint>
#include <string>
#include <vector>

#include "core/ExactSum.hpp"
#include "parallel/ByteBuffer.hpp"

namespace rondel {

// The text MPI gives for an error code.
std::string mpi_error_text(int code);

// Initialises and finalises MPI for the process (one object, in main or the test runner).
class MpiEnvironment {
 public:
  MpiEnvironment(int* argc, char*** argv);
  ~MpiEnvironment();
  MpiEnvironment(const MpiEnvironment&) = delete;
  MpiEnvironment& operator=(const MpiEnvironment&) = delete;
};

// What this rank has asked of MPI so far (docs/scaling.md): collective calls (each MPI collective counts
// one), point-to-point messages sent and their bytes. The scaling audit and the benchmarks read them.
struct CommStats {
  std::int64_t collectives = 0, messages = 0, bytes = 0;
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
  // The sum of `local` over the ranks below this one (0 on rank 0; no collective on one rank): a block's offset.
  std::uint64_t exclusive_sum(std::uint64_t local) const;
  // Order-independent exact sum over ranks: the same bits on any rank count.
  double exact_sum(ExactSum local) const;
  void exact_sum_in_place(ExactSum& local) const;
  // Sends out[r] to rank r and returns what each rank sent here (in[r] from rank r).
  std::vector<ByteBuffer> all_to_all(const std::vector<ByteBuffer>& out) const;
  // Sends `out` to each rank in `to` and receives from each rank in `from` (point to point) `sizes` bytes.
  std::vector<ByteBuffer> exchange(const std::vector<int>& to, const std::vector<ByteBuffer>& out,
                                   const std::vector<int>& from, const std::vector<std::size_t>& sizes) const;
  // The same when the receiver does not know the sizes: each message is preceded by its 64-bit size. Every
  // rank in `to` must list this rank in its `from` (an empty buffer is still sent).
  std::vector<ByteBuffer> exchange(const std::vector<int>& to, const std::vector<ByteBuffer>& out,
                                   const std::vector<int>& from) const;
  // Every rank gets root's bytes.
  void broadcast(std::vector<char>& bytes, int root = 0) const;
  // Every rank gets every rank's bytes, in rank order.
  std::vector<ByteBuffer> all_gather(const ByteBuffer& mine) const;
  // Root gets every rank's bytes, in rank order (others get an empty vector).
  std::vector<ByteBuffer> gather(const ByteBuffer& mine, int root = 0) const;
  void barrier() const;
  MPI_Comm comm() const { return comm_; }
  const CommStats& stats() const { return stats_; }
  // For MPI calls made outside this class (Agreement, FusedReduction, the partitioner's scans).
  void count_collective() const { ++stats_.collectives; }

 private:
  MPI_Comm comm_;
  int rank_ = 0;
  int size_ = 1;
  mutable CommStats stats_;
};

}  // namespace rondel
