// ExactSum (core/exact_sum.hpp): the correctly rounded sum, whatever the order and split of the terms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "peridot/core/exact_sum.hpp"

namespace peridot {
namespace {

double sum_of(const std::vector<double>& terms) {
  ExactSum s;
  for (double t : terms) s.add(t);
  return s.value();
}

TEST(ExactSum, CancellationThatNaiveSummationLoses) {
  // 1e16 + 1 − 1e16 is 0 in left-to-right doubles; the exact sum is 1.
  EXPECT_EQ(sum_of({1e16, 1.0, -1e16}), 1.0);
  EXPECT_EQ(sum_of({1e300, 1e-300, -1e300}), 1e-300);
  EXPECT_EQ(sum_of({0x1p-1074, 0x1p-1074}), 0x1p-1073);  // subnormals
  EXPECT_EQ(sum_of({-2.5, 1.25, -0.75}), -2.0);
  EXPECT_EQ(sum_of({}), 0.0);
  EXPECT_EQ(sum_of({1.0, INFINITY, 2.0}), INFINITY);  // as a floating-point sum would give
  EXPECT_EQ(sum_of({-INFINITY, 1.0}), -INFINITY);
  EXPECT_TRUE(std::isnan(sum_of({INFINITY, -INFINITY})));
  EXPECT_TRUE(std::isnan(sum_of({1.0, NAN})));
  EXPECT_EQ(sum_of({0x1.fffffffffffffp1023, 0x1.fffffffffffffp1023}), INFINITY);  // finite terms, a sum beyond range
}

TEST(ExactSum, RoundsTiesToEvenOnce) {
  // 1 + 2^-53 is a tie between 1 and 1 + 2^-52: to even, 1. With 2^-80 more it is above the tie: 1 + 2^-52.
  EXPECT_EQ(sum_of({1.0, 0x1p-53}), 1.0);
  EXPECT_EQ(sum_of({1.0, 0x1p-53, 0x1p-80}), 1.0 + 0x1p-52);
  EXPECT_EQ(sum_of({-1.0, -0x1p-53, -0x1p-80}), -(1.0 + 0x1p-52));
  EXPECT_EQ(sum_of({1.0 + 0x1p-52, 0x1p-53}), 1.0 + 0x1p-51);  // tie, odd below: up
}

TEST(ExactSum, SameBitsForAnyOrderAndSplit) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  std::uniform_int_distribution<int> exponent(-60, 60);
  std::vector<double> terms(20000);
  for (double& t : terms) t = std::ldexp(mantissa(random), exponent(random));
  const double reference = sum_of(terms);
  // Against a long double sum of the sorted magnitudes (close, not exact): the exact sum is within its error.
  long double wide = 0;
  std::vector<double> sorted = terms;
  std::sort(sorted.begin(), sorted.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
  for (double t : sorted) wide += t;
  EXPECT_NEAR(reference, static_cast<double>(wide), 1e-9 * std::abs(reference) + 1e-6);
  for (int trial = 0; trial < 5; ++trial) {
    std::shuffle(terms.begin(), terms.end(), random);
    EXPECT_EQ(sum_of(terms), reference);
    // Split in parts summed apart, then added (threads, ranks): the same bits.
    ExactSum total;
    const std::size_t parts = 3 + static_cast<std::size_t>(trial);
    for (std::size_t p = 0; p < parts; ++p) {
      ExactSum part;
      for (std::size_t k = p; k < terms.size(); k += parts) part.add(terms[k]);
      total.add(part);
    }
    EXPECT_EQ(total.value(), reference);
    // Through canonical digits added as integers (the all-reduce).
    ExactSum a, b;
    for (std::size_t k = 0; k < terms.size(); ++k) (k % 2 ? a : b).add(terms[k]);
    ExactSum::Digits da = a.canonical(), db = b.canonical();
    for (int k = 0; k < ExactSum::digits; ++k) da[k] += db[k];
    ExactSum reduced;
    reduced.load(da, 0);
    EXPECT_EQ(reduced.value(), reference);
  }
}

TEST(ExactSum, IntegersAreExactUpToManyTerms) {
  // Σ k for k < 2^21 = 2^20 (2^21 − 1), exactly representable; and a sum that goes negative.
  ExactSum s;
  for (int k = 0; k < (1 << 21); ++k) s.add(static_cast<double>(k));
  EXPECT_EQ(s.value(), std::ldexp(1.0, 20) * (std::ldexp(1.0, 21) - 1));
  for (int k = 0; k < (1 << 21); ++k) s.add(-2.0 * k);
  EXPECT_EQ(s.value(), -std::ldexp(1.0, 20) * (std::ldexp(1.0, 21) - 1));
}

}  // namespace
}  // namespace peridot
