// The AVX-512 building blocks of the bond loops (core/avx512_gather.hpp) against plain scalar reads, on a
// CPU that has AVX-512 (skipped elsewhere). The checks are compiled in the AVX-512 pass of Highway's
// foreach_target, as the bond loops are.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "unit/avx512_gather_test.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
#if HWY_TARGET == HWY_AVX3
#include "peridot/core/avx512_gather.hpp"
namespace peridot::N_AVX3 {
namespace {

std::vector<double> lanes(__m512d v) {
  std::vector<double> out(8);
  _mm512_storeu_pd(out.data(), v);
  return out;
}

void TransposedLoadsGiveEveryComponentOfEveryPartner() {
  const std::size_t points = 50;
  std::vector<double> vectors(3 * points), tensors(9 * points);
  for (std::size_t k = 0; k < vectors.size(); ++k) vectors[k] = 0.5 + 1.25 * static_cast<double>(k);
  for (std::size_t k = 0; k < tensors.size(); ++k) tensors[k] = -3.0 + 0.75 * static_cast<double>(k);
  // Repeated, unordered indices, and the last point (whose record ends the array).
  const std::uint32_t j[8] = {49, 0, 17, 17, 3, 48, 25, 49};
  __m512d v[3], t[9];
  avx512::load_vec3(vectors.data(), j, v);
  avx512::load_tensor(tensors.data(), j, t);
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 8; ++k) EXPECT_EQ(lanes(v[c])[k], vectors[3 * j[k] + c]) << "component " << c << " lane " << k;
  for (int c = 0; c < 9; ++c)
    for (int k = 0; k < 8; ++k) EXPECT_EQ(lanes(t[c])[k], tensors[9 * j[k] + c]) << "component " << c << " lane " << k;
}

void GroupWeightsAreZeroForBrokenBondsAndPastTheRun() {
  const std::uint32_t neighbor[11] = {4, 8, 15, 16, 23, 42, 7, 9, 11, 13, 2};
  const std::uint8_t broken[11] = {0, 1, 0, 0, 1, 0, 0, 0, 0, 1, 0};
  const double weight[11] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
  std::uint32_t tail[8];
  const std::uint32_t* j = nullptr;
  const std::vector<double> first = lanes(avx512::load_group(neighbor, broken, weight, 0, 11, tail, j));
  EXPECT_EQ(j, neighbor);
  EXPECT_EQ(first, (std::vector<double>{1, 0, 3, 4, 0, 6, 7, 8}));
  // The last group has three bonds; the other lanes repeat the last neighbour with weight 0.
  const std::vector<double> last = lanes(avx512::load_group(neighbor, broken, weight, 8, 11, tail, j));
  EXPECT_EQ(j, tail);
  EXPECT_EQ(last, (std::vector<double>{9, 0, 11, 0, 0, 0, 0, 0}));
  EXPECT_EQ(std::vector<std::uint32_t>(tail, tail + 8), (std::vector<std::uint32_t>{11, 13, 2, 2, 2, 2, 2, 2}));
}

void ReciprocalSqrtIsWithinTwoUlp() {
  double worst = 0;
  for (double x = 1e-12; x < 1e12; x *= 1.0137) {
    const double y = lanes(avx512::reciprocal_sqrt(_mm512_set1_pd(x)))[0];
    const double exact = 1.0 / std::sqrt(static_cast<long double>(x));
    const double ulp = std::nextafter(exact, INFINITY) - exact;
    worst = std::max(worst, std::abs(y - exact) / ulp);
  }
  EXPECT_LE(worst, 2.0);
}

}  // namespace
}  // namespace peridot::N_AVX3
#endif
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace {

bool cpu_has_avx512() { return (hwy::SupportedTargets() & HWY_AVX3) != 0; }

#if HWY_TARGETS & HWY_AVX3
TEST(Avx512Gather, TransposedLoadsGiveEveryComponentOfEveryPartner) {
  if (!cpu_has_avx512()) GTEST_SKIP() << "this CPU has no AVX-512";
  peridot::N_AVX3::TransposedLoadsGiveEveryComponentOfEveryPartner();
}

TEST(Avx512Gather, GroupWeightsAreZeroForBrokenBondsAndPastTheRun) {
  if (!cpu_has_avx512()) GTEST_SKIP() << "this CPU has no AVX-512";
  peridot::N_AVX3::GroupWeightsAreZeroForBrokenBondsAndPastTheRun();
}

TEST(Avx512Gather, ReciprocalSqrtIsWithinTwoUlp) {
  if (!cpu_has_avx512()) GTEST_SKIP() << "this CPU has no AVX-512";
  peridot::N_AVX3::ReciprocalSqrtIsWithinTwoUlp();
}

#else
TEST(Avx512Gather, NotBuiltWithoutAvx512) { GTEST_SKIP() << "this build has no AVX-512 target"; }
#endif

}  // namespace
#endif  // HWY_ONCE
