// reproducible_sum (parallel/communicator.hpp): the fixed-point sum that decides a symmetry wall's release
// with the same bits on any number of ranks. One rank here; what makes it rank-independent is that the
// result does not depend on the order or grouping of the terms, which a permutation tests, and that it is
// within its stated bound of the exact sum. (py.test_mpi runs it on 1–4 ranks through mpi_symmetry_wall.yaml.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "peridot/parallel/communicator.hpp"

namespace peridot {
namespace {

TEST(ReproducibleSum, IndependentOfTheOrderAndWithinItsBoundOfTheExactSum) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<double> terms(100000);
  // Terms over twelve orders of magnitude, and a total that nearly cancels: the case a sign decision meets.
  for (double& t : terms) t = uniform(random) * std::pow(10.0, 12 * std::abs(uniform(random)) - 6);
  const Communicator serial;
  const double forward = reproducible_sum(serial, terms.size(), [&](std::size_t i) { return terms[i]; });
  std::vector<double> shuffled = terms;
  std::shuffle(shuffled.begin(), shuffled.end(), random);
  const double permuted = reproducible_sum(serial, shuffled.size(), [&](std::size_t i) { return shuffled[i]; });
  EXPECT_EQ(forward, permuted);  // bitwise: the integers add exactly, in any order
  // Against a long-double sum of sorted magnitudes (accurate to far better than the bound here).
  std::vector<long double> sorted(terms.begin(), terms.end());
  std::sort(sorted.begin(), sorted.end(), [](long double a, long double b) { return std::abs(a) < std::abs(b); });
  const long double exact = std::accumulate(sorted.begin(), sorted.end(), 0.0L);
  const double largest = std::abs(*std::max_element(terms.begin(), terms.end(), [](double a, double b) {
    return std::abs(a) < std::abs(b);
  }));
  // Each term is rounded to a multiple of 2^e ≤ largest · N · 2^-60, by at most half of it.
  const double n = static_cast<double>(terms.size());
  const double bound = n * n * largest * std::ldexp(1.0, -61);
  EXPECT_LE(std::abs(static_cast<double>(exact) - forward), bound)
      << "exact " << static_cast<double>(exact) << ", fixed point " << forward;
  // A sum of one sign keeps it, and zero terms give zero.
  EXPECT_GT(reproducible_sum(serial, 3, [](std::size_t i) { return 1e-300 * static_cast<double>(i + 1); }), 0.0);
  EXPECT_EQ(reproducible_sum(serial, 10, [](std::size_t) { return 0.0; }), 0.0);
}

}  // namespace
}  // namespace peridot
