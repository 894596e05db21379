// The building blocks of the vectorised bond loops, for every SIMD target (core/simd.hpp), in Highway's
// vectors of doubles: one group of bonds is as many bonds as the target has lanes (8 with AVX-512, 4 with
// AVX2, 2 with SSE4, 1 scalar). The loops themselves are written once with these (solvers/internal_force.cpp);
// what needs an instruction Highway has no portable op for is written here per target:
//   - load_vec3: the partners' 3-vectors, one record per lane, transposed into x, y, z vectors. Highway's
//     GatherIndex issues one gather per component; AVX-512 and AVX2 load each record whole and transpose
//     in registers (core/avx512_gather.hpp says what that saved on AVX-512).
//   - lengths: |ξ|, |Y| and 1/(|ξ||Y|). AVX-512 has a 14-bit estimate of 1/√x for doubles, refined by
//     two Newton steps, which keeps the bond loops off the divider. AVX2 has only the 12-bit single-precision
//     estimate: narrowing, estimating and three Newton steps made the AVX2 PMB loop 1.5× slower than two
//     square roots and two divisions, 1.9× slower than two square roots and one division (what the other
//     targets do) on AMD Zen 5 (bench_explicit, 37³ points).
//   - load_tensor: the same for 3×3 tensors (9 doubles per point).
//   - sum_lanes: the lanes' sum in a fixed order per target (the same bits for any thread count).
// Per-target include guard (Highway's convention): a foreach_target file includes this once per target,
// after HWY_BEFORE_NAMESPACE; the file includes <immintrin.h>, <algorithm>, <cstdint> and <vector> at its
// top, so that nothing of the standard library is compiled for a wider instruction set than the baseline.
#if defined(PERIDOT_SIMD_BONDS_TOGGLE) == defined(HWY_TARGET_TOGGLE)
#ifdef PERIDOT_SIMD_BONDS_TOGGLE
#undef PERIDOT_SIMD_BONDS_TOGGLE
#else
#define PERIDOT_SIMD_BONDS_TOGGLE
#endif

#undef PERIDOT_SIMD_BONDS_BEGIN
#undef PERIDOT_SIMD_BONDS_END
#if HWY_TARGET == HWY_AVX3
#include "peridot/core/avx512_gather.hpp"
// Code with these vectors goes between the two (GCC bug 105593: avx512_gather.hpp).
#define PERIDOT_SIMD_BONDS_BEGIN PERIDOT_AVX512_BEGIN
#define PERIDOT_SIMD_BONDS_END PERIDOT_AVX512_END
#else
#define PERIDOT_SIMD_BONDS_BEGIN
#define PERIDOT_SIMD_BONDS_END
#endif

