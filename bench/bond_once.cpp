// Each bond once or twice? The PMB force of the benchmark block (bench/benchmark_problem.hpp: a simple-cubic
// block, horizon 3.015 spacings, 122 bonds per interior point, points in the space-filling-curve order of a
// run), one thread, by three loops in two forms each:
//
//   gather   every directed bond i → j evaluated, its force added to i only: each bond computed twice,
//            f written once per point (what Peridot's loops do; 4 B of neighbour index per directed bond);
//   scatter  each bond once, from the point with the smaller index, added to both ends in a fixed order
//            (LAMMPS's Newton-on pair loop, bpm/peri's "walk each bond once"): half the neighbour list
//            (2 B per directed bond), stores into the partners' forces;
//   buffer   each bond once into a per-bond buffer (24 B per bond pair), then every point gathers its
//            bonds' entries in its CSR order (4 B of pair index per directed bond): deterministic for any
//            thread count by construction, 16 B per directed bond more than gather.
//
// The plain forms are C++ loops written alike (GCC vectorises none of them for the baseline); the vector
// forms are the same three in Highway's vectors with the production loops' building blocks
// (core/simd_bonds.hpp: partners' records loaded whole and transposed, AVX-512's 1/√x estimate), compiled
// for every SIMD target and run on the best one (PERIDOT_SIMD forces one), a group of bonds per lane count.
// The vector gather is the production PMB loop's arithmetic (constant influence, uniform volume). LPS
// (ω = δ/|ξ|, the dilatation pass and the force pass, the production loops' arithmetic) is timed in the
// vector gather and scatter forms: each bond once then adds e to both ends' dilatation sums and the force to
// both ends.
//
// Prints one JSON line: directed bonds, seconds per pass (best of --repeat; --clock cpu takes the thread's
// CPU time instead of the wall clock, for a machine that is busy with something else), directed-bond
// updates per second, bytes per directed bond of each, and the largest difference of the forces from the
// gather of the same form (relative to the largest force), and how many components of the buffer's forces
// differ from that gather's at all. Measures the options the performance issue asks for before any is built
// into the production loops.
//
//   [PERIDOT_SIMD=avx2] bond_once --n 37 37 37 [--repeat 20] [--clock wall|cpu]
#include <time.h>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>  // before the per-target code: the standard headers are compiled for the baseline only
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

// The vector forms are compiled once per SIMD target: Highway's foreach_target includes this file again
// for each (core/simd.hpp); the rest is compiled once.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "bond_once.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#ifndef PERIDOT_BOND_ONCE_SHARED
#define PERIDOT_BOND_ONCE_SHARED
#include "peridot/core/simd.hpp"
#include "peridot/parallel/communicator.hpp"
#include "peridot/solvers/simulation.hpp"
#include "benchmark_problem.hpp"

