#include "core/ExactSum.hpp"

#include <cmath>
#include <limits>

namespace rondel {

void ExactSum::add(double x) {
  if (x == 0.0) return;
  if (!std::isfinite(x)) {
    ++nonfinite_;
    return;
  }
  int e = 0;
  const double f = std::frexp(std::fabs(x), &e);  // |x| = f 2^e, f in [0.5, 1)
  // |x| = m 2^(e - 53) with m a 53-bit integer; bit position relative to 2^-1074.
  auto m = static_cast<std::uint64_t>(std::ldexp(f, 53));
  int p = e - 53 + 1074;
  if (p < 0) {  // subnormal: the low bits are zero, shift them out exactly
    m >>= -p;
    p = 0;
  }
  // m 2^s split into three 32-bit limbs without overflowing 64 bits.
  const int s = p % 32, k = p / 32;
  const std::uint64_t low_bits = 32 - s;
  const std::uint64_t part0 = (m & ((std::uint64_t{1} << low_bits) - 1)) << s;
  const std::uint64_t rest = m >> low_bits;
  const std::int64_t sign = x < 0.0 ? -1 : 1;
  limbs_[k] += sign * static_cast<std::int64_t>(part0);
  limbs_[k + 1] += sign * static_cast<std::int64_t>(rest & 0xffffffffu);
  limbs_[k + 2] += sign * static_cast<std::int64_t>(rest >> 32);
  if (++pending_ >= (std::int64_t{1} << 29)) normalise();
}

void ExactSum::normalise() {
  for (int k = 0; k + 1 < kLimbs; ++k) {
    const std::int64_t carry = limbs_[k] >> 32;  // floor division by 2^32
    limbs_[k] -= carry * (std::int64_t{1} << 32);
    limbs_[k + 1] += carry;
  }
  pending_ = 0;
}

void ExactSum::merge(const ExactSum& other) {
  ExactSum o = other;
  o.normalise();
  normalise();
  for (int k = 0; k < kLimbs; ++k) limbs_[k] += o.limbs_[k];
  nonfinite_ += o.nonfinite_;
  normalise();
}

double ExactSum::value() const {
  if (nonfinite_ != 0) return std::numeric_limits<double>::quiet_NaN();
  ExactSum n = *this;
  n.normalise();
  // In canonical form the sign is the top limb's; convert the magnitude (a negative value written as a
  // negative top limb over positive lower limbs would overflow double on the way).
  const bool negative = n.limbs_[kLimbs - 1] < 0;
  if (negative) {
    for (auto& l : n.limbs_) l = -l;
    n.normalise();
  }
  double r = 0.0;
  for (int k = kLimbs - 1; k >= 0; --k)
    if (n.limbs_[k] != 0) r += std::ldexp(static_cast<double>(n.limbs_[k]), 32 * k - 1074);
  return negative ? -r : r;
}

}  // namespace rondel
