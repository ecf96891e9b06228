#pragma once
#include <array>
#include <cstdint>

namespace rondel {

// An order-independent exact sum of doubles: every addend is placed exactly into a long fixed-point
// accumulator (68 limbs of 32 bits spanning the whole double range), so the result does not depend on the
// order of the additions nor on how they are split over ranks (docs/design.md section 5). Limbs add limb-wise,
// which is what the MPI reduction does. Non-finite addends make the sum NaN.
class ExactSum {
 public:
  static constexpr int kLimbs = 68;

  void add(double x);
  ExactSum& operator+=(double x) {
    add(x);
    return *this;
  }
  // Limb-wise sum of another accumulator (both normalised first).
  void merge(const ExactSum& other);
  // The sum rounded to a double (deterministic: a function of the exact value only).
  double value() const;
  // Carries propagated so every limb but the top lies in [0, 2^32): the canonical form.
  void normalise();

  std::array<std::int64_t, kLimbs>& limbs() { return limbs_; }
  bool finite() const { return nonfinite_ == 0; }
  std::int64_t& nonfinite_count() { return nonfinite_; }

 private:
  std::array<std::int64_t, kLimbs> limbs_{};
  std::int64_t nonfinite_ = 0;
  std::int64_t pending_ = 0;  // additions since the last normalisation
};

}  // namespace rondel