namespace {

using namespace peridot;

struct Block {
  std::size_t n = 0;
  std::vector<double> x, u, volume;  // x, u: 3 per point
  std::vector<std::uint64_t> offsets;
  std::vector<std::uint32_t> neighbors;
  std::vector<std::uint64_t> upper_offsets;  // the bonds i → j with j > i, in i's CSR order
  std::vector<std::uint32_t> upper_neighbors;
  std::vector<std::uint32_t> pair_of;  // per directed bond: its bond pair (the upper bond's place)
  double c = 0;                        // micromodulus
  double uniform_volume = 0;           // V of every point (a lattice block): the vector forms broadcast it
  // LPS with ω = δ/|ξ| (bench_explicit's LPS): a = 1/m per point, α_d = 15G, β = 3K − 5G (3D), the δ V of
  // ω V_j in one constant; θ per point, written by the dilatation pass.
  std::vector<double> inverse_m, theta;
  double alpha_d = 0, beta = 0, delta_volume = 0;
};

// f_i += c s V_j y/|y| for the bond i → j (the constant influence; s = (|y| − |ξ|)/|ξ|).
inline void bond_force(const Block& k, std::size_t i, std::size_t j, double g[3]) {
  double xi[3], y[3];
  for (int d = 0; d < 3; ++d) {
    xi[d] = k.x[3 * j + d] - k.x[3 * i + d];
    y[d] = xi[d] + (k.u[3 * j + d] - k.u[3 * i + d]);  // negated exactly when i and j swap
  }
  const double r = std::sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
  const double l = std::sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
  const double scale = k.c * (l - r) / (r * l);
  for (int d = 0; d < 3; ++d) g[d] = scale * y[d];
}

void gather(const Block& k, double* f) {
  for (std::size_t i = 0; i < k.n; ++i) {
    double fi[3] = {0, 0, 0};
    for (std::uint64_t b = k.offsets[i]; b < k.offsets[i + 1]; ++b) {
      const std::size_t j = k.neighbors[b];
      double g[3];
      bond_force(k, i, j, g);
      for (int d = 0; d < 3; ++d) fi[d] += g[d] * k.volume[j];
    }
    for (int d = 0; d < 3; ++d) f[3 * i + d] = fi[d];
  }
}

void scatter(const Block& k, double* f) {
  std::fill(f, f + 3 * k.n, 0.0);
  for (std::size_t i = 0; i < k.n; ++i) {
    double fi[3] = {0, 0, 0};
    for (std::uint64_t b = k.upper_offsets[i]; b < k.upper_offsets[i + 1]; ++b) {
      const std::size_t j = k.upper_neighbors[b];
      double g[3];
      bond_force(k, i, j, g);
      for (int d = 0; d < 3; ++d) {
        fi[d] += g[d] * k.volume[j];
        f[3 * j + d] -= g[d] * k.volume[i];
      }
    }
    for (int d = 0; d < 3; ++d) f[3 * i + d] += fi[d];
  }
}

void buffered(const Block& k, double* f, std::vector<double>& pair_force) {
  for (std::size_t i = 0; i < k.n; ++i)
    for (std::uint64_t b = k.upper_offsets[i]; b < k.upper_offsets[i + 1]; ++b) bond_force(k, i, k.upper_neighbors[b], &pair_force[3 * b]);
  for (std::size_t i = 0; i < k.n; ++i) {
    double fi[3] = {0, 0, 0};
    for (std::uint64_t b = k.offsets[i]; b < k.offsets[i + 1]; ++b) {
      const std::size_t j = k.neighbors[b];
      const double sign = j > i ? 1.0 : -1.0;  // the pair's force was computed from its smaller end
      const double* g = &pair_force[3 * static_cast<std::size_t>(k.pair_of[b])];
      for (int d = 0; d < 3; ++d) fi[d] += sign * g[d] * k.volume[j];
    }
    for (int d = 0; d < 3; ++d) f[3 * i + d] = fi[d];
  }
}

}  // namespace
#endif  // PERIDOT_BOND_ONCE_SHARED

