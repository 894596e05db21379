#pragma once
// AVX-512 building blocks of the bond loops: loads of one small record per lane for 8 bonds at once, from
// point-major arrays, as vectors with one record component each (a 3-vector: x, u, v, 3 doubles per point;
// a 3×3 tensor: 9 per point), and 1/√x without the divider.
//
// Why not gathers: the correspondence bond loops read 6–24 doubles of each partner j, PMB 6. GCC's gathers
// cost about 0.42 ns per element on the Sapphire Rapids VM of bench/README.md; eight plain loads of each
// record and a transpose in registers cost 0.24 ns per element (a stand-alone loop of 9-double records).
// Included only in the HWY_AVX3 pass of a file compiled per target with Highway's foreach_target, after
// HWY_BEFORE_NAMESPACE, so that these functions get AVX-512 code; that file includes <immintrin.h>,
// <algorithm>, <cstdint> and <vector> at its top, so that the standard library stays compiled for the
// baseline (an inline function compiled here for AVX-512 could be the copy the linker keeps for all).
#if HWY_TARGET != HWY_AVX3
#error "core/avx512_gather.hpp belongs in the HWY_AVX3 pass of a foreach_target file"
#endif

// GCC 12's intrinsics leave the unused part of an unmasked result "undefined" through a self-initialised
// variable, which -Wmaybe-uninitialized reports at every use (GCC bug 105593); the code between these
// two is written with intrinsics only.
#define PERIDOT_AVX512_BEGIN                                         \
  _Pragma("GCC diagnostic push") _Pragma("GCC diagnostic ignored \"-Wmaybe-uninitialized\"") \
      _Pragma("GCC diagnostic ignored \"-Wuninitialized\"")
#define PERIDOT_AVX512_END _Pragma("GCC diagnostic pop")

PERIDOT_AVX512_BEGIN
namespace peridot::avx512 {

/// The lanes of the bonds b … b+7 of a run of `count` bonds (b < count) that are inside the run. `j` is
/// pointed at their neighbour indices: the run's own, or for a last partial group `tail`, which repeats the
/// run's last neighbour in the lanes past it (a masked lane reads that partner's finite record and adds
/// nothing); nothing past the run is read.
[[gnu::always_inline]] inline __mmask8 group_lanes(const std::uint32_t* neighbor, std::uint64_t b, std::uint64_t count,
                                                   std::uint32_t tail[8], const std::uint32_t*& j) {
  const std::uint64_t left = count - b;
  j = neighbor + b;
  if (left >= 8) return 0xff;
  for (std::uint64_t k = 0; k < 8; ++k) tail[k] = neighbor[b + std::min(k, left - 1)];
  j = tail;
  return static_cast<__mmask8>((1u << left) - 1);
}

/// The group_lanes whose bonds are intact (broken[b + k] = 0).
[[gnu::always_inline]] inline __mmask8 intact_lanes(const std::uint32_t* neighbor, const std::uint8_t* broken,
                                                    std::uint64_t b, std::uint64_t count, std::uint32_t tail[8],
                                                    const std::uint32_t*& j) {
  const __mmask8 lanes = group_lanes(neighbor, b, count, tail, j);
  const __m128i flags = _mm_maskz_loadu_epi8(lanes, broken + b);
  return lanes & static_cast<__mmask8>(_mm_testn_epi8_mask(flags, flags));
}

/// weight[b + k] in the intact_lanes, 0 elsewhere.
[[gnu::always_inline]] inline __m512d load_group(const std::uint32_t* neighbor, const std::uint8_t* broken,
                                                 const double* weight, std::uint64_t b, std::uint64_t count,
                                                 std::uint32_t tail[8], const std::uint32_t*& j) {
  return _mm512_maskz_loadu_pd(intact_lanes(neighbor, broken, b, count, tail, j), weight + b);
}

/// out[c] lane k = base[3 j_k + c], c < 3, for the 8 indices of `j`. The fourth double of each load is
/// masked off, so the last point's record is read without running past the array.
[[gnu::always_inline]] inline void load_vec3(const double* base, const std::uint32_t* j, __m512d out[3]) {
  __m256d r[8];
  for (int k = 0; k < 8; ++k) r[k] = _mm256_maskz_loadu_pd(0x7, base + 3 * static_cast<std::uint64_t>(j[k]));
  // t_k = [r_k | r_{k+4}]: each 256-bit half is transposed as a 4×4 block.
  const __m512d t0 = _mm512_insertf64x4(_mm512_zextpd256_pd512(r[0]), r[4], 1);
  const __m512d t1 = _mm512_insertf64x4(_mm512_zextpd256_pd512(r[1]), r[5], 1);
  const __m512d t2 = _mm512_insertf64x4(_mm512_zextpd256_pd512(r[2]), r[6], 1);
  const __m512d t3 = _mm512_insertf64x4(_mm512_zextpd256_pd512(r[3]), r[7], 1);
  const __m512d lo01 = _mm512_unpacklo_pd(t0, t1), hi01 = _mm512_unpackhi_pd(t0, t1);  // x0 x1 z0 z1 | …
  const __m512d lo23 = _mm512_unpacklo_pd(t2, t3), hi23 = _mm512_unpackhi_pd(t2, t3);
  const __m512i first = _mm512_setr_epi64(0, 1, 8, 9, 4, 5, 12, 13), second = _mm512_setr_epi64(2, 3, 10, 11, 6, 7, 14, 15);
  out[0] = _mm512_permutex2var_pd(lo01, first, lo23);
  out[1] = _mm512_permutex2var_pd(hi01, first, hi23);
  out[2] = _mm512_permutex2var_pd(lo01, second, lo23);
}

/// out[c] lane k = base[9 j_k + c], c < 9, for the 8 indices of `j` (row-major 3×3 tensors): an 8×8
/// transpose of the first eight components and one gather of the ninth.
[[gnu::always_inline]] inline void load_tensor(const double* base, const std::uint32_t* j, __m512d out[9]) {
  __m512d r[8];
  for (int k = 0; k < 8; ++k) r[k] = _mm512_loadu_pd(base + 9 * static_cast<std::uint64_t>(j[k]));
  __m512d a[8], b[8];
  for (int k = 0; k < 8; k += 2) a[k] = _mm512_unpacklo_pd(r[k], r[k + 1]), a[k + 1] = _mm512_unpackhi_pd(r[k], r[k + 1]);
  // a[0] = r0_0 r1_0 r0_2 r1_2 r0_4 r1_4 r0_6 r1_6, a[1] the odd components; a[2], a[3] for rows 2, 3 …
  for (int k = 0; k < 8; k += 4)
    for (int p = 0; p < 2; ++p) {
      b[k + p] = _mm512_shuffle_f64x2(a[k + p], a[k + 2 + p], 0x88);      // 128-bit lanes 0, 2 of each
      b[k + 2 + p] = _mm512_shuffle_f64x2(a[k + p], a[k + 2 + p], 0xdd);  // lanes 1, 3
    }
  // b[0] = r0_0 r1_0 r0_4 r1_4 r2_0 r3_0 r2_4 r3_4 …: one more exchange of 128-bit lanes across the halves.
  const __m512i low = _mm512_setr_epi64(0, 1, 4, 5, 8, 9, 12, 13), high = _mm512_setr_epi64(2, 3, 6, 7, 10, 11, 14, 15);
  // Components c = 0, 4 from b[0] and b[4] (even), 1, 5 from b[1], b[5], 2, 6 from b[2], b[6], 3, 7 from b[3], b[7].
  for (int p = 0; p < 4; ++p) {
    out[p] = _mm512_permutex2var_pd(b[p], low, b[p + 4]);
    out[p + 4] = _mm512_permutex2var_pd(b[p], high, b[p + 4]);
  }
  const __m256i jj = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(j));
  const __m512i index = _mm512_add_epi64(_mm512_mullo_epi64(_mm512_cvtepu32_epi64(jj), _mm512_set1_epi64(9)),
                                         _mm512_set1_epi64(8));
  out[8] = _mm512_i64gather_pd(index, base, 8);
}

