// ExactSum (src/core/ExactSum.*): the order-independent exact accumulator behind every global sum
// (docs/design.md section 5). The result must not depend on the order of the additions nor on how they are
// split (merged like the MPI reduction), and must be exact where the exact sum is a double.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/ExactSum.hpp"
#include "support/Assertions.hpp"

namespace rondel {
namespace {

using test::same_bits;

double sum_of(const std::vector<double>& xs) {
  ExactSum s;
  for (double x : xs) s.add(x);
  return s.value();
}

// Addends over 600 binary orders of magnitude, both signs, some of them cancelling exactly.
std::vector<double> wide_addends(unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> mant(1.0, 2.0);
  std::uniform_int_distribution<int> expo(-300, 300);
  std::vector<double> xs;
  for (int k = 0; k < 2000; ++k) {
    const double x = std::ldexp(mant(rng), expo(rng)) * (rng() % 2 ? 1.0 : -1.0);
    xs.push_back(x);
    if (k % 7 == 0) xs.push_back(-x);
  }
  return xs;
}

TEST(ExactSum, EmptySumIsPositiveZero) {
  const double v = ExactSum().value();
  EXPECT_EQ(v, 0.0);
  EXPECT_FALSE(std::signbit(v));
}

TEST(ExactSum, ResultDoesNotDependOnTheOrder) {
  std::vector<double> xs = wide_addends(1);
  const double reference = sum_of(xs);
  std::mt19937 rng(2);
  for (int k = 0; k < 10; ++k) {
    std::shuffle(xs.begin(), xs.end(), rng);
    EXPECT_TRUE(same_bits(sum_of(xs), reference)) << "shuffle " << k;
  }
  std::reverse(xs.begin(), xs.end());
  EXPECT_TRUE(same_bits(sum_of(xs), reference));
}

TEST(ExactSum, MergedPartsEqualOneSum) {
  const std::vector<double> xs = wide_addends(3);
  const double reference = sum_of(xs);
  for (std::size_t parts : {2u, 3u, 7u, 64u}) {
    // Deal the addends round-robin to `parts` accumulators (like ranks), then merge in two orders.
    std::vector<ExactSum> acc(parts);
    for (std::size_t i = 0; i < xs.size(); ++i) acc[i % parts].add(xs[i]);
    ExactSum forward, backward;
    for (std::size_t p = 0; p < parts; ++p) forward.merge(acc[p]);
    for (std::size_t p = parts; p-- > 0;) backward.merge(acc[p]);
    EXPECT_TRUE(same_bits(forward.value(), reference)) << parts << " parts";
    EXPECT_TRUE(same_bits(backward.value(), reference)) << parts << " parts, merged backwards";
  }
}

TEST(ExactSum, ExactOnIllConditionedSums) {
  EXPECT_EQ(sum_of({1e100, 1.0, -1e100}), 1.0);  // naive: 0
  EXPECT_EQ(sum_of({1.0, std::ldexp(1.0, -60), -1.0}), std::ldexp(1.0, -60));
  const double big = std::ldexp(1.0, 53);
  EXPECT_EQ(sum_of({big, 1.0, 1.0}), big + 2.0);  // naive (left to right): big
  EXPECT_EQ(sum_of({1e308, -1e308, 1e-308, 1e-308}), 2e-308);
  // 0.1 ten times minus 1: the exact excess of ten binary 0.1s over 1 (5.55e-17), not the naive 1.1e-16.
  std::vector<double> tenths(10, 0.1);
  tenths.push_back(-1.0);
  EXPECT_EQ(sum_of(tenths), std::ldexp(1.0, -54));
}

TEST(ExactSum, NegativeZeroAddsNothing) {
  EXPECT_FALSE(std::signbit(sum_of({-0.0})));
  EXPECT_FALSE(std::signbit(sum_of({-0.0, -0.0, 0.0})));
  EXPECT_EQ(sum_of({-0.0, 2.5}), 2.5);
  EXPECT_FALSE(std::signbit(sum_of({1.0, -1.0})));  // an exact cancellation is +0
  EXPECT_EQ(sum_of({-1.5, -2.25, -0.0}), -3.75);
}

TEST(ExactSum, LargestAndSmallestMagnitudes) {
  const double max = std::numeric_limits<double>::max();
  const double tiny = std::numeric_limits<double>::denorm_min();
  const double min_normal = std::numeric_limits<double>::min();
  EXPECT_EQ(sum_of({max, max, -max}), max);  // no overflow on the way
  EXPECT_EQ(sum_of({-max, -max, max}), -max);
  EXPECT_EQ(sum_of({max, tiny, -max}), tiny);  // 2098 bits apart
  EXPECT_EQ(sum_of({tiny, tiny, tiny}), 3 * tiny);
  EXPECT_EQ(sum_of({-tiny, -tiny}), -2 * tiny);
  EXPECT_EQ(sum_of({min_normal, -tiny}), min_normal - tiny);  // a subnormal result
  EXPECT_EQ(sum_of({max, -max, min_normal}), min_normal);
}

TEST(ExactSum, ManySmallAdditionsCarryExactly) {
  ExactSum s;
  for (int k = 0; k < 1000000; ++k) s.add(0.75);
  EXPECT_EQ(s.value(), 750000.0);
  ExactSum t;
  for (int k = 0; k < 100000; ++k) t.add(k % 2 ? 4294967295.0 : -4294967296.0);  // carries in both signs
  EXPECT_EQ(t.value(), -50000.0);
}

TEST(ExactSum, NonFiniteAddendMakesTheSumNaN) {
  ExactSum s;
  s.add(1.0);
  EXPECT_TRUE(s.finite());
  s.add(std::numeric_limits<double>::infinity());
  EXPECT_FALSE(s.finite());
  EXPECT_TRUE(std::isnan(s.value()));
  ExactSum t;
  t.add(2.0);
  t.merge(s);  // merging carries the non-finite count
  EXPECT_TRUE(std::isnan(t.value()));
  ExactSum u;
  u.add(std::numeric_limits<double>::quiet_NaN());
  EXPECT_TRUE(std::isnan(u.value()));
}

TEST(ExactSum, OperatorPlusEqualsIsAdd) {
  ExactSum a, b;
  a += 0.1;
  a += 0.2;
  b.add(0.1);
  b.add(0.2);
  EXPECT_TRUE(same_bits(a.value(), b.value()));
}

}  // namespace
}  // namespace rondel