HWY_BEFORE_NAMESPACE();
#include "peridot/core/simd_bonds.hpp"
PERIDOT_SIMD_BONDS_BEGIN
namespace peridot::HWY_NAMESPACE {
namespace {

namespace hn = hwy::HWY_NAMESPACE;
namespace sb = simd_bonds;
using D = sb::D;
using V = sb::V;
using M = sb::M;

/// The geometry of a group of bonds of point i (neighbours j): Y, |ξ|, e = |Y| − |ξ| and 1/(|ξ||Y|), as the
/// production loops compute them. From the other end the same operations give exactly −Y and the same
/// lengths (ξ and u_j − u_i are negated exactly), so a bond's force from its other end is exactly negated.
struct Group {
  V dy[3], xi, e, inverse_product;
};

/// Point i's x and u, broadcast.
struct PointOf {
  V x[3], u[3];
  PointOf(D d, const Block& k, std::size_t i) {
    for (int c = 0; c < 3; ++c) x[c] = hn::Set(d, k.x[3 * i + c]), u[c] = hn::Set(d, k.u[3 * i + c]);
  }
};

[[gnu::always_inline]] inline Group group_geometry(D d, const Block& k, const PointOf& p, const std::uint32_t* j) {
  Group g;
  V dx[3], du[3];
  sb::load_vec3(d, k.x.data(), j, dx);
  sb::load_vec3(d, k.u.data(), j, du);
  for (int c = 0; c < 3; ++c) dx[c] = dx[c] - p.x[c], du[c] = du[c] - p.u[c], g.dy[c] = dx[c] + du[c];
  const V xi2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
  const V y2 = g.dy[0] * g.dy[0] + g.dy[1] * g.dy[1] + g.dy[2] * g.dy[2];
  V l;
  sb::lengths(d, xi2, y2, g.xi, l, g.inverse_product);
  g.e = l - g.xi;
  return g;
}

/// Runs body(g, j, lanes, b) for the groups of point i's bonds in `list` (count of them): g the geometry of
/// the group starting at bond b, j its neighbours, lanes those inside the list.
template <class Body>
[[gnu::always_inline]] inline void for_each_group(D d, const Block& k, std::size_t i, const std::uint32_t* list,
                                                  std::uint64_t count, Body&& body) {
  const std::uint64_t n = hn::Lanes(d);
  const PointOf p(d, k, i);
  std::uint32_t tail[sb::max_lanes];
  for (std::uint64_t b = 0; b < count; b += n) {
    const std::uint32_t* j;
    const M lanes = sb::group_lanes(d, list, b, count, tail, j);
    body(group_geometry(d, k, p, j), j, lanes, b);
  }
}

/// The PMB forces on i of a group, c V e/(|ξ||Y|) along Y: the production PMB loop's arithmetic for the
/// constant influence and a uniform volume.
[[gnu::always_inline]] inline void pmb_force(const Group& g, V cv, M lanes, V out[3]) {
  const V scale = hn::IfThenElseZero(lanes, (cv * g.inverse_product) * g.e);
  for (int c = 0; c < 3; ++c) out[c] = scale * g.dy[c];
}

/// Runs body(g, j, lanes, b) with g the PMB forces on i of each group of its bonds in `list`.
template <class Body>
[[gnu::always_inline]] inline void for_each_pmb_group(D d, const Block& k, std::size_t i, const std::uint32_t* list,
                                                      std::uint64_t count, Body&& body) {
  const V cv = hn::Set(d, k.c * k.uniform_volume);
  for_each_group(d, k, i, list, count, [&](const Group& geometry, const std::uint32_t* j, M lanes, std::uint64_t b) {
    V g[3];
    pmb_force(geometry, cv, lanes, g);
    body(g, j, lanes, b);
  });
}

/// f[3 j_q + c] += add[c] lane q for the first `active` lanes: partners of one point are distinct, so no
/// lane overwrites another's. Stored lane by lane (the last partial group's lanes past the list repeat a
/// partner): AVX-512's scatter instruction made the PMB scatter 10-20 % slower on AMD Zen 4.
[[gnu::always_inline]] inline void add_to_partners(D d, double* f, const std::uint32_t* j, const V add[3],
                                                   std::uint64_t active) {
  HWY_ALIGN double partner[3][sb::max_lanes];
  V fj[3];
  sb::load_vec3(d, f, j, fj);
  for (int c = 0; c < 3; ++c) hn::Store(fj[c] + add[c], d, partner[c]);
  for (std::uint64_t q = 0; q < active; ++q)
    for (int c = 0; c < 3; ++c) f[3 * static_cast<std::uint64_t>(j[q]) + c] = partner[c][q];
}

void gather_vector(const Block& k, double* f) {
  const D d;
  for (std::size_t i = 0; i < k.n; ++i) {
    V sum[3] = {hn::Zero(d), hn::Zero(d), hn::Zero(d)};
    for_each_pmb_group(d, k, i, k.neighbors.data() + k.offsets[i], k.offsets[i + 1] - k.offsets[i],
                       [&](const V g[3], const std::uint32_t*, M, std::uint64_t) {
                         for (int c = 0; c < 3; ++c) sum[c] = sum[c] + g[c];
                       });
    for (int c = 0; c < 3; ++c) f[3 * i + c] = sb::sum_lanes(d, sum[c]);
  }
}

void scatter_vector(const Block& k, double* f) {
  const D d;
  const std::uint64_t n = hn::Lanes(d);
  std::fill(f, f + 3 * k.n, 0.0);
  for (std::size_t i = 0; i < k.n; ++i) {
    const std::uint64_t count = k.upper_offsets[i + 1] - k.upper_offsets[i];
    V sum[3] = {hn::Zero(d), hn::Zero(d), hn::Zero(d)};
    for_each_pmb_group(d, k, i, k.upper_neighbors.data() + k.upper_offsets[i], count,
                       [&](const V g[3], const std::uint32_t* j, M, std::uint64_t b) {
      const V minus[3] = {hn::Neg(g[0]), hn::Neg(g[1]), hn::Neg(g[2])};
      for (int c = 0; c < 3; ++c) sum[c] = sum[c] + g[c];
      add_to_partners(d, f, j, minus, std::min(n, count - b));
    });
    for (int c = 0; c < 3; ++c) f[3 * i + c] += sb::sum_lanes(d, sum[c]);
  }
}

/// pair_force: 3 doubles per bond pair, x y z, as the points' records: written with an interleaved store and
/// read back with the transposed record load of x and u (three gathers per group instead ran at 0.36–0.47 of
/// the vector gather on AMD Zen 4, 50 k to 1 M points).
void buffer_vector(const Block& k, double* f, double* pair_force) {
  const D d;
  const hn::RebindToSigned<D> di;
  const hn::Rebind<std::uint32_t, D> d32;
  const std::uint64_t n = hn::Lanes(d);
  std::uint32_t tail[sb::max_lanes];
  HWY_ALIGN double last[3 * sb::max_lanes];
  for (std::size_t i = 0; i < k.n; ++i) {  // each pair once, from its smaller end, stored in pair order
    const std::uint64_t first = k.upper_offsets[i], count = k.upper_offsets[i + 1] - first;
    for_each_pmb_group(d, k, i, k.upper_neighbors.data() + first, count,
                       [&](const V g[3], const std::uint32_t*, M, std::uint64_t b) {
      double* out = pair_force + 3 * (first + b);
      if (b + n <= count) {
        hn::StoreInterleaved3(g[0], g[1], g[2], d, out);
      } else {  // the last partial group: only its own pairs (the next point's may be another thread's)
        hn::StoreInterleaved3(g[0], g[1], g[2], d, last);
        std::copy(last, last + 3 * (count - b), out);
      }
    });
  }
  for (std::size_t i = 0; i < k.n; ++i) {  // each point sums its bonds' pair forces in its CSR order
    const std::uint32_t* family = k.neighbors.data() + k.offsets[i];
    const std::uint32_t* pairs = k.pair_of.data() + k.offsets[i];
    const std::uint64_t count = k.offsets[i + 1] - k.offsets[i];
    const auto me = hn::Set(di, static_cast<std::int64_t>(i));
    V sum[3] = {hn::Zero(d), hn::Zero(d), hn::Zero(d)};
    for (std::uint64_t b = 0; b < count; b += n) {
      const std::uint32_t* j;
      std::uint32_t pair_tail[sb::max_lanes];
      const std::uint32_t* pair;
      const M lanes = sb::group_lanes(d, family, b, count, tail, j);
      sb::group_lanes(d, pairs, b, count, pair_tail, pair);
      // The pair's force was computed from its smaller end: negated where the partner is the smaller.
      const M lower = hn::RebindMask(d, hn::Lt(hn::BitCast(di, hn::PromoteTo(hn::RebindToUnsigned<D>(), hn::LoadU(d32, j))), me));
      V g[3];
      sb::load_vec3(d, pair_force, pair, g);
      for (int c = 0; c < 3; ++c) {
        const V term = hn::IfThenElseZero(lanes, g[c]);
        sum[c] = sum[c] + hn::IfThenElse(lower, hn::Neg(term), term);
      }
    }
    for (int c = 0; c < 3; ++c) f[3 * i + c] = sb::sum_lanes(d, sum[c]);
  }
}

/// arr[j_q] += add lane q for the first `active` lanes (as add_to_partners, one value per point).
[[gnu::always_inline]] inline void add_to_partner_values(D d, double* arr, const std::uint32_t* j, V add,
                                                         std::uint64_t active) {
  HWY_ALIGN double partner[sb::max_lanes];
  hn::Store(sb::gather(d, arr, j) + add, d, partner);
  for (std::uint64_t q = 0; q < active; ++q) arr[j[q]] = partner[q];
}

/// The LPS forces on i of a group, (t_ij + t_ji) V_j along Y/|Y| with ω = δ/|ξ|: the production loop's
/// α_d (a_i + a_j) e + β ξ (a_i θ_i + a_j θ_j), symmetric in i and j to the bit.
struct LpsForce {
  V alpha_d, beta, delta_volume, a_i, a_theta_i;
  const Block& k;
  LpsForce(D d, const Block& block, std::size_t i)
      : alpha_d(hn::Set(d, block.alpha_d)), beta(hn::Set(d, block.beta)), delta_volume(hn::Set(d, block.delta_volume)),
        a_i(hn::Set(d, block.inverse_m[i])), a_theta_i(hn::Set(d, block.inverse_m[i] * block.theta[i])), k(block) {}
  [[gnu::always_inline]] void operator()(D d, const Group& g, const std::uint32_t* j, M lanes, V out[3]) const {
    const V a_j = sb::gather(d, k.inverse_m.data(), j), theta_j = sb::gather(d, k.theta.data(), j);
    const V t_xi = (alpha_d * (a_i + a_j)) * g.e + (beta * (a_theta_i + a_j * theta_j)) * g.xi;
    const V carried = hn::IfThenElseZero(lanes, t_xi * delta_volume * g.inverse_product);
    for (int c = 0; c < 3; ++c) out[c] = carried * g.dy[c];
  }
};

/// The whole LPS evaluation, each bond twice: θ_i = 3 a_i δV Σ e over i's bonds (ω ξ V = δ V), then the
/// forces, each point gathering from its whole family.
void lps_gather_vector(Block& k, double* f) {
  const D d;
  for (std::size_t i = 0; i < k.n; ++i) {
    V sum = hn::Zero(d);
    for_each_group(d, k, i, k.neighbors.data() + k.offsets[i], k.offsets[i + 1] - k.offsets[i],
                   [&](const Group& g, const std::uint32_t*, M lanes, std::uint64_t) { sum = sum + hn::IfThenElseZero(lanes, g.e); });
    k.theta[i] = 3 * k.inverse_m[i] * (k.delta_volume * sb::sum_lanes(d, sum));
  }
  for (std::size_t i = 0; i < k.n; ++i) {
    const LpsForce force(d, k, i);
    V sum[3] = {hn::Zero(d), hn::Zero(d), hn::Zero(d)};
    for_each_group(d, k, i, k.neighbors.data() + k.offsets[i], k.offsets[i + 1] - k.offsets[i],
                   [&](const Group& g, const std::uint32_t* j, M lanes, std::uint64_t) {
      V t[3];
      force(d, g, j, lanes, t);
      for (int c = 0; c < 3; ++c) sum[c] = sum[c] + t[c];
    });
    for (int c = 0; c < 3; ++c) f[3 * i + c] = sb::sum_lanes(d, sum[c]);
  }
}

/// The same, each bond once from its smaller end: e added to both ends' dilatation sums, the force to both
/// ends (`sums`: a scratch array of one value per point).
void lps_scatter_vector(Block& k, double* f, double* sums) {
  const D d;
  const std::uint64_t n = hn::Lanes(d);
  std::fill(sums, sums + k.n, 0.0);
  for (std::size_t i = 0; i < k.n; ++i) {
    const std::uint64_t count = k.upper_offsets[i + 1] - k.upper_offsets[i];
    V sum = hn::Zero(d);
    for_each_group(d, k, i, k.upper_neighbors.data() + k.upper_offsets[i], count,
                   [&](const Group& g, const std::uint32_t* j, M lanes, std::uint64_t b) {
      const V e = hn::IfThenElseZero(lanes, g.e);
      sum = sum + e;
      add_to_partner_values(d, sums, j, e, std::min(n, count - b));
    });
    sums[i] += sb::sum_lanes(d, sum);
    k.theta[i] = 3 * k.inverse_m[i] * (k.delta_volume * sums[i]);  // every smaller point has added its share
  }
  std::fill(f, f + 3 * k.n, 0.0);
  for (std::size_t i = 0; i < k.n; ++i) {
    const std::uint64_t count = k.upper_offsets[i + 1] - k.upper_offsets[i];
    const LpsForce force(d, k, i);
    V sum[3] = {hn::Zero(d), hn::Zero(d), hn::Zero(d)};
    for_each_group(d, k, i, k.upper_neighbors.data() + k.upper_offsets[i], count,
                   [&](const Group& g, const std::uint32_t* j, M lanes, std::uint64_t b) {
      V t[3];
      force(d, g, j, lanes, t);
      const V minus[3] = {hn::Neg(t[0]), hn::Neg(t[1]), hn::Neg(t[2])};
      for (int c = 0; c < 3; ++c) sum[c] = sum[c] + t[c];
      add_to_partners(d, f, j, minus, std::min(n, count - b));
    });
    for (int c = 0; c < 3; ++c) f[3 * i + c] += sb::sum_lanes(d, sum[c]);
  }
}

}  // namespace
}  // namespace peridot::HWY_NAMESPACE
PERIDOT_SIMD_BONDS_END
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace peridot {
HWY_EXPORT(gather_vector);
HWY_EXPORT(scatter_vector);
HWY_EXPORT(buffer_vector);
HWY_EXPORT(lps_gather_vector);
HWY_EXPORT(lps_scatter_vector);
}  // namespace peridot