PERIDOT_SIMD_BONDS_BEGIN
namespace peridot::HWY_NAMESPACE::simd_bonds {

namespace hn = hwy::HWY_NAMESPACE;
using D = hn::ScalableTag<double>;
using V = hn::Vec<D>;
using M = hn::Mask<D>;

/// The most lanes a group has on this target (for arrays on the stack).
constexpr std::size_t max_lanes = HWY_MAX_BYTES / sizeof(double);

/// out[c] lane k = base[Width j_k + c], c < Width, through a buffer on the stack: the targets without a
/// transposed load below.
template <int Width>
[[maybe_unused, gnu::always_inline]] inline void load_records(D d, const double* base, const std::uint32_t* j,
                                                              V out[Width]) {
  HWY_ALIGN double lanes[Width][max_lanes];
  for (std::size_t k = 0; k < hn::Lanes(d); ++k)
    for (int c = 0; c < Width; ++c) lanes[c][k] = base[Width * static_cast<std::uint64_t>(j[k]) + c];
  for (int c = 0; c < Width; ++c) out[c] = hn::Load(d, lanes[c]);
}

/// out[c] lane k = base[3 j_k + c], c < 3, for the Lanes(d) indices of `j`; nothing past the last point's
/// record is read.
[[gnu::always_inline]] inline void load_vec3(D d, const double* base, const std::uint32_t* j, V out[3]) {
#if HWY_TARGET == HWY_AVX3
  (void)d;
  __m512d o[3];
  avx512::load_vec3(base, j, o);
  for (int c = 0; c < 3; ++c) out[c] = V{o[c]};
#elif HWY_TARGET == HWY_AVX2
  (void)d;
  const __m256i first_three = _mm256_setr_epi64x(-1, -1, -1, 0);
  __m256d r[4];
  for (int k = 0; k < 4; ++k) r[k] = _mm256_maskload_pd(base + 3 * static_cast<std::uint64_t>(j[k]), first_three);
  const __m256d xz01 = _mm256_unpacklo_pd(r[0], r[1]), y01 = _mm256_unpackhi_pd(r[0], r[1]);  // x0 x1 | z0 z1
  const __m256d xz23 = _mm256_unpacklo_pd(r[2], r[3]), y23 = _mm256_unpackhi_pd(r[2], r[3]);
  out[0] = V{_mm256_permute2f128_pd(xz01, xz23, 0x20)};
  out[1] = V{_mm256_permute2f128_pd(y01, y23, 0x20)};
  out[2] = V{_mm256_permute2f128_pd(xz01, xz23, 0x31)};
#elif HWY_TARGET == HWY_SSE4
  (void)d;
  const double* a = base + 3 * static_cast<std::uint64_t>(j[0]);
  const double* b = base + 3 * static_cast<std::uint64_t>(j[1]);
  const __m128d xy_a = _mm_loadu_pd(a), xy_b = _mm_loadu_pd(b);
  out[0] = V{_mm_unpacklo_pd(xy_a, xy_b)};
  out[1] = V{_mm_unpackhi_pd(xy_a, xy_b)};
  out[2] = V{_mm_loadh_pd(_mm_load_sd(a + 2), b + 2)};
#else
  load_records<3>(d, base, j, out);
#endif
}

/// out[c] lane k = base[9 j_k + c], c < 9, for the Lanes(d) indices of `j` (row-major 3×3 tensors).
[[gnu::always_inline]] inline void load_tensor(D d, const double* base, const std::uint32_t* j, V out[9]) {
#if HWY_TARGET == HWY_AVX3
  (void)d;
  __m512d o[9];
  avx512::load_tensor(base, j, o);
  for (int c = 0; c < 9; ++c) out[c] = V{o[c]};
#elif HWY_TARGET == HWY_AVX2
  (void)d;
  // Components 0–3 and 4–7 of the four records as two 4×4 transposes, the ninth one by one.
  const double* r[4];
  for (int k = 0; k < 4; ++k) r[k] = base + 9 * static_cast<std::uint64_t>(j[k]);
  for (int half = 0; half < 2; ++half) {
    __m256d q[4];
    for (int k = 0; k < 4; ++k) q[k] = _mm256_loadu_pd(r[k] + 4 * half);
    const __m256d lo01 = _mm256_unpacklo_pd(q[0], q[1]), hi01 = _mm256_unpackhi_pd(q[0], q[1]);  // c0 c0 | c2 c2
    const __m256d lo23 = _mm256_unpacklo_pd(q[2], q[3]), hi23 = _mm256_unpackhi_pd(q[2], q[3]);
    out[4 * half + 0] = V{_mm256_permute2f128_pd(lo01, lo23, 0x20)};
    out[4 * half + 1] = V{_mm256_permute2f128_pd(hi01, hi23, 0x20)};
    out[4 * half + 2] = V{_mm256_permute2f128_pd(lo01, lo23, 0x31)};
    out[4 * half + 3] = V{_mm256_permute2f128_pd(hi01, hi23, 0x31)};
  }
  out[8] = V{_mm256_setr_pd(r[0][8], r[1][8], r[2][8], r[3][8])};
#else
  load_records<9>(d, base, j, out);
#endif
}

/// base[j_k] in lane k (64-bit indices: a 32-bit gather would read point indices past 2³¹ as negative).
[[gnu::always_inline]] inline V gather(D d, const double* base, const std::uint32_t* j) {
  const hn::Rebind<std::uint32_t, D> d32;
  const hn::RebindToUnsigned<D> du;
  return hn::GatherIndex(d, base, hn::BitCast(hn::RebindToSigned<D>(), hn::PromoteTo(du, hn::LoadU(d32, j))));
}

/// |ξ| = √ξ², |Y| = √Y² and 1/(|ξ||Y|) of a group of bonds. Where the target has a double-precision
/// estimate of 1/√x (AVX-512), from two of them, each within about 1 ulp, and no divider; elsewhere two
/// square roots and one division. Zero lengths give NaN or ∞: callers mask such lanes.
[[gnu::always_inline]] inline void lengths(D d, V xi2, V y2, V& xi, V& length, V& inverse_product) {
#if HWY_TARGET == HWY_AVX3
  (void)d;
  const V inverse_xi{avx512::reciprocal_sqrt(xi2.raw)}, inverse_length{avx512::reciprocal_sqrt(y2.raw)};
  xi = xi2 * inverse_xi, length = y2 * inverse_length, inverse_product = inverse_xi * inverse_length;
#else
  xi = hn::Sqrt(xi2), length = hn::Sqrt(y2);
  inverse_product = hn::Div(hn::Set(d, 1.0), xi * length);
#endif
}

/// The sum of the lanes of v, in this target's fixed order.
[[gnu::always_inline]] inline double sum_lanes(D d, V v) {
#if HWY_TARGET == HWY_AVX3
  (void)d;
  return _mm512_reduce_add_pd(v.raw);
#else
  return hn::GetLane(hn::SumOfLanes(d, v));
#endif
}

/// The lanes of the group of bonds b … b+Lanes−1 of a list of `count` bonds (b < count) that are inside
/// it. `j` is pointed at their neighbour indices: the list's own, or for a last partial group `tail`,
/// which repeats the list's last neighbour in the lanes past it (a masked lane reads that partner's finite
/// record and adds nothing); nothing past the list is read.
[[gnu::always_inline]] inline M group_lanes(D d, const std::uint32_t* neighbor, std::uint64_t b, std::uint64_t count,
                                            std::uint32_t tail[max_lanes], const std::uint32_t*& j) {
  const std::uint64_t left = count - b, n = hn::Lanes(d);
  j = neighbor + b;
  if (left >= n) return hn::FirstN(d, n);
  for (std::uint64_t k = 0; k < n; ++k) tail[k] = neighbor[b + std::min(k, left - 1)];
  j = tail;
  return hn::FirstN(d, static_cast<std::size_t>(left));
}

/// The weights of the group of bonds b … of a weighted run (state/bond_runs.hpp: `count` bonds, neighbours,
/// weights, broken flags), 0 for a broken bond or a lane past the run, with `j` pointed at the group's
/// neighbours. AVX-512 reads the run in place (the last group masked by group_lanes, the broken flags tested);
/// the other targets read a padded copy whose count is a whole number of groups and whose weights are
/// already 0 where a bond is broken.
[[gnu::always_inline]] inline V group_weights(D d, const std::uint32_t* neighbor, const std::uint8_t* broken,
                                              const double* weight, std::uint64_t b, std::uint64_t count,
                                              std::uint32_t tail[max_lanes], const std::uint32_t*& j) {
#if HWY_TARGET == HWY_AVX3
  (void)d;
  return V{avx512::load_group(neighbor, broken, weight, b, count, tail, j)};
#else
  (void)broken, (void)count, (void)tail;
  j = neighbor + b;
  return hn::LoadU(d, weight + b);
#endif
}

/// The lanes of m as bits, lane k in bit k.
[[gnu::always_inline]] inline unsigned mask_bits(D d, M m) {
  std::uint8_t bytes[8] = {};
  hn::StoreMaskBits(d, m, bytes);
  return bytes[0];  // at most 8 lanes of doubles
}

/// The intact bonds of one run, for a loop that skips broken bonds (LAMMPS PERI skips them too): their
/// neighbours and their places in the run, in the run's order. One per thread; it grows to the longest run.
#if HWY_TARGET == HWY_AVX3
using IntactBonds = avx512::IntactBonds;
#else
struct IntactBonds {
  std::vector<std::uint32_t> neighbor, position;
  std::uint64_t count = 0;

  /// Lists the intact bonds among the run's `n` (neighbours `run_neighbor`, flags `broken`); false, and
  /// nothing listed, when none is broken: the run itself is then the list.
  bool compact(const std::uint32_t* run_neighbor, const std::uint8_t* broken, std::uint64_t n) {
    unsigned any = 0;
    for (std::uint64_t k = 0; k < n; ++k) any |= broken[k];
    if (!any) return false;
    if (neighbor.size() < n) neighbor.resize(n), position.resize(n);
    std::uint32_t* to = neighbor.data();  // local pointers: through `this` they are reloaded after each store
    std::uint32_t* place = position.data();
    std::uint64_t c = 0;
    for (std::uint64_t k = 0; k < n; ++k)
      if (!broken[k]) to[c] = run_neighbor[k], place[c] = static_cast<std::uint32_t>(k), ++c;
    count = c;
    return true;
  }
};
#endif

}  // namespace peridot::HWY_NAMESPACE::simd_bonds
PERIDOT_SIMD_BONDS_END

#endif  // per-target include guard
