#pragma once
#include <cstdint>
#include <vector>

#include "core/ExactSum.hpp"
#include "parallel/Communicator.hpp"

namespace rondel {

// One reduction of a small buffer for everything a step needs from the other ranks (docs/scaling.md): the
// largest displacement, the error flag, the exact wall loads of every controlled wall, the load-balance
// counts. Values are added in the same order on every rank; reduce() is a single MPI_Allreduce with a
// user-defined operation that takes the maximum of the first part and the sum of the second. The maxima are
// of non-negative doubles and of integers, compared as 64-bit integers (the bits of a non-negative double
// order as the double does); the sums are integers and the limbs of ExactSum, so the result is exact and
// independent of the order in which MPI combines the ranks.
class FusedReduction {
 public:
  // Each returns the slot to read the reduced value from.
  std::size_t max(double non_negative);
  std::size_t max(std::int64_t value);
  std::size_t sum(std::int64_t value);
  std::size_t sum(const ExactSum& value);
  bool empty() const { return max_.empty() && sum_.empty(); }

  // Collective (one MPI call; none on one rank).
  void reduce(const Communicator& comm);

  double max_double(std::size_t slot) const;
  std::int64_t max_int(std::size_t slot) const { return max_[slot]; }
  std::int64_t sum_int(std::size_t slot) const { return sum_[slot]; }
  ExactSum sum_exact(std::size_t slot) const;

 private:
  std::vector<std::int64_t> max_, sum_;
};

}  // namespace rondel
