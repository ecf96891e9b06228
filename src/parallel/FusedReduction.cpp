#include "parallel/FusedReduction.hpp"

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace rondel {

namespace {

// The buffer travels as one element of a contiguous type, so MPI never splits it and the operation sees
// the whole layout: [n_max][max values...][sum values...].
void fused_op(void* in, void* inout, int* len, MPI_Datatype* type) {
  int bytes = 0;
  MPI_Type_size(*type, &bytes);
  const std::size_t n = static_cast<std::size_t>(bytes) / sizeof(std::int64_t);
  for (int e = 0; e < *len; ++e) {
    const auto* a = static_cast<const std::int64_t*>(in) + static_cast<std::size_t>(e) * n;
    auto* b = static_cast<std::int64_t*>(inout) + static_cast<std::size_t>(e) * n;
    const auto n_max = static_cast<std::size_t>(a[0]);
    for (std::size_t k = 1; k <= n_max; ++k) b[k] = std::max(a[k], b[k]);
    for (std::size_t k = n_max + 1; k < n; ++k) b[k] += a[k];
  }
}

}  // namespace

std::size_t FusedReduction::max(double non_negative) {
  std::int64_t bits = 0;
  // -0 and negatives become 0, NaN becomes inf (a displacement that is not finite must trigger everything).
  const double v = std::isnan(non_negative) ? INFINITY : (non_negative > 0.0 ? non_negative : 0.0);
  std::memcpy(&bits, &v, sizeof bits);
  max_.push_back(bits);
  return max_.size() - 1;
}

std::size_t FusedReduction::max(std::int64_t value) {
  max_.push_back(value);
  return max_.size() - 1;
}

std::size_t FusedReduction::sum(std::int64_t value) {
  sum_.push_back(value);
  return sum_.size() - 1;
}

std::size_t FusedReduction::sum(const ExactSum& value) {
  ExactSum v = value;
  v.normalise();
  const std::size_t slot = sum_.size();
  sum_.insert(sum_.end(), v.limbs().begin(), v.limbs().end());
  sum_.push_back(v.nonfinite_count());
  return slot;
}

double FusedReduction::max_double(std::size_t slot) const {
  double v = 0.0;
  std::memcpy(&v, &max_[slot], sizeof v);
  return v;
}

ExactSum FusedReduction::sum_exact(std::size_t slot) const {
  ExactSum v;
  std::copy(sum_.begin() + static_cast<std::ptrdiff_t>(slot),
            sum_.begin() + static_cast<std::ptrdiff_t>(slot + ExactSum::kLimbs), v.limbs().begin());
  v.nonfinite_count() = sum_[slot + ExactSum::kLimbs];
  v.normalise();
  return v;
}

void FusedReduction::reduce(const Communicator& comm) {
  if (comm.size() == 1 || empty()) return;
  std::vector<std::int64_t> buffer;
  buffer.reserve(1 + max_.size() + sum_.size());
  buffer.push_back(static_cast<std::int64_t>(max_.size()));
  buffer.insert(buffer.end(), max_.begin(), max_.end());
  buffer.insert(buffer.end(), sum_.begin(), sum_.end());
  // The operation and the type of the last size are kept (the layout of a run's steps repeats); MPI frees
  // them at MPI_Finalize.
  static MPI_Op op = [] {
    MPI_Op o;
    MPI_Op_create(&fused_op, 1, &o);
    return o;
  }();
  static MPI_Datatype type = MPI_DATATYPE_NULL;
  static std::size_t type_size = 0;
  if (type_size != buffer.size()) {
    if (type != MPI_DATATYPE_NULL) MPI_Type_free(&type);
    MPI_Type_contiguous(static_cast<int>(buffer.size() * sizeof(std::int64_t)), MPI_BYTE, &type);
    MPI_Type_commit(&type);
    type_size = buffer.size();
  }
  comm.count_collective();
  MPI_Allreduce(MPI_IN_PLACE, buffer.data(), 1, type, op, comm.comm());
  std::copy(buffer.begin() + 1, buffer.begin() + 1 + static_cast<std::ptrdiff_t>(max_.size()), max_.begin());
  std::copy(buffer.begin() + 1 + static_cast<std::ptrdiff_t>(max_.size()), buffer.end(), sum_.begin());
}

}  // namespace rondel