/// 1/√x to about 1 ulp (2.7e-16 relative measured): the 14-bit estimate and two Newton steps
/// y ← y (3/2 − x y²/2). 0.32 ns per element on this VM against 1.05 ns for a square root and 0.71 ns for a
/// division, which wait for the divider (bench/README.md). x = 0 gives a NaN: callers mask such lanes.
[[gnu::always_inline]] inline __m512d reciprocal_sqrt(__m512d x) {
  const __m512d half_x = x * _mm512_set1_pd(0.5), three_halves = _mm512_set1_pd(1.5);
  __m512d y = _mm512_rsqrt14_pd(x);
  y = y * (three_halves - half_x * y * y);
  return y * (three_halves - half_x * y * y);
}

/// The intact bonds of one run, for a loop that skips broken bonds (LAMMPS PERI skips them too): their
/// neighbours and their places in the run, in the run's order. One per thread; it grows to the longest run.
struct IntactBonds {
  std::vector<std::uint32_t> neighbor, position;
  std::uint64_t count = 0;

  /// Lists the intact bonds among the run's `n` (neighbours `run_neighbor`, flags `broken`); false, and
  /// nothing listed, when none is broken: the run itself is then the list.
  bool compact(const std::uint32_t* run_neighbor, const std::uint8_t* broken, std::uint64_t n) {
    bool any = false;
    for (std::uint64_t k = 0; k < n && !any; k += 64) {
      const __mmask64 lanes = n - k >= 64 ? ~__mmask64{0} : (__mmask64{1} << (n - k)) - 1;
      const __m512i flags = _mm512_maskz_loadu_epi8(lanes, broken + k);
      any = _mm512_test_epi8_mask(flags, flags) != 0;
    }
    if (!any) return false;
    if (neighbor.size() < n + 16) neighbor.resize(n + 16), position.resize(n + 16);
    std::uint32_t* to = neighbor.data();  // local pointers: through `this` they are reloaded after each store
    std::uint32_t* place = position.data();
    std::uint64_t c = 0;
    __m512i places = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    // 16 bonds at a time; each store writes 16 entries at c ≤ k, inside the n + 16 reserved.
    for (std::uint64_t k = 0; k < n; k += 16, places = _mm512_add_epi32(places, _mm512_set1_epi32(16))) {
      const __mmask16 lanes = n - k >= 16 ? 0xffff : static_cast<__mmask16>((1u << (n - k)) - 1);
      const __m128i flags = _mm_maskz_loadu_epi8(lanes, broken + k);
      const __mmask16 keep = lanes & _mm_testn_epi8_mask(flags, flags);
      // Register compress and a plain store: the compress-to-memory form is microcoded on Zen 4.
      _mm512_storeu_si512(to + c, _mm512_maskz_compress_epi32(keep, _mm512_maskz_loadu_epi32(lanes, run_neighbor + k)));
      _mm512_storeu_si512(place + c, _mm512_maskz_compress_epi32(keep, places));
      c += static_cast<std::uint64_t>(__builtin_popcount(keep));
    }
    count = c;
    return true;
  }
};

}  // namespace peridot::avx512
PERIDOT_AVX512_END