namespace {

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// The shortest of `repeat` passes, by the wall clock or by this thread's CPU time.
template <class Pass>
double best_seconds(int repeat, bool cpu_clock, Pass&& pass) {
  double best = 1e300;
  for (int r = 0; r < repeat; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = thread_cpu_seconds();
    pass();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    best = std::min(best, cpu_clock ? thread_cpu_seconds() - c0 : wall);
  }
  return best;
}

/// Largest |a − b| relative to the largest |b|, and how many components differ at all.
struct Difference {
  double relative = 0;
  std::size_t unequal = 0;
};

Difference difference(const std::vector<double>& a, const std::vector<double>& b) {
  double largest = 0, worst = 0;
  Difference out;
  for (std::size_t q = 0; q < a.size(); ++q) {
    out.unequal += a[q] != b[q];
    largest = std::max(largest, std::abs(b[q]));
    worst = std::max(worst, std::abs(a[q] - b[q]));
  }
  out.relative = worst / largest;
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  int n[3] = {37, 37, 37}, repeat = 20;
  bool cpu_clock = false;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--n" && a + 3 < argc) for (int d = 0; d < 3; ++d) n[d] = std::stoi(argv[++a]);
    else if (arg == "--repeat" && a + 1 < argc) repeat = std::stoi(argv[++a]);
    else if (arg == "--clock" && a + 1 < argc && (std::string(argv[a + 1]) == "cpu" || std::string(argv[a + 1]) == "wall"))
      cpu_clock = std::string(argv[++a]) == "cpu";
    else {
      std::fprintf(stderr, "usage: bond_once [--n NX NY NZ] [--repeat R] [--clock wall|cpu]\n");
      return 2;
    }
  }
  MpiSession mpi(argc, argv);
  bench::Options o;  // PMB, the constant influence, Δx = 1 mm
  for (int d = 0; d < 3; ++d) o.n[d] = n[d];
  o.steps = 1;
  Simulation sim(bench::benchmark_problem(o));
  const Discretization& disc = sim.discretization();
  const BondList& bonds = sim.bonds();
  Block k;
  k.n = disc.num_points();
  k.x.assign(disc.x.data(), disc.x.data() + 3 * k.n);
  k.volume = disc.volume;
  k.offsets = bonds.offsets;
  k.neighbors = bonds.neighbors;
  // The block's moduli and horizon, as benchmark_problem set them.
  const ElasticConstants& elastic = sim.problem().materials.front().elastic;
  const double delta = sim.problem().bodies.front().horizon, K = elastic.bulk_modulus, G = elastic.shear_modulus;
  k.c = 18 * K / (std::numbers::pi * delta * delta * delta * delta);
  // A smooth displacement of about 1e-4 strain, as bench_explicit's block after some steps.
  k.u.resize(3 * k.n);
  for (std::size_t i = 0; i < k.n; ++i)
    for (int d = 0; d < 3; ++d) k.u[3 * i + d] = 1e-6 * std::sin(300.0 * k.x[3 * i + (d + 1) % 3] + d);
  // Half list and pair index.
  k.upper_offsets.assign(k.n + 1, 0);
  for (std::size_t i = 0; i < k.n; ++i) {
    k.upper_offsets[i + 1] = k.upper_offsets[i];
    for (std::uint64_t b = k.offsets[i]; b < k.offsets[i + 1]; ++b)
      if (k.neighbors[b] > i) k.upper_neighbors.push_back(k.neighbors[b]), ++k.upper_offsets[i + 1];
  }
  k.pair_of.resize(k.neighbors.size());
  for (std::size_t i = 0; i < k.n; ++i)
    for (std::uint64_t b = k.offsets[i]; b < k.offsets[i + 1]; ++b) {
      const std::size_t j = k.neighbors[b];
      const std::size_t lo = std::min(i, j), hi = std::max(i, j);
      const auto first = k.upper_neighbors.begin() + static_cast<std::ptrdiff_t>(k.upper_offsets[lo]);
      const auto last = k.upper_neighbors.begin() + static_cast<std::ptrdiff_t>(k.upper_offsets[lo + 1]);
      k.pair_of[b] = static_cast<std::uint32_t>(std::find(first, last, static_cast<std::uint32_t>(hi)) - k.upper_neighbors.begin());
    }

  k.uniform_volume = k.volume.front();
  for (double v : k.volume)
    if (v != k.uniform_volume) {
      std::fprintf(stderr, "bond_once: the block's volumes are not uniform\n");
      return 1;
    }

  // LPS: m_i = Σ ω ξ² V = δ V Σ |ξ| with ω = δ/|ξ|.
  k.alpha_d = 15 * G, k.beta = 3 * K - 5 * G, k.delta_volume = delta * k.uniform_volume;
  k.inverse_m.resize(k.n), k.theta.assign(k.n, 0.0);
  for (std::size_t i = 0; i < k.n; ++i) {
    double sum = 0;
    for (std::uint64_t b = k.offsets[i]; b < k.offsets[i + 1]; ++b) {
      const std::size_t j = k.neighbors[b];
      double xi2 = 0;
      for (int d = 0; d < 3; ++d) xi2 += (k.x[3 * j + d] - k.x[3 * i + d]) * (k.x[3 * j + d] - k.x[3 * i + d]);
      sum += std::sqrt(xi2);
    }
    k.inverse_m[i] = 1 / (k.delta_volume * sum);
  }

  const double directed = static_cast<double>(k.neighbors.size());
  const std::size_t pairs = k.upper_neighbors.size();
  std::vector<double> f_gather(3 * k.n), f_scatter(3 * k.n), f_buffer(3 * k.n), pair_force(3 * pairs);
  std::vector<double> v_gather(3 * k.n), v_scatter(3 * k.n), v_buffer(3 * k.n);
  std::vector<double> pair_records(3 * pairs);
  simd::apply_environment();
  double t[8];
  t[0] = best_seconds(repeat, cpu_clock, [&] { gather(k, f_gather.data()); });
  t[1] = best_seconds(repeat, cpu_clock, [&] { scatter(k, f_scatter.data()); });
  t[2] = best_seconds(repeat, cpu_clock, [&] { buffered(k, f_buffer.data(), pair_force); });
  t[3] = best_seconds(repeat, cpu_clock, [&] { HWY_DYNAMIC_DISPATCH(gather_vector)(k, v_gather.data()); });
  t[4] = best_seconds(repeat, cpu_clock, [&] { HWY_DYNAMIC_DISPATCH(scatter_vector)(k, v_scatter.data()); });
  t[5] = best_seconds(repeat, cpu_clock, [&] { HWY_DYNAMIC_DISPATCH(buffer_vector)(k, v_buffer.data(), pair_records.data()); });
  std::vector<double> lps_gather(3 * k.n), lps_scatter(3 * k.n), sums(k.n);
  t[6] = best_seconds(repeat, cpu_clock, [&] { HWY_DYNAMIC_DISPATCH(lps_gather_vector)(k, lps_gather.data()); });
  t[7] = best_seconds(repeat, cpu_clock, [&] { HWY_DYNAMIC_DISPATCH(lps_scatter_vector)(k, lps_scatter.data(), sums.data()); });
  const Difference lps = difference(lps_scatter, lps_gather);
  const Difference plain_scatter = difference(f_scatter, f_gather), plain_buffer = difference(f_buffer, f_gather);
  const Difference vector_scatter = difference(v_scatter, v_gather), vector_buffer = difference(v_buffer, v_gather);
  const Difference vector_plain = difference(v_gather, f_gather);
  auto form = [&](const char* name, double s, int bytes, double gather_s, const Difference* from_gather) {
    std::printf("\"%s\": {\"s\": %.5f, \"bond_updates_per_s\": %.4g, \"bytes_per_bond\": %d", name, s, directed / s, bytes);
    if (from_gather)
      std::printf(", \"vs_gather\": %.3f, \"largest_difference\": %.3g, \"components_unequal_to_gather\": %zu",
                  gather_s / s, from_gather->relative, from_gather->unequal);
    std::printf("}, ");
  };
  std::printf("{\"points\": %zu, \"directed_bonds\": %.0f, \"repeat\": %d, \"clock\": \"%s\", \"simd\": \"%s\", ", k.n,
              directed, repeat, cpu_clock ? "cpu" : "wall", simd::active_target().c_str());
  std::printf("\"plain\": {");
  form("gather", t[0], 4, t[0], nullptr);
  form("scatter", t[1], 2, t[0], &plain_scatter);
  form("buffer", t[2], 20, t[0], &plain_buffer);
  std::printf("\"end\": 0}, \"vector\": {");
  form("gather", t[3], 4, t[3], nullptr);
  form("scatter", t[4], 2, t[3], &vector_scatter);
  form("buffer", t[5], 20, t[3], &vector_buffer);
  std::printf("\"vs_plain_gather\": %.3f, \"largest_difference_from_plain\": %.3g}, ", t[0] / t[3], vector_plain.relative);
  std::printf("\"lps_vector\": {");
  form("gather", t[6], 4, t[6], nullptr);
  form("scatter", t[7], 2, t[6], &lps);
  std::printf("\"end\": 0}}\n");
  return 0;
}

#endif  // HWY_ONCE
