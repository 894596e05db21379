#include "peridot/solvers/internal_force.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include "peridot/core/error.hpp"
#include "peridot/damage/critical_stretch.hpp"
#include "peridot/materials/bond_loop.hpp"
#include "peridot/materials/maxwell_element.hpp"
#include "peridot/core/simd.hpp"
#include "peridot/state/bond_runs.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>  // before the per-target code below: every header is compiled for the baseline only
#endif

// The dilatation and force passes are compiled once per SIMD target (core/simd.hpp): Highway's
// foreach_target includes this file again for each, with HWY_TARGET set and that target's instruction
// set enabled between HWY_BEFORE_NAMESPACE and HWY_AFTER_NAMESPACE. Everything else is compiled once.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "peridot/solvers/internal_force.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

// What the per-target passes share, compiled once (on the first inclusion), for the baseline.
#ifndef PERIDOT_INTERNAL_FORCE_SHARED
#define PERIDOT_INTERNAL_FORCE_SHARED
namespace peridot {

using namespace bond_loop;

namespace {

/// t_ji for a neighbour in another block (interfaces only): dispatch on the neighbour's model.
inline double other_block_force_scalar(const ModelContext& ctx, std::size_t block, const KernelFields& s, std::size_t j,
                                       std::uint64_t reverse_bond, double e, double xi, std::uint64_t bond) {
  const MaterialParams& pj = ctx.params[block];
  const double omega = influence(pj.influence, xi, pj.horizon) * bond_scale(ctx, pj, bond);
  // Bonds between a correspondence block and another model's block are refused at set-up
  // (CorrespondenceBlocks), so an interface bond never reaches a model without a bond kernel.
  return with_model(pj.model, [&](auto model) -> double {
    using Model = decltype(model);
    if constexpr (!Model::has_bond_kernel)
      throw std::logic_error("other_block_force_scalar: model " + std::string(Model::name) + " has no bond kernel");
    else
      return end_force_scalar<Model>(pj, ctx.model_params_of<Model>(block), s, j, reverse_bond, e, xi, omega);
  });
}

/// The bond passes hand out a block's points in chunks to whichever thread is free (schedule(dynamic)). On a
/// shared VM one core at a time runs slower for a while; with an even split of the points (schedule(static))
/// the other thread then waits at the barrier. 1 M-point PMB, 2 threads against 1, 4 interleaved pairs each
/// (bench/thread_scaling.py): an even split 1.84× (8.2 % more CPU time than one thread), a split by bond
/// count 1.87× (6.4 %), chunks of 512 points 1.92× (3.3 %). 512 points are about 60 000 bonds, so handing a
/// chunk out costs nothing measurable; small blocks take smaller chunks, at least 16 per thread, so that
/// every thread gets some of a test deck's few hundred points. A point's sums do not depend on the thread
/// that takes it: the same bits for any thread count.
inline int points_per_chunk(BlockRange range) {
  const std::size_t per_thread = (range.end - range.begin) / (16 * static_cast<std::size_t>(omp_get_max_threads()));
  return static_cast<int>(std::clamp<std::size_t>(per_thread, 1, 512));
}

/// Runs f(std::bool_constant<a>{}, std::bool_constant<b>{}): two run-time switches of a bond loop (failure
/// check, thermal stretch) as compile-time ones.
template <class F>
void with_flags(bool a, bool b, F&& f) {
  if (a) {
    if (b) f(std::true_type{}, std::true_type{});
    else f(std::true_type{}, std::false_type{});
  } else {
    if (b) f(std::false_type{}, std::true_type{});
    else f(std::false_type{}, std::false_type{});
  }
}

/// Runs f(std::bool_constant<scaled>{}) for a model that applies the surface correction's bond factor, and
/// f(std::false_type{}) for the others (no instantiation with the factor for them).
template <class Model, class F>
void with_scale(bool scaled, F&& f) {
  if constexpr (Model::corrects_surfaces) {
    if (scaled) return f(std::true_type{});
  }
  f(std::false_type{});
}

/// Critical stretch of a bond of a point of block `block`: the smaller of its two blocks'.
inline double pair_critical_stretch(const ModelContext& ctx, const MaterialParams& p, std::int32_t block, std::uint32_t j) {
  const std::int32_t other = ctx.disc->block[j];
  if (other == block) return p.critical_stretch;
  return std::min(p.critical_stretch, ctx.params[other].critical_stretch);
}

}  // namespace

}  // namespace peridot
#endif  // PERIDOT_INTERNAL_FORCE_SHARED

HWY_BEFORE_NAMESPACE();
#if HWY_TARGET == HWY_AVX3 && defined(__GNUC__) && !defined(__clang__)
// 512-bit vectors for GCC's own vectorised loops too: their mask conversions fail at 256 bits.
#pragma GCC target("prefer-vector-width=512")
#endif
#include "peridot/core/simd_bonds.hpp"
#include "hwy/contrib/math/math-inl.h"  // Exp, for the Gaussian influence
namespace peridot {
namespace HWY_NAMESPACE {

namespace {

/// The bonds of point i to its own block, [b_begin, b_end), for the vectorised loops below, with what
/// they read and write by value (private copies: state/bond_runs.hpp says why).
struct SameBlockRun {
  const double* x;
  const double* u;
  const double* volume;
  const std::uint32_t* reverse;  ///< the partner bond j → i (models with per-bond history)
  double partial_volume_radius;
  /// A bond breaks when e > break_limit ξ (+∞: no failure check this step); it stops carrying force
  /// in this step when e > drop_limit ξ (+∞ when it breaks only after this step's force).
  double break_limit;
  double drop_limit;
  std::uint64_t b_begin, b_end;
  const std::uint32_t* neighbor;  ///< the run's neighbours, padded (this thread's RunScratch)
  const double* intact;           ///< per bond of the run: 1 intact, 0 broken
  double* breaking;               ///< per bond of the run: set to 1 where it breaks now, else 0
  double uniform_volume = 0;      ///< V_j of every partner in the block (ModelContext::uniform_volume), 0: read V_j
  bool family_in_block = false;   ///< ModelContext::family_in_block of the block
  /// Per-point coefficients a model's vector force loop computes once per pass for every point (lps_plastic:
  /// plastic_force_terms), null where there are none.
  const double* point_terms[2] = {nullptr, nullptr};
};

/// The run of a point of `block` (its bonds still to be set, set_same_block_run), for the given limits.
SameBlockRun block_run(const ModelContext& ctx, const double* u, std::int32_t block, double break_limit,
                       double drop_limit) {
  SameBlockRun run{ctx.disc->x.data(), u, ctx.disc->volume.data(), ctx.bonds->reverse.data(),
                   ctx.partial_volume_radius, break_limit, drop_limit, 0, 0, nullptr, nullptr, nullptr};
  const auto b = static_cast<std::size_t>(block);
  if (!ctx.uniform_volume.empty()) run.uniform_volume = ctx.uniform_volume[b];
  run.family_in_block = !ctx.family_in_block.empty() && ctx.family_in_block[b];
  return run;
}

/// Point i's run of bonds to its own block: its whole family where no family of the block leaves it
/// (ModelContext::family_in_block), else looked up.
inline void set_same_block_run(const BondList& bonds, const std::vector<std::int32_t>& blocks, std::size_t i,
                               SameBlockRun& run) {
  if (run.family_in_block) run.b_begin = bonds.offsets[i], run.b_end = bonds.offsets[i + 1];
  else find_same_block_run(bonds, blocks, i, run.b_begin, run.b_end);
}

/// Copies the run's neighbours and flags to `scratch` and points `run` at them.
inline void load_run(RunScratch& scratch, const std::uint32_t* neighbors, const std::uint8_t* broken, SameBlockRun& run) {
  scratch.load(neighbors, broken, run.b_begin, run.b_end);
  run.neighbor = scratch.neighbor.data(), run.intact = scratch.intact.data(), run.breaking = scratch.breaking.data();
}

/// Deformed bond Y = (dy0, dy1, dy2), |ξ| and |Y| of the bond to j, written out per component into the
/// caller's registers: with an inner loop over Dim, or a struct returned (bond_geometry in bond_loop.hpp),
/// GCC 12 leaves the loops below scalar.
template <int Dim>
[[gnu::always_inline]] inline void run_bond_geometry(const SameBlockRun& run, const double x_i[3], const double u_i[3],
                                                     std::uint32_t j, double& dy0, double& dy1, double& dy2,
                                                     double& xi, double& length) {
  const double dx0 = run.x[3 * j] - x_i[0], dx1 = run.x[3 * j + 1] - x_i[1];
  const double dx2 = Dim == 3 ? run.x[3 * j + 2] - x_i[2] : 0.0;
  dy0 = dx0 + (run.u[3 * j] - u_i[0]), dy1 = dx1 + (run.u[3 * j + 1] - u_i[1]);
  dy2 = Dim == 3 ? dx2 + (run.u[3 * j + 2] - u_i[2]) : 0.0;
  double xi2 = dx0 * dx0 + dx1 * dx1, y2 = dy0 * dy0 + dy1 * dy1;
  if constexpr (Dim == 3) xi2 += dx2 * dx2, y2 += dy2 * dy2;
  xi = std::sqrt(xi2), length = std::sqrt(y2);
}

/// The dilatation sum Σ ω ξ e V over the run, and what the bonds that break now took out of it. Thermal: e less
/// the free thermal stretch of point i (bond_loop::mechanical_extension), the failure check on the bond's
/// (bond_mechanical_extension). Scaled: ω times the bond's surface-correction factor.
template <int Dim, class Model, bool CheckFailure, InfluenceKind Influence, bool Thermal, bool Scaled>
inline void run_dilatation(const SameBlockRun& run_in, const MaterialParams& p_in, const KernelFields& s_in,
                           std::size_t i, double& sum_out, double& lost_out) {
  const SameBlockRun run = run_in;  // private copies (SameBlockRun)
  const MaterialParams p = p_in;
  const KernelFields s = s_in;
  const bool partial_volume = run.partial_volume_radius > 0;
  double x_i[3], u_i[3];
  for (int d = 0; d < 3; ++d) x_i[d] = run.x[3 * i + d], u_i[d] = run.u[3 * i + d];
  double sum = 0, lost = 0;
  constexpr bool padded_run = Model::bond_history_arrays == 0 && !Scaled;
  const std::uint64_t count = padded_run ? padded_length(run.b_end - run.b_begin) : run.b_end - run.b_begin;
#pragma omp simd reduction(+ : sum, lost)
  for (std::uint64_t k = 0; k < count; ++k) {
    const std::uint64_t b = run.b_begin + k;  // past the run (padded_run only) never read
    const std::uint32_t j = run.neighbor[k];
    double dy0, dy1, dy2, xi, length;
    run_bond_geometry<Dim>(run, x_i, u_i, j, dy0, dy1, dy2, xi, length);
    const double e = Thermal ? length - xi - s.thermal_stretch[i] * xi : length - xi;
    const double e_bond = Thermal ? length - xi - 0.5 * (s.thermal_stretch[i] + s.thermal_stretch[j]) * xi : e;
    double v = run.volume[j];
    if (partial_volume) v *= partial_volume_factor(xi, p.horizon, run.partial_volume_radius);
    const double omega =
        Scaled ? influence_of<Influence>(xi, p.horizon) * s.bond_scale[b] : influence_of<Influence>(xi, p.horizon);
    const double term = omega * xi * Model::dilatation_extension(s, b, e, xi) * v;
    const bool intact = run.intact[k] != 0;
    const bool breaks = intact && e_bond > run.break_limit * xi;
    if constexpr (CheckFailure) run.breaking[k] = breaks ? 1.0 : 0.0;
    // Weights, not selects: with a select GCC loads V only for the bonds that count, a masked gather it
    // cannot vectorise. term is finite (ξ > 0), so a weight of 0 adds nothing.
    sum += term * ((intact && !breaks) ? 1.0 : 0.0);
    lost += term * (breaks ? 1.0 : 0.0);
  }
  sum_out = sum, lost_out = lost;
}

/// Σ_j of the force density on point i from the bonds of the run; Thermal as for run_dilatation, each end's
/// kernel with its own thermal stretch, Scaled as for run_dilatation (and the model's corrected kernel, if it has
/// one). Not inlined: inlined into the dispatch with both Thermal variants, GCC 12
/// vectorised the loop of the models with partner-bond history (lps_plastic, lps_viscoelastic) differently, 40–60 %
/// slower and with other round-off; on its own each instantiation gets the loop it had before the Thermal switch.
template <int Dim, class Model, bool CheckFailure, InfluenceKind Influence, bool Thermal, bool Scaled>
[[gnu::noinline]] void run_force(const SameBlockRun& run_in, const MaterialParams& p_in, const typename Model::Params& mp_in,
                      const KernelFields& s_in, std::size_t i, double f[3]) {
  const SameBlockRun run = run_in;  // private copies (SameBlockRun)
  const MaterialParams p = p_in;
  const typename Model::Params mp = mp_in;
  const KernelFields s = s_in;
  constexpr bool reads_partner_bond = Model::bond_history_arrays > 0;
  const bool partial_volume = run.partial_volume_radius > 0;
  double x_i[3], u_i[3];
  for (int d = 0; d < 3; ++d) x_i[d] = run.x[3 * i + d], u_i[d] = run.u[3 * i + d];
  double fx = 0, fy = 0, fz = 0;
  constexpr bool padded_run = Model::bond_history_arrays == 0 && !Scaled;
  const std::uint64_t count = padded_run ? padded_length(run.b_end - run.b_begin) : run.b_end - run.b_begin;
#pragma omp simd reduction(+ : fx, fy, fz)
  for (std::uint64_t k = 0; k < count; ++k) {
    const std::uint64_t b = run.b_begin + k;  // past the run (padded_run only) never read
    const std::uint32_t j = run.neighbor[k];
    double dy0, dy1, dy2, xi, length;
    run_bond_geometry<Dim>(run, x_i, u_i, j, dy0, dy1, dy2, xi, length);
    const double e = length - xi;
    const double e_i = Thermal ? e - s.thermal_stretch[i] * xi : e;
    const double e_j = Thermal ? e - s.thermal_stretch[j] * xi : e;
    const double e_bond = Thermal ? e - 0.5 * (s.thermal_stretch[i] + s.thermal_stretch[j]) * xi : e;
    const double omega =
        Scaled ? influence_of<Influence>(xi, p.horizon) * s.bond_scale[b] : influence_of<Influence>(xi, p.horizon);
    const std::uint64_t partner_bond = reads_partner_bond ? run.reverse[b] : 0;
    const double t = end_force_scalar<Scaled, Model>(mp, s, i, b, e_i, xi, omega) +
                     end_force_scalar<Scaled, Model>(mp, s, j, partner_bond, e_j, xi, omega);
    double v = run.volume[j];
    if (partial_volume) v *= partial_volume_factor(xi, p.horizon, run.partial_volume_radius);
    const double carried = t * v / length;
    const bool intact = run.intact[k] != 0;
    if constexpr (CheckFailure) run.breaking[k] = (intact && e_bond > run.break_limit * xi) ? 1.0 : 0.0;
    const double scale = (intact && !(e_bond > run.drop_limit * xi)) ? carried : 0.0;
    fx += scale * dy0;
    fy += scale * dy1;
    if constexpr (Dim == 3) fz += scale * dy2;
  }
  f[0] = fx, f[1] = fy, f[2] = fz;
}

// The vectorised loops of PMB, LPS, lps_plastic and lps_viscoelastic in 2D and 3D (every influence function;
// the two inelastic models' return map and commit too), written once for every target with
// core/simd_bonds.hpp: the partners' x and u loaded whole and transposed, the lengths from simd_bonds::lengths
// (AVX-512's 1/√x estimate, no square root or division; elsewhere two square roots and one division per
// bond), a group of bonds per lane count,
// the bond list read in place (a run with broken bonds: the list of its intact bonds, IntactBonds, so broken
// bonds cost nothing, as in LAMMPS) and the flags of bonds that break set where they break. |ξ| and |Y| are
// within about 1 ulp of the square roots, and a bond at rest still has e = |Y| − |ξ| = 0 exactly (the same
// operations on the same bits), so the answers differ from the portable loops' by round-off. The
// cancellation-free e = η·(2ξ + η)/(|Y| + |ξ|), η = u_j − u_i, cost 3–15 % of the AVX-512 PMB loop in two
// runs and is not used. The scalar target has one lane: it keeps the portable loops above. The inelastic
// models read their per-bond history in place (IntactRun::bond_values) and the partner bond's through the
// reverse index (a gather from another family's bonds: half of lps_plastic's force loop, 37³ points, AVX-512,
// Zen 5). A prefetch four groups ahead made lps_plastic's whole step 13–20 % faster there (three interleaved
// pairs of runs); for lps_viscoelastic's two arrays it was slower, and it has none.
constexpr bool vector_loops = HWY_TARGET != HWY_SCALAR && HWY_TARGET != HWY_EMU128;
PERIDOT_SIMD_BONDS_BEGIN

namespace hn = hwy::HWY_NAMESPACE;
namespace sb = simd_bonds;
using sb::D;
using sb::M;
using sb::V;
using IntactScratch = sb::IntactBonds;

/// The failure check of a pass: none, before any force uses the bond, or after (LAMMPS's order).
enum class FailureCheck { none, before_force, after_force };

/// The check a pass runs, from the run's limits (SameBlockRun): none where they are +∞.
[[maybe_unused]] inline FailureCheck failure_check(const SameBlockRun& run) {
  if (run.break_limit == std::numeric_limits<double>::infinity()) return FailureCheck::none;
  return run.drop_limit == run.break_limit ? FailureCheck::before_force : FailureCheck::after_force;
}

/// Runs f(std::integral_constant<FailureCheck, check>, std::integral_constant<InfluenceKind, kind>) for the
/// run's check and influence.
template <class F>
bool with_check_and_influence(const SameBlockRun& run, InfluenceKind influence, F&& f) {
  const auto with_check = [&](auto kind) {
    switch (failure_check(run)) {
      case FailureCheck::none: f(std::integral_constant<FailureCheck, FailureCheck::none>{}, kind); break;
      case FailureCheck::before_force: f(std::integral_constant<FailureCheck, FailureCheck::before_force>{}, kind); break;
      case FailureCheck::after_force: f(std::integral_constant<FailureCheck, FailureCheck::after_force>{}, kind); break;
    }
    return true;
  };
  if (influence == InfluenceKind::constant)
    return with_check(std::integral_constant<InfluenceKind, InfluenceKind::constant>{});
  if (influence == InfluenceKind::inverse_distance)
    return with_check(std::integral_constant<InfluenceKind, InfluenceKind::inverse_distance>{});
  return with_check(std::integral_constant<InfluenceKind, InfluenceKind::gaussian>{});
}

/// The bonds of a run the loops visit: the run in place, or, with any broken, the list of its intact ones.
struct IntactRun {
  const std::uint32_t* neighbor;
  std::uint64_t count;
  std::uint8_t* broken;  ///< the run's flags (b_begin on)
  const std::uint32_t* position = nullptr;  ///< listed bond → its place in the run (nullptr: in place)

  std::uint64_t first;  ///< the run's first bond in the bond list

  IntactRun(const SameBlockRun& run, const std::uint32_t* neighbors, std::uint8_t* flags, IntactScratch& list)
      : neighbor(neighbors + run.b_begin), count(run.b_end - run.b_begin), broken(flags + run.b_begin),
        first(run.b_begin) {
    // Without broken bonds the list would be the run itself: the same lanes and bits either way.
    if (list.compact(neighbor, broken, count))
      neighbor = list.neighbor.data(), count = list.count, position = list.position.data();
  }

  /// array[bond] of the group's listed bonds b …, bond their index in the bond list (per-bond history); 0 in
  /// the lanes past the list. Read in place while no bond of the run is broken and the group is whole.
  [[gnu::always_inline]] V bond_values(D d, const double* array, std::uint64_t b) const {
    if (!position && b + hn::Lanes(d) <= count) return hn::LoadU(d, array + first + b);
    HWY_ALIGN double lanes[sb::max_lanes] = {};
    for (std::uint64_t k = 0; k < hn::Lanes(d) && b + k < count; ++k) lanes[k] = array[first + place(b + k)];
    return hn::Load(d, lanes);
  }

  /// The partner bonds j → i (`reverse`) of the group's listed bonds b …, as gather indices (0 past the list).
  [[gnu::always_inline]] hn::Vec<hn::RebindToSigned<D>> partner_bonds(D d, const std::uint32_t* reverse,
                                                                       std::uint64_t b) const {
    const hn::RebindToSigned<D> di;
    if (!position && b + hn::Lanes(d) <= count) {
      const hn::Rebind<std::uint32_t, D> d32;
      return hn::BitCast(di, hn::PromoteTo(hn::RebindToUnsigned<D>(), hn::LoadU(d32, reverse + first + b)));
    }
    HWY_ALIGN std::int64_t lanes[sb::max_lanes] = {};
    for (std::uint64_t k = 0; k < hn::Lanes(d) && b + k < count; ++k) lanes[k] = reverse[first + place(b + k)];
    return hn::Load(di, lanes);
  }

  /// array[bond] = v for the group's listed bonds b … in `lanes` (the inverse of bond_values).
  [[gnu::always_inline]] void store_bond_values(D d, double* array, std::uint64_t b, V v, M lanes) const {
    if (!position && b + hn::Lanes(d) <= count && hn::AllTrue(d, lanes)) return hn::StoreU(v, d, array + first + b);
    HWY_ALIGN double values[sb::max_lanes];
    hn::Store(v, d, values);
    for (unsigned m = sb::mask_bits(d, lanes); m != 0; m &= m - 1) {
      const unsigned k = static_cast<unsigned>(__builtin_ctz(m));
      array[first + place(b + k)] = values[k];
    }
  }

  /// Prefetches array[reverse[bond]] for the listed bonds b … b + Lanes − 1 that exist.
  [[gnu::always_inline]] void prefetch_partners(D d, const double* array, const std::uint32_t* reverse,
                                                std::uint64_t b) const {
    for (std::uint64_t k = b; k < b + hn::Lanes(d) && k < count; ++k) __builtin_prefetch(array + reverse[first + place(k)]);
  }

  /// The place in the run of listed bond k.
  [[gnu::always_inline]] std::uint64_t place(std::uint64_t k) const { return position ? position[k] : k; }

  /// Sets the flags of the group's bonds b … in `breaking`. Only when a bond breaks: a masked store, even
  /// of no lane, stalls a later load of the same bytes (no store-to-load forwarding from masked stores);
  /// stored in every group it cost 13 % of the AVX-512 PMB loop on Zen 4.
  [[gnu::always_inline]] void mark_broken(D d, M breaking, std::uint64_t b) const {
    if (hn::AllFalse(d, breaking)) return;
#if HWY_TARGET == HWY_AVX3
    if (!position) {
      _mm_mask_storeu_epi8(broken + b, static_cast<__mmask8>(breaking.raw), _mm_set1_epi8(1));
      return;
    }
#endif
    for (unsigned m = sb::mask_bits(d, breaking); m != 0; m &= m - 1) {
      const std::uint64_t k = b + static_cast<unsigned>(__builtin_ctz(m));
      broken[place(k)] = 1;
    }
  }
};

/// Point i's x and u, broadcast.
struct PointI {
  V x[3], u[3];
  PointI(D d, const SameBlockRun& run, std::size_t i) {
    for (int c = 0; c < 3; ++c) x[c] = hn::Set(d, run.x[3 * i + c]), u[c] = hn::Set(d, run.u[3 * i + c]);
  }
};

/// The geometry of a group of bonds of point i: Y, |ξ|, |Y|, 1/(|ξ||Y|) and e = |Y| − |ξ|. In 2D the third
/// components are left out, as the portable loops do (run_bond_geometry).
template <int Dim>
struct BondGroup {
  V dy[3], xi2, xi, length, inverse_product, e;

  [[gnu::always_inline]] BondGroup(D d, const SameBlockRun& run, const PointI& point, const std::uint32_t* j) {
    V dx[3], du[3];
    sb::load_vec3(d, run.x, j, dx);
    sb::load_vec3(d, run.u, j, du);
    for (int c = 0; c < 3; ++c) dx[c] = dx[c] - point.x[c], du[c] = du[c] - point.u[c], dy[c] = dx[c] + du[c];
    if constexpr (Dim == 2) dx[2] = dy[2] = hn::Zero(d);
    xi2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
    const V y2 = dy[0] * dy[0] + dy[1] * dy[1] + dy[2] * dy[2];
    sb::lengths(d, xi2, y2, xi, length, inverse_product);  // 1/(|ξ||Y|) unused in the dilatation: not computed
    e = length - xi;
  }
};

/// Runs body(group, j, lanes, b) for the listed bonds' groups in order (b the first bond, j its
/// neighbours, lanes those inside the list), two groups per iteration while two are whole, so that the
/// scheduler sees two independent chains of loads, transposes and Newton steps side by side (37³ PMB and LPS
/// 2–4 % faster with AVX-512 in 3 interleaved pairs of runs; the sums are added in the same order, so the same
/// bits).
template <int Dim, class Body>
[[gnu::always_inline]] inline void for_each_group(D d, const SameBlockRun& run, const PointI& point,
                                                  const IntactRun& bonds, Body&& body) {
  const std::uint64_t n = hn::Lanes(d);
  const M all = hn::FirstN(d, n);
  std::uint64_t b = 0;
  for (; b + 2 * n <= bonds.count; b += 2 * n) {
    const std::uint32_t* j = bonds.neighbor + b;
    const BondGroup<Dim> first(d, run, point, j), second(d, run, point, j + n);
    body(first, j, all, b);
    body(second, j + n, all, b + n);
  }
  for (; b + n <= bonds.count; b += n) body(BondGroup<Dim>(d, run, point, bonds.neighbor + b), bonds.neighbor + b, all, b);
  if (b == bonds.count) return;
  if (bonds.count >= n) {
    // The last partial group as the list's last n bonds with the lanes done already masked off: no copy of
    // the neighbours (2D LPS, 28 bonds per family, was 20 % slower with AVX-512 than with AVX2 with it).
    const std::uint64_t start = bonds.count - n;
    body(BondGroup<Dim>(d, run, point, bonds.neighbor + start), bonds.neighbor + start,
         hn::Not(hn::FirstN(d, static_cast<std::size_t>(b - start))), start);
    return;
  }
  std::uint32_t tail[sb::max_lanes];
  const std::uint32_t* j;
  const M lanes = sb::group_lanes(d, bonds.neighbor, b, bonds.count, tail, j);
  body(BondGroup<Dim>(d, run, point, j), j, lanes, b);
}

/// ω of a group for the Gaussian influence, exp(−ξ²/δ²) (Highway's Exp: within a few ulp of std::exp);
/// `minus_inverse_h2` = −1/δ². The other influences are folded into each loop's constants and lengths.
template <int Dim>
[[gnu::always_inline]] inline V gaussian_influence(D d, const BondGroup<Dim>& g, V minus_inverse_h2) {
  return hn::Exp(d, g.xi2 * minus_inverse_h2);
}

/// c V_j times the partial-volume factor of the bonds of a group, for a constant c of the run.
struct PartnerVolume {
  bool uniform;  // lattice blocks: one volume for all, broadcast instead of gathered (a ninth of PMB's loads)
  double r;
  V c, c_uniform_volume, outer, half_over_r;

  PartnerVolume(D d, const SameBlockRun& run, double constant, double horizon)
      : uniform(run.uniform_volume > 0), r(run.partial_volume_radius), c(hn::Set(d, constant)),
        c_uniform_volume(hn::Set(d, constant * run.uniform_volume)), outer(hn::Set(d, horizon + r)),
        half_over_r(hn::Set(d, r > 0 ? 0.5 / r : 0.0)) {}

  [[gnu::always_inline]] V operator()(D d, const SameBlockRun& run, const std::uint32_t* j, V xi) const {
    V cv = c_uniform_volume;
    if (!uniform) cv = c * sb::gather(d, run.volume, j);
    if (r > 0)  // partial_volume_factor: (δ + r − ξ)/(2r), clipped to [0, 1]
      cv = cv * hn::Min(hn::Max((outer - xi) * half_over_r, hn::Zero(d)), hn::Set(d, 1.0));
    return cv;
  }
};

/// Which lanes of a group carry force and which break now, for the pass's check.
template <FailureCheck Check, int Dim>
[[gnu::always_inline]] inline M carrying_lanes(D d, M lanes, const BondGroup<Dim>& g, V break_limit, M& breaking) {
  breaking = hn::FirstN(d, 0);
  if constexpr (Check == FailureCheck::none) return lanes;
  breaking = hn::And(lanes, hn::Gt(g.e, break_limit * g.xi));
  return Check == FailureCheck::before_force ? hn::AndNot(breaking, lanes) : lanes;
}

/// The force on point i from its listed bonds, Σ carried(g, j) Y, with the pass's failure check: the bonds
/// that break now get their flags, and carry nothing when they break before the force.
template <int Dim, FailureCheck Check, class Carried>
[[gnu::always_inline]] inline void sum_bond_forces(const SameBlockRun& run, std::size_t i, const IntactRun& bonds,
                                                   Carried&& carried_of, double f[3]) {
  const D d;
  const PointI point(d, run, i);
  const V break_limit = hn::Set(d, run.break_limit);
  V fx = hn::Zero(d), fy = fx, fz = fx;
  for_each_group<Dim>(d, run, point, bonds, [&](const BondGroup<Dim>& g, const std::uint32_t* j, M lanes,
                                                std::uint64_t b) __attribute__((always_inline)) {
    const V carried = carried_of(g, j, b);
    M breaking;
    const M carries = carrying_lanes<Check>(d, lanes, g, break_limit, breaking);
    bonds.mark_broken(d, breaking, b);
    const V scale = hn::IfThenElseZero(carries, carried);
    fx = fx + scale * g.dy[0], fy = fy + scale * g.dy[1], fz = fz + scale * g.dy[2];  // no fused multiply-add (CMakeLists.txt)
  });
  f[0] = sb::sum_lanes(d, fx), f[1] = sb::sum_lanes(d, fy), f[2] = sb::sum_lanes(d, fz);
}

/// PMB force on point i from its run: c ω e V_j/(|ξ||Y|) along Y per bond (Pmb::force_scalar of both ends),
/// δ of the 1/|ξ| influence and c in one constant, and a uniform V_j too.
template <int Dim, InfluenceKind Influence, FailureCheck Check>
void run_force_pmb_vector(const SameBlockRun& run, const MaterialParams& p, const Pmb::Params& mp, std::size_t i,
                          const IntactRun& bonds, double f[3]) {
  const D d;
  const PartnerVolume volume(
      d, run, Influence == InfluenceKind::inverse_distance ? mp.micromodulus * p.horizon : mp.micromodulus, p.horizon);
  const V minus_inverse_h2 = hn::Set(d, -1 / (p.horizon * p.horizon));
  sum_bond_forces<Dim, Check>(run, i, bonds, [&](const BondGroup<Dim>& g, const std::uint32_t* j, std::uint64_t)
                                                  __attribute__((always_inline)) {
    const V cv = volume(d, run, j, g.xi);
    // ω/(|ξ||Y|): 1/(|ξ|²|Y|) = |Y|/(|ξ||Y|)², δ being in c; 1/(|ξ||Y|); exp(−ξ²/δ²)/(|ξ||Y|)
    V weight = g.inverse_product;
    if constexpr (Influence == InfluenceKind::inverse_distance) weight = g.inverse_product * g.inverse_product * g.length;
    if constexpr (Influence == InfluenceKind::gaussian) weight = gaussian_influence(d, g, minus_inverse_h2) * weight;
    return (cv * weight) * g.e;
  }, f);
}

/// LPS dilatation sum Σ ω ξ e V_j over point i's run (δ of the 1/|ξ| influence in the volume constant), and
/// what the bonds that break now took out of it; for lps_plastic Σ ω ξ (e − e^dp) V_j (its (P7)).
template <int Dim, class Model, InfluenceKind Influence, FailureCheck Check>
void run_dilatation_lps_vector(const SameBlockRun& run, const MaterialParams& p, const KernelFields& s, std::size_t i,
                               const IntactRun& bonds, double& sum_out, double& lost_out) {
  static_assert(Check != FailureCheck::after_force, "the dilatation pass checks before the force");
  const D d;
  const PointI point(d, run, i);
  const PartnerVolume volume(d, run, Influence == InfluenceKind::inverse_distance ? p.horizon : 1.0, p.horizon);
  const V break_limit = hn::Set(d, run.break_limit), minus_inverse_h2 = hn::Set(d, -1 / (p.horizon * p.horizon));
  V sum = hn::Zero(d), lost = sum;
  for_each_group<Dim>(d, run, point, bonds, [&](const BondGroup<Dim>& g, const std::uint32_t* j, M lanes,
                                                std::uint64_t b) __attribute__((always_inline)) {
    const V cv = volume(d, run, j, g.xi);
    V e = g.e;
    if constexpr (std::is_same_v<Model, LpsPlastic>) e = e - bonds.bond_values(d, s.bond[0], b);
    // ω ξ: δ (in cv), ξ, or exp(−ξ²/δ²) ξ
    V term = (Influence == InfluenceKind::inverse_distance ? e : e * g.xi) * cv;
    if constexpr (Influence == InfluenceKind::gaussian) term = gaussian_influence(d, g, minus_inverse_h2) * term;
    M breaking;
    const M counts = carrying_lanes<Check>(d, lanes, g, break_limit, breaking);
    bonds.mark_broken(d, breaking, b);
    sum = sum + hn::IfThenElseZero(counts, term);
    if constexpr (Check != FailureCheck::none) lost = lost + hn::IfThenElseZero(breaking, term);
  });
  sum_out = sb::sum_lanes(d, sum), lost_out = sb::sum_lanes(d, lost);
}

/// LPS force on point i from its run. Lps::force_scalar of both ends, t = ω[a (e − θξ/n) α_d + a θ ξ α_v]
/// with a = 1/m, summed and regrouped as t = ω[α_d (a_i + a_j) e + β ξ (a_i θ_i + a_j θ_j)], β = α_v − α_d/n;
/// with ω = δ/|ξ| that is δ[α_d (a_i + a_j) e + β ξ (a_i θ_i + a_j θ_j)]/|ξ|, δ in the volume constant. θ_j and
/// a_j are gathered.
template <int Dim, InfluenceKind Influence, FailureCheck Check>
void run_force_lps_vector(const SameBlockRun& run, const MaterialParams& p, const Lps::Params& mp, const KernelFields& s,
                          std::size_t i, const IntactRun& bonds, double f[3]) {
  const D d;
  const PartnerVolume volume(d, run, Influence == InfluenceKind::inverse_distance ? p.horizon : 1.0, p.horizon);
  const double beta = mp.alpha_volumetric - mp.alpha_deviatoric * mp.inverse_dilatation_factor;
  const V alpha_d = hn::Set(d, mp.alpha_deviatoric), beta_v = hn::Set(d, beta);
  const V a_i = hn::Set(d, s.inverse_m[i]), a_theta_i = hn::Set(d, s.inverse_m[i] * s.theta[i]);
  const V minus_inverse_h2 = hn::Set(d, -1 / (p.horizon * p.horizon));
  sum_bond_forces<Dim, Check>(run, i, bonds, [&](const BondGroup<Dim>& g, const std::uint32_t* j, std::uint64_t)
                                                  __attribute__((always_inline)) {
    const V a_j = sb::gather(d, s.inverse_m, j);
    const V theta_j = sb::gather(d, s.theta, j);
    const V cv = volume(d, run, j, g.xi);
    const V deviatoric = alpha_d * (a_i + a_j), volumetric = beta_v * (a_theta_i + a_j * theta_j);
    // t/|Y| = |ξ| t/(|ξ||Y|): with ω = δ/|ξ|, (α_d(a_i + a_j) e + β ξ (…)) /(|ξ||Y|)
    const V t_xi = deviatoric * g.e + volumetric * g.xi;
    if constexpr (Influence == InfluenceKind::inverse_distance) return t_xi * cv * g.inverse_product;
    V carried = t_xi * cv * g.xi * g.inverse_product;
    if constexpr (Influence == InfluenceKind::gaussian) carried = gaussian_influence(d, g, minus_inverse_h2) * carried;
    return carried;
  }, f);
}

/// ω/|Y| of a group, δ of the 1/|ξ| influence left to the caller's constant: |ξ|/(|ξ||Y|), 1/(|ξ||Y|) or
/// exp(−ξ²/δ²)|ξ|/(|ξ||Y|).
template <InfluenceKind Influence, int Dim>
[[gnu::always_inline]] inline V influence_over_length(D d, const BondGroup<Dim>& g, V minus_inverse_h2) {
  if constexpr (Influence == InfluenceKind::inverse_distance) return g.inverse_product;
  const V over_length = g.xi * g.inverse_product;
  if constexpr (Influence == InfluenceKind::gaussian) return gaussian_influence(d, g, minus_inverse_h2) * over_length;
  return over_length;
}

/// A = α_d r/m and B = (α_v θ − α_d (r(θ/n + ρ) + q))/m of lps_plastic's force (run_force_plastic_vector) for
/// every point, owned and ghost, into terms[0, n) and terms[n, 2n): computed once per pass, so that the force
/// loop gathers two values per partner instead of the five they are made of.
[[maybe_unused]] void plastic_force_terms(const LpsPlastic::Params& mp, const KernelFields& s, std::size_t n,
                                          std::vector<double>& terms) {
  terms.resize(2 * n);
  const double* r = s.point[LpsPlastic::yield_scale];
  const double* rho = s.point[LpsPlastic::released_extension];
  const double* q = s.point[LpsPlastic::deviatoric_moment];
  double* A = terms.data();
  double* B = terms.data() + n;
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const double a = s.inverse_m[i], theta = s.theta[i];
    A[i] = mp.alpha_deviatoric * a * r[i];
    B[i] = a * (mp.alpha_volumetric * theta -
                mp.alpha_deviatoric * (r[i] * (theta * mp.inverse_dilatation_factor + rho[i]) + q[i]));
  }
}

/// lps_plastic force on point i from its run. LpsPlastic::force_scalar of one end, regrouped:
/// t = ω[A e + B ξ − A e^dp], A = α_d r/m, B = (α_v θ − α_d (r(θ/n + ρ) + q))/m (r, ρ, q of the end's return
/// map; A and B of every point in run.point_terms); the two ends summed, e^dp of the bond and of its partner
/// bond (gathered through `reverse`).
template <int Dim, InfluenceKind Influence, FailureCheck Check>
void run_force_plastic_vector(const SameBlockRun& run, const MaterialParams& p, const LpsPlastic::Params& /*in A, B*/,
                              const KernelFields& s, std::size_t i, const IntactRun& bonds, double f[3]) {
  const D d;
  const PartnerVolume volume(d, run, Influence == InfluenceKind::inverse_distance ? p.horizon : 1.0, p.horizon);
  const double* A = run.point_terms[0];  // A and B of every point (plastic_force_terms)
  const double* B = run.point_terms[1];
  const V A_i = hn::Set(d, A[i]), B_i = hn::Set(d, B[i]);
  const V minus_inverse_h2 = hn::Set(d, -1 / (p.horizon * p.horizon));
  sum_bond_forces<Dim, Check>(run, i, bonds, [&](const BondGroup<Dim>& g, const std::uint32_t* j, std::uint64_t b)
                                                  __attribute__((always_inline)) {
    const V A_j = sb::gather(d, A, j), B_j = sb::gather(d, B, j);
    bonds.prefetch_partners(d, s.bond[0], run.reverse, b + 4 * hn::Lanes(d));
    const V plastic = bonds.bond_values(d, s.bond[0], b);
    const V partner_plastic = hn::GatherIndex(d, s.bond[0], bonds.partner_bonds(d, run.reverse, b));
    const V t_over_omega = (A_i + A_j) * g.e + (B_i + B_j) * g.xi - (A_i * plastic + A_j * partner_plastic);
    return t_over_omega * volume(d, run, j, g.xi) * influence_over_length<Influence>(d, g, minus_inverse_h2);
  }, f);
}

/// lps_viscoelastic force on point i from its run. LpsViscoelastic::force_scalar of one end, regrouped with
/// γ = 1 − λβ and c = 1 − ε − β: t = ω[α_d γ a e + (α_v − α_d γ/n) a θ ξ − α_d λ a (ε e^b + c e^d_n)], a = 1/m;
/// the LPS loop with α_d γ for α_d, and the history of the bond and of its partner bond.
template <int Dim, InfluenceKind Influence, FailureCheck Check>
void run_force_viscoelastic_vector(const SameBlockRun& run, const MaterialParams& p, const LpsViscoelastic::Params& mp,
                                   const KernelFields& s, std::size_t i, const IntactRun& bonds, double f[3]) {
  const D d;
  const PartnerVolume volume(d, run, Influence == InfluenceKind::inverse_distance ? p.horizon : 1.0, p.horizon);
  const double gamma = 1 - mp.relaxing_fraction * mp.viscous_ramp;
  const double beta = mp.alpha_volumetric - mp.alpha_deviatoric * gamma * mp.inverse_dilatation_factor;
  const V deviatoric = hn::Set(d, mp.alpha_deviatoric * gamma), volumetric = hn::Set(d, beta);
  const V viscous = hn::Set(d, mp.alpha_deviatoric * mp.relaxing_fraction);
  const V decay = hn::Set(d, mp.viscous_decay), ramp = hn::Set(d, 1 - mp.viscous_decay - mp.viscous_ramp);
  const V a_i = hn::Set(d, s.inverse_m[i]), a_theta_i = hn::Set(d, s.inverse_m[i] * s.theta[i]);
  const V minus_inverse_h2 = hn::Set(d, -1 / (p.horizon * p.horizon));
  const double* back = s.bond[0];
  const double* previous = s.bond[1];
  sum_bond_forces<Dim, Check>(run, i, bonds, [&](const BondGroup<Dim>& g, const std::uint32_t* j, std::uint64_t b)
                                                  __attribute__((always_inline)) {
    const V a_j = sb::gather(d, s.inverse_m, j), theta_j = sb::gather(d, s.theta, j);
    const V history_i = decay * bonds.bond_values(d, back, b) + ramp * bonds.bond_values(d, previous, b);
    const auto partner = bonds.partner_bonds(d, run.reverse, b);
    const V history_j = decay * hn::GatherIndex(d, back, partner) + ramp * hn::GatherIndex(d, previous, partner);
    const V t_over_omega = deviatoric * (a_i + a_j) * g.e + volumetric * (a_theta_i + a_j * theta_j) * g.xi -
                           viscous * (a_i * history_i + a_j * history_j);
    return t_over_omega * volume(d, run, j, g.xi) * influence_over_length<Influence>(d, g, minus_inverse_h2);
  }, f);
}

/// ω of a group: 1, δ/|ξ| (as δ|Y|/(|ξ||Y|)) or exp(−ξ²/δ²).
template <InfluenceKind Influence, int Dim>
[[gnu::always_inline]] inline V group_influence(D d, const BondGroup<Dim>& g, V horizon, V minus_inverse_h2) {
  if constexpr (Influence == InfluenceKind::inverse_distance) return horizon * g.length * g.inverse_product;
  if constexpr (Influence == InfluenceKind::gaussian) return gaussian_influence(d, g, minus_inverse_h2);
  (void)g, (void)horizon, (void)minus_inverse_h2;
  return hn::Set(d, 1.0);
}

/// lps_viscoelastic's commit (LpsViscoelastic::commit) over point i's run: e^b and e^d of every intact bond
/// advance (V3), and the dissipation of the step (V4) is returned.
template <int Dim, InfluenceKind Influence>
double run_viscous_commit_vector(const SameBlockRun& run, const MaterialParams& p, const LpsViscoelastic::Params& mp,
                                 const KernelFields& s, std::size_t i, const IntactRun& bonds, double* back,
                                 double* previous, double dt) {
  const D d;
  const PointI point(d, run, i);
  const PartnerVolume volume(d, run, 1.0, p.horizon);
  const double tau = mp.relaxation_time;
  const V shift = hn::Set(d, s.theta[i] * mp.inverse_dilatation_factor);
  const V decay = hn::Set(d, mp.viscous_decay), one_minus = hn::Set(d, 1 - mp.viscous_decay);
  const V ramp = hn::Set(d, mp.viscous_ramp);
  // MaxwellStep::integral with ρ = (e^d − e^d_n)/Δt, x₀ = e^d_n − e^b_n
  const MaxwellStep maxwell = dt > 0 ? MaxwellStep(tau, dt) : MaxwellStep();
  const V inverse_dt = hn::Set(d, dt > 0 ? 1 / dt : 0.0), start_square = hn::Set(d, maxwell.start_square);
  const V cross = hn::Set(d, maxwell.cross), rate_square = hn::Set(d, maxwell.rate_square);
  const V horizon = hn::Set(d, p.horizon), minus_inverse_h2 = hn::Set(d, -1 / (p.horizon * p.horizon));
  V dissipated = hn::Zero(d);
  for_each_group<Dim>(d, run, point, bonds, [&](const BondGroup<Dim>& g, const std::uint32_t* j, M lanes,
                                                std::uint64_t b) __attribute__((always_inline)) {
    const V ed = g.e - shift * g.xi;
    const V back_n = bonds.bond_values(d, back, b), previous_n = bonds.bond_values(d, previous, b);
    if (dt > 0) {
      const V rate = (ed - previous_n) * inverse_dt, start = previous_n - back_n;
      const V integral = start * start * start_square + start * rate * cross + rate * rate * rate_square;
      const V omega_v = group_influence<Influence>(d, g, horizon, minus_inverse_h2) * volume(d, run, j, g.xi);
      dissipated = dissipated + hn::IfThenElseZero(lanes, omega_v * integral);
    }
    bonds.store_bond_values(d, back, b, decay * back_n + one_minus * previous_n + ramp * (ed - previous_n), lanes);
    bonds.store_bond_values(d, previous, b, ed, lanes);
  });
  return mp.relaxing_fraction * mp.alpha_deviatoric * s.inverse_m[i] / tau * sb::sum_lanes(d, dissipated);
}

/// lps_plastic's commit (LpsPlastic::commit) over point i's run, for a point whose step was not elastic or
/// lost bonds: e^dp of every intact bond advances by (P8) and (P4).
template <int Dim>
void run_plastic_commit_vector(const SameBlockRun& run, const LpsPlastic::Params& mp, const KernelFields& s,
                               std::size_t i, const IntactRun& bonds, double r, double released, double* plastic) {
  const D d;
  const PointI point(d, run, i);
  const V shift = hn::Set(d, s.theta[i] * mp.inverse_dilatation_factor), rho = hn::Set(d, released);
  const V flow = hn::Set(d, 1 - r);
  for_each_group<Dim>(d, run, point, bonds, [&](const BondGroup<Dim>& g, const std::uint32_t*, M lanes,
                                                std::uint64_t b) __attribute__((always_inline)) {
    const V ed = g.e - shift * g.xi;
    const V before = bonds.bond_values(d, plastic, b) + rho * g.xi;  // (P8)
    bonds.store_bond_values(d, plastic, b, before + flow * (ed - before), lanes);  // (P4)
  });
}

/// The sums of lps_plastic's return map over point i's run (LpsPlastic::prepare): ‖t^d_tr‖² = Σ (t^d_tr)² V,
/// S = Σ (t^d_tr)²/ω V and Σ ω ξ (e^d − e^dp_n) V, with e^d − e^dp_n = (e − e^dp_n) − (θ/n + ρ)ξ and
/// t^d_tr = α ω (e^d − e^dp_n), α = α_d/m.
template <int Dim, InfluenceKind Influence>
void run_return_map_sums_vector(const SameBlockRun& run, const MaterialParams& p, const LpsPlastic::Params& mp,
                                const KernelFields& s, std::size_t i, const IntactRun& bonds, double& norm2_out,
                                double& weighted_out, double& along_out) {
  const D d;
  const PointI point(d, run, i);
  const PartnerVolume volume(d, run, 1.0, p.horizon);
  const V alpha = hn::Set(d, mp.alpha_deviatoric * s.inverse_m[i]);
  const V shift = hn::Set(d, s.theta[i] * mp.inverse_dilatation_factor + s.point[LpsPlastic::released_extension][i]);
  const V horizon = hn::Set(d, p.horizon), minus_inverse_h2 = hn::Set(d, -1 / (p.horizon * p.horizon));
  V norm2 = hn::Zero(d), weighted = norm2, along = norm2;
  for_each_group<Dim>(d, run, point, bonds, [&](const BondGroup<Dim>& g, const std::uint32_t* j, M lanes,
                                                std::uint64_t b) __attribute__((always_inline)) {
    const V omega = group_influence<Influence>(d, g, horizon, minus_inverse_h2);
    const V elastic = (g.e - bonds.bond_values(d, s.bond[0], b)) - shift * g.xi;
    const V omega_v = hn::IfThenElseZero(lanes, omega * volume(d, run, j, g.xi));
    const V t = alpha * elastic;  // t^d_tr/ω
    const V t2_omega_v = t * t * omega_v;
    weighted = weighted + t2_omega_v;
    norm2 = norm2 + t2_omega_v * omega;
    along = along + omega_v * g.xi * elastic;
  });
  norm2_out = sb::sum_lanes(d, norm2), weighted_out = sb::sum_lanes(d, weighted), along_out = sb::sum_lanes(d, along);
}

PERIDOT_SIMD_BONDS_END

/// The models with vector loops (the others take the portable loops above).
template <class Model>
constexpr bool has_vector_loops = std::is_same_v<Model, Pmb> || std::is_same_v<Model, Lps> ||
                                  std::is_same_v<Model, LpsPlastic> || std::is_same_v<Model, LpsViscoelastic>;

/// Point i's force from its own block through a vector loop, where one applies (2D or 3D, a model with vector
/// loops, a target with more than one lane); false elsewhere, and then nothing is done. It reads and writes the
/// bond list itself.
template <int Dim, class Model>
bool force_in_place(const SameBlockRun& run, const MaterialParams& p, const typename Model::Params& mp,
                    const KernelFields& s, std::size_t i, const std::uint32_t* neighbors, std::uint8_t* broken,
                    IntactScratch& scratch, double f[3]) {
  if constexpr (vector_loops && (Dim == 2 || Dim == 3) && has_vector_loops<Model>) {
    return with_check_and_influence(run, p.influence, [&](auto check, auto kind) {
      const IntactRun bonds(run, neighbors, broken, scratch);
      if constexpr (std::is_same_v<Model, Pmb>)
        run_force_pmb_vector<Dim, kind.value, check.value>(run, p, mp, i, bonds, f);
      else if constexpr (std::is_same_v<Model, Lps>)
        run_force_lps_vector<Dim, kind.value, check.value>(run, p, mp, s, i, bonds, f);
      else if constexpr (std::is_same_v<Model, LpsPlastic>)
        run_force_plastic_vector<Dim, kind.value, check.value>(run, p, mp, s, i, bonds, f);
      else
        run_force_viscoelastic_vector<Dim, kind.value, check.value>(run, p, mp, s, i, bonds, f);
    });
  }
  (void)run, (void)p, (void)mp, (void)s, (void)i, (void)neighbors, (void)broken, (void)scratch, (void)f;
  return false;
}

/// Point i's dilatation sum from its own block through the vector LPS loop, where it applies (2D or 3D, a model
/// with vector loops and a dilatation, a target with more than one lane); false elsewhere, and then nothing is
/// done.
template <int Dim, class Model>
bool dilatation_in_place(const SameBlockRun& run, const MaterialParams& p, const KernelFields& s, std::size_t i,
                         const std::uint32_t* neighbors, std::uint8_t* broken, IntactScratch& scratch, double& sum,
                         double& lost) {
  if constexpr (vector_loops && (Dim == 2 || Dim == 3) && has_vector_loops<Model> && Model::uses_dilatation) {
    if (failure_check(run) == FailureCheck::after_force) return false;  // never: this pass checks before the force
    return with_check_and_influence(run, p.influence, [&](auto check, auto kind) {
      const IntactRun bonds(run, neighbors, broken, scratch);
      if constexpr (check.value != FailureCheck::after_force)
        run_dilatation_lps_vector<Dim, Model, kind.value, check.value>(run, p, s, i, bonds, sum, lost);
    });
  }
  (void)run, (void)p, (void)s, (void)i, (void)neighbors, (void)broken, (void)scratch, (void)sum, (void)lost;
  return false;
}
}  // namespace

void dilatation_pass(const ModelContext& ctx, const VectorField& u, std::vector<double>& theta, bool fail_bonds,
                     MaterialHistory* history) {
  const BondFailure failure(ctx);
  const std::vector<double>& inverse_m = ctx.inverse_weighted_volume;
  const double* x = ctx.disc->x.data();
  const double* up = u.data();
  BondList& bonds = *ctx.bonds;  // broken flags are written when fail_bonds
  const std::uint32_t* neighbors = bonds.neighbors.data();
  std::uint8_t* broken = bonds.broken.data();
  const auto& blocks = ctx.disc->block;
  theta.resize(ctx.disc->num_points());
  const KernelFields fields = kernel_fields(ctx, theta, history);
  // With protected points the failure check needs both ends' flags: the general path only.
  const bool vector_path = failure.no_fail == nullptr;
  const bool thermal = fields.thermal_stretch != nullptr;  // the AVX-512 loops have no thermal stretch
  for_each_block(ctx, [&](auto dim, auto model, const MaterialParams& p, const auto& mp, BlockRange range) {
    constexpr int Dim = decltype(dim)::value;
    using Model = decltype(model);
    const double break_limit = fail_bonds ? p.critical_stretch : std::numeric_limits<double>::infinity();
    const bool scaled = p.surface_correction && fields.bond_scale;  // the AVX-512 loops have no bond factor
    // The run loops have no quadrature direction weight: such a block takes the general path.
    const bool runs = vector_path && !p.quadrature.on;
    constexpr int released_array = Model::released_extension_array;
    double* released = nullptr;  // what θ lost to the bonds breaking now, where the model keeps it
    if constexpr (released_array >= 0)
      if (history && history->point.size() > static_cast<std::size_t>(released_array))
        released = history->point[released_array].data();
    const int chunk = points_per_chunk(range);
    // Clang cannot reach compute_dilatation's locals from the lambda inside the parallel region below:
    // this lambda's own names for them.
    const double* const xs = x;
    const BondFailure& fails = failure;
#pragma omp parallel
    {
      RunScratch scratch;
      IntactScratch intact;
      SameBlockRun run = block_run(ctx, up, blocks[range.begin], break_limit, break_limit);
#pragma omp for schedule(dynamic, chunk)
      for (std::size_t i = range.begin; i < range.end; ++i) {
        set_same_block_run(bonds, blocks, i, run);
        double sum = 0, lost = 0;
        const bool in_place = runs && !thermal && !scaled &&
                              dilatation_in_place<Dim, Model>(run, p, fields, i, neighbors, broken, intact, sum, lost);
        if (runs && !in_place) {
          load_run(scratch, neighbors, broken, run);
          with_influence(p.influence, [&](auto kind) {
            with_flags(fail_bonds, thermal, [&](auto check, auto heated) {
              with_scale<Model>(scaled, [&](auto corrected) {
                run_dilatation<Dim, Model, check.value, kind.value, heated.value, corrected.value>(run, p, fields, i, sum,
                                                                                                  lost);
              });
            });
          });
          if (fail_bonds) scratch.store(broken, run.b_begin, run.b_end);
        }
        // The general path: every bond of a protected deck, and interface bonds.
        auto general_bond = [&](std::uint64_t b) {
          if (broken[b]) return;
          const std::uint32_t j = neighbors[b];
          const BondGeometry<Dim> g = bond_geometry<Dim>(xs, up, i, j);
          const double term = influence(p.influence, g.xi, p.horizon) * bond_scale(ctx, p, b) * g.xi *
                              model.dilatation_extension(fields, b, mechanical_extension(ctx, i, g), g.xi) *
                              neighbor_volume(ctx, i, j, g.xi);
          if (fail_bonds && fails.fails(i, j, bond_mechanical_extension(ctx, i, j, g.e, g.xi), g.xi,
                                          pair_critical_stretch(ctx, p, blocks[i], j))) {
            broken[b] = 1;
            lost += term;
            return;
          }
          sum += term;
        };
        if (!runs)
          for (std::uint64_t b = run.b_begin; b < run.b_end; ++b) general_bond(b);
        for (std::uint64_t b = bonds.offsets[i]; b < run.b_begin; ++b) general_bond(b);
        for (std::uint64_t b = run.b_end; b < bonds.offsets[i + 1]; ++b) general_bond(b);
        theta[i] = Model::dilatation(mp, fields, i, sum, Dim);
        if (released && fail_bonds) released[i] = lost * inverse_m[i];
      }
    }
  });
}

void force_pass(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta, VectorField& f,
                bool fail_bonds, const MaterialHistory* history) {
  const BondFailure failure(ctx);
  const KernelFields fields = kernel_fields(ctx, theta, history);
  const double* x = ctx.disc->x.data();
  const double* up = u.data();
  double* fp = f.data();
  const BondList& bonds = *ctx.bonds;
  const auto& blocks = ctx.disc->block;
  const std::uint32_t* neighbors = bonds.neighbors.data();
  const std::uint32_t* reverse = bonds.reverse.data();
  std::uint8_t* broken = ctx.bonds->broken.data();
  const bool any_history = ctx.bond_history_arrays() > 0;
  const bool after_force = ctx.bond_failure_after_force;
  // With protected points the failure check needs both ends' flags: the general path only.
  const bool vector_path = failure.no_fail == nullptr;
  const bool thermal = fields.thermal_stretch != nullptr;  // the AVX-512 loops have no thermal stretch
  for_each_block(ctx, [&](auto dim, auto model, const MaterialParams& p, const auto& mp, BlockRange range) {
    constexpr int Dim = decltype(dim)::value;
    using Model = decltype(model);
    const double infinity = std::numeric_limits<double>::infinity();
    const double break_limit = fail_bonds ? p.critical_stretch : infinity;
    const bool scaled = p.surface_correction && fields.bond_scale;  // the AVX-512 loops have no bond factor
    // The run loops have no quadrature direction weight: such a block takes the general path.
    const bool runs = vector_path && !p.quadrature.on;
    const int chunk = points_per_chunk(range);
    // Clang cannot reach compute_internal_force's locals from the lambda inside the parallel region below:
    // this lambda's own names for them.
    const double* const xs = x;
    const BondFailure& fails = failure;
    const bool histories = any_history;
    const std::uint32_t* const partners = reverse;
    // The vector loop's per-point coefficients, where the model has some: kept from pass to pass (per thread
    // that calls the pass) so that a step allocates nothing; read inside the parallel region through `terms`.
    const double* terms = nullptr;
    const std::size_t points = ctx.disc->num_points();
    if constexpr (vector_loops && std::is_same_v<Model, LpsPlastic>) {
      static thread_local std::vector<double> plastic_terms;
      if (runs && !thermal) plastic_force_terms(mp, fields, points, plastic_terms), terms = plastic_terms.data();
    }
#pragma omp parallel
    {
      RunScratch scratch;
      IntactScratch intact;
      SameBlockRun run = block_run(ctx, up, blocks[range.begin], break_limit, after_force ? infinity : break_limit);
      if (terms != nullptr) run.point_terms[0] = terms, run.point_terms[1] = terms + points;
#pragma omp for schedule(dynamic, chunk)
      for (std::size_t i = range.begin; i < range.end; ++i) {
        set_same_block_run(bonds, blocks, i, run);
        double fi[3] = {0, 0, 0};
        const bool in_place = runs && !thermal && !scaled &&
                              force_in_place<Dim, Model>(run, p, mp, fields, i, neighbors, broken, intact, fi);
        if (runs && !in_place) {
          load_run(scratch, neighbors, broken, run);
          with_influence(p.influence, [&](auto kind) {
            with_flags(fail_bonds, thermal, [&](auto check, auto heated) {
              with_scale<Model>(scaled, [&](auto corrected) {
                run_force<Dim, Model, check.value, kind.value, heated.value, corrected.value>(run, p, mp, fields, i, fi);
              });
            });
          });
          if (fail_bonds) scratch.store(broken, run.b_begin, run.b_end);
        }
        double fx = fi[0], fy = fi[1], fz = fi[2];
        // The general path: every bond of a protected deck, and interface bonds (t_ji from the
        // neighbour's own model and parameters).
        auto general_bond = [&](std::uint64_t b) {
          if (broken[b]) return;
          const std::uint32_t j = neighbors[b];
          const BondGeometry<Dim> g = bond_geometry<Dim>(xs, up, i, j);
          if (fail_bonds && fails.fails(i, j, bond_mechanical_extension(ctx, i, j, g.e, g.xi), g.xi,
                                        pair_critical_stretch(ctx, p, blocks[i], j))) {
            broken[b] = 1;
            if (!after_force) return;
          }
          const double scale = bond_scale(ctx, p, b);
          const double omega = influence(p.influence, g.xi, p.horizon) * scale;
          const std::uint64_t partner_bond = histories ? partners[b] : 0;
          const double e_j = mechanical_extension(ctx, j, g);  // |ξ| and e are the same from j
          const double t_ji = blocks[j] == blocks[i]
                                  ? end_force_scalar<Model>(p, mp, fields, j, partner_bond, e_j, g.xi, omega)
                                  : other_block_force_scalar(ctx, static_cast<std::size_t>(blocks[j]), fields, j,
                                                             partner_bond, e_j, g.xi, b);
          const double t = end_force_scalar<Model>(p, mp, fields, i, b, mechanical_extension(ctx, i, g), g.xi, omega) + t_ji;
          const double carried = t * neighbor_volume(ctx, i, j, g.xi) / g.length;
          fx += carried * g.y[0];
          fy += carried * g.y[1];
          if constexpr (Dim == 3) fz += carried * g.y[2];
        };
        if (!runs)
          for (std::uint64_t b = run.b_begin; b < run.b_end; ++b) general_bond(b);
        for (std::uint64_t b = bonds.offsets[i]; b < run.b_begin; ++b) general_bond(b);
        for (std::uint64_t b = run.b_end; b < bonds.offsets[i + 1]; ++b) general_bond(b);
        fp[3 * i] = fx;
        fp[3 * i + 1] = fy;
        fp[3 * i + 2] = fz;
      }
    }
  });
}

/// Runs point(i, run, intact bonds) in parallel for every point of a block whose whole family lies in the
/// block, and afterwards others(range) for each stretch of consecutive other points (interface points: the
/// model's own loop), so that which loop a point takes depends on its family only, not on the rank count (a
/// block-wide choice gave 3 and 4 ranks other bits than 1). False, and nothing done, for a block with a
/// temperature field or quadrature weights (the model's own loop then). Each stretch is a parallel loop of
/// its own: a deck with many interface points pays a few microseconds per stretch and step (per-point
/// kernels in the models would remove that).
template <class PointBody, class Others>
bool for_each_point_run(const ModelContext& ctx, const VectorField& u, const MaterialParams& p, BlockRange range,
                        PointBody&& point, Others&& others) {
  if (!vector_loops || !ctx.thermal_stretch.empty() || p.quadrature.on) return false;
  BondList& bonds = *ctx.bonds;
  const auto& blocks = ctx.disc->block;
  const double infinity = std::numeric_limits<double>::infinity();
  const SameBlockRun block = block_run(ctx, u.data(), blocks[range.begin], infinity, infinity);
  // Which points are interface points, kept from pass to pass (per calling thread): a step allocates nothing.
  static thread_local std::vector<std::uint8_t> interface_flags;
  interface_flags.assign(block.family_in_block ? 0 : range.end - range.begin, 0);
  std::uint8_t* const interface = interface_flags.data();  // the workers' name for it (theirs would be their own)
  const std::size_t flagged = interface_flags.size();
  const int chunk = points_per_chunk(range);
#pragma omp parallel
  {
    IntactScratch intact;
    SameBlockRun run = block;
#pragma omp for schedule(dynamic, chunk)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      set_same_block_run(bonds, blocks, i, run);
      if (run.b_begin != bonds.offsets[i] || run.b_end != bonds.offsets[i + 1]) {
        interface[i - range.begin] = 1;
        continue;
      }
      point(i, run, IntactRun(run, bonds.neighbors.data(), bonds.broken.data(), intact));
    }
  }
  for (std::size_t k = 0; k < flagged;) {
    if (!interface[k]) {
      ++k;
      continue;
    }
    std::size_t end = k;
    while (end < flagged && interface[end]) ++end;
    others(BlockRange{range.begin + k, range.begin + end});
    k = end;
  }
  return true;
}

/// The return maps of this step (ModelBase::prepare) of every block: lps_plastic's through the vector loop
/// above where for_each_point_run applies, the others as their model does it.
void prepare_pass(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                  MaterialHistory& history) {
  const KernelFields fields = kernel_fields(ctx, theta, &history);
  for_each_block(ctx, [&](auto dim, auto model, const MaterialParams& p, const auto& mp, BlockRange range) {
    constexpr int Dim = decltype(dim)::value;
    using Model = decltype(model);
    if constexpr (vector_loops && std::is_same_v<Model, LpsPlastic>) {
      const bool done = for_each_point_run(ctx, u, p, range, [&](std::size_t i, const SameBlockRun& run,
                                                                 const IntactRun& bonds) {
        double norm2 = 0, weighted = 0, along = 0;
        with_influence(p.influence, [&](auto kind) {
          run_return_map_sums_vector<Dim, kind.value>(run, p, mp, fields, i, bonds, norm2, weighted, along);
        });
        LpsPlastic::finish_return_map(ctx, history, mp, i, norm2, weighted, along);
      }, [&](BlockRange stretch) { model.prepare(ctx, u, theta, history, p, mp, stretch); });
      if (done) return;
    }
    model.prepare(ctx, u, theta, history, p, mp, range);
  });
}

/// Makes the step final (ModelBase::commit) in every block: lps_plastic's and lps_viscoelastic's through the
/// vector loops above where for_each_point_run applies, the others as their model does it.
void commit_pass(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                 MaterialHistory& history, double dt) {
  const KernelFields fields = kernel_fields(ctx, theta, &history);
  for_each_block(ctx, [&](auto dim, auto model, const MaterialParams& p, const auto& mp, BlockRange range) {
    constexpr int Dim = decltype(dim)::value;
    using Model = decltype(model);
    if constexpr (vector_loops && std::is_same_v<Model, LpsPlastic>) {
      const bool done = for_each_point_run(ctx, u, p, range, [&](std::size_t i, const SameBlockRun& run,
                                                                 const IntactRun& bonds) {
        const double r = history.point[LpsPlastic::yield_scale][i];
        const double released = history.point[LpsPlastic::released_extension][i];
        if (r == 1 && released == 0) return;  // elastic step, no bond broke: nothing changes
        run_plastic_commit_vector<Dim>(run, mp, fields, i, bonds, r, released, history.bond[0].data());
        LpsPlastic::finish_commit(history, mp, i);
      }, [&](BlockRange stretch) { model.commit(ctx, u, theta, history, p, mp, stretch, dt); });
      if (done) return;
    }
    if constexpr (vector_loops && std::is_same_v<Model, LpsViscoelastic>) {
      const bool done = for_each_point_run(ctx, u, p, range, [&](std::size_t i, const SameBlockRun& run,
                                                                 const IntactRun& bonds) {
        with_influence(p.influence, [&](auto kind) {
          history.dissipation[i] += run_viscous_commit_vector<Dim, kind.value>(
              run, p, mp, fields, i, bonds, history.bond[0].data(), history.bond[1].data(), dt);
        });
      }, [&](BlockRange stretch) { model.commit(ctx, u, theta, history, p, mp, stretch, dt); });
      if (done) return;
    }
    model.commit(ctx, u, theta, history, p, mp, range, dt);
  });
}

}  // namespace HWY_NAMESPACE
}  // namespace peridot
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace peridot {

void calibrate_models(ModelContext& ctx) {
  ctx.point_constants.assign(static_cast<std::size_t>(ctx.point_constant_arrays()),
                             std::vector<double>(ctx.disc->num_points(), 0.0));
  for (std::size_t b = 0; b < ctx.ranges.size(); ++b)
    if (ctx.ranges[b].begin < ctx.ranges[b].end)
      with_model(ctx.params[b].model, [&](auto model) {
        using Model = decltype(model);
        Model::calibrate(ctx, ctx.params[b], ctx.model_params_of<Model>(b), ctx.ranges[b]);
      });
  // Ghosts carry their block too, and a bond loop reads their volumes: all points count.
  const Discretization& disc = *ctx.disc;
  constexpr double unset = -1;
  ctx.uniform_volume.assign(ctx.params.size(), unset);
  for (std::size_t i = 0; i < disc.num_points(); ++i) {
    double& v = ctx.uniform_volume[static_cast<std::size_t>(disc.block[i])];
    if (v == unset) v = disc.volume[i];
    else if (v != disc.volume[i]) v = 0;
  }
  for (double& v : ctx.uniform_volume) v = std::max(v, 0.0);  // a block without points: gather (never read)
  // A family's blocks rise along its bonds (find_same_block_run): its first and last bonds tell.
  const BondList& bonds = *ctx.bonds;
  ctx.family_in_block.assign(ctx.params.size(), 1);
  for (std::size_t b = 0; b < ctx.ranges.size(); ++b)
    for (std::size_t i = ctx.ranges[b].begin; i < ctx.ranges[b].end; ++i) {
      const std::uint64_t first = bonds.offsets[i], end = bonds.offsets[i + 1];
      if (first < end && (disc.block[bonds.neighbors[first]] != disc.block[i] ||
                          disc.block[bonds.neighbors[end - 1]] != disc.block[i])) {
        ctx.family_in_block[b] = 0;
        break;
      }
    }
}

KernelFields kernel_fields(const ModelContext& ctx, const std::vector<double>& theta, const MaterialHistory* history) {
  KernelFields s;
  s.theta = theta.data();
  s.inverse_m = ctx.inverse_weighted_volume.data();
  if (!ctx.thermal_stretch.empty()) s.thermal_stretch = ctx.thermal_stretch.data();
  if (!ctx.bond_scale.empty()) s.bond_scale = ctx.bond_scale.data();
  if (history) {
    for (std::size_t k = 0; k < history->point.size(); ++k) s.point[k] = history->point[k].data();
    for (std::size_t k = 0; k < history->bond.size() && k < kernel_bond_arrays; ++k)
      s.bond[k] = history->bond[k].empty() ? nullptr : history->bond[k].data();
    s.history = history;
  }
  for (std::size_t k = 0; k < ctx.point_constants.size() && k < kernel_point_constant_arrays; ++k)
    s.point_constant[k] = ctx.point_constants[k].data();
  PERIDOT_REQUIRE(ctx.bond_history_arrays() == 0 || s.bond[0], "an inelastic model needs the material history");
  PERIDOT_REQUIRE(ctx.point_arrays() == 0 || s.point[0], "a model with point arrays needs the material history");
  return s;
}

void compute_weighted_volume(const ModelContext& ctx, std::vector<double>& m) {
  const std::size_t n = ctx.disc->num_points();
  m.assign(n, 0.0);
  const double* x = ctx.disc->x.data();
  const BondList& bonds = *ctx.bonds;
  for_each_block_geometry(ctx, [&](auto dim, const MaterialParams& p, BlockRange range) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      double sum = 0;
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        const std::uint32_t j = bonds.neighbors[b];
        const double xi = bond_length<Dim>(x, i, j);
        sum += influence(p.influence, xi, p.horizon) * xi * xi * neighbor_volume(ctx, i, j, xi);
      }
      m[i] = sum;
    }
  });
}

HWY_EXPORT(dilatation_pass);
HWY_EXPORT(force_pass);

void compute_dilatation(const ModelContext& ctx, const VectorField& u, std::vector<double>& theta, bool fail_bonds,
                        MaterialHistory* history) {
  simd::apply_environment();
  HWY_DYNAMIC_DISPATCH(dilatation_pass)(ctx, u, theta, fail_bonds, history);
}

void start_step(const ModelContext& ctx, MaterialHistory& history, double dt) {
  for_each_block(ctx, [&](auto, auto model, const MaterialParams& p, const auto& mp, BlockRange range) {
    model.start_step(ctx, history, p, mp, range, dt);
  });
}

HWY_EXPORT(prepare_pass);

void prepare_history(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                     MaterialHistory& history) {
  simd::apply_environment();
  HWY_DYNAMIC_DISPATCH(prepare_pass)(ctx, u, theta, history);
}

HWY_EXPORT(commit_pass);

void commit_history(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                    MaterialHistory& history, double dt) {
  simd::apply_environment();
  HWY_DYNAMIC_DISPATCH(commit_pass)(ctx, u, theta, history, dt);
}

void compute_internal_force(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                            VectorField& f, bool fail_bonds, const MaterialHistory* history) {
  simd::apply_environment();
  HWY_DYNAMIC_DISPATCH(force_pass)(ctx, u, theta, f, fail_bonds, history);
}

void compute_strain_energy_density(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                                   std::vector<double>& W, const MaterialHistory* history) {
  const KernelFields fields = kernel_fields(ctx, theta, history);
  const double* x = ctx.disc->x.data();
  const double* up = u.data();
  const BondList& bonds = *ctx.bonds;
  W.resize(ctx.disc->num_points());
  for_each_block(ctx, [&](auto dim, auto model, const MaterialParams& p, const auto& mp, BlockRange range) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      double sum = model.point_energy(mp, fields, i);
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        if (bonds.broken[b]) continue;
        const std::uint32_t j = bonds.neighbors[b];
        const BondGeometry<Dim> g = bond_geometry<Dim>(x, up, i, j);
        const double omega = influence(p.influence, g.xi, p.horizon) * bond_scale(ctx, p, b);
        sum += model.bond_energy(mp, fields, i, b, mechanical_extension(ctx, i, g), g.xi, omega) *
               neighbor_volume(ctx, i, j, g.xi);
      }
      W[i] = sum;
    }
  });
}

void stiffness_bound(const ModelContext& ctx, std::vector<double>& k) {
  const double* x = ctx.disc->x.data();
  const BondList& bonds = *ctx.bonds;
  k.assign(ctx.disc->num_points(), 0.0);
  for_each_block_geometry(ctx, [&](auto dim, const MaterialParams& p, BlockRange range) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      double stiffness = 0;
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        const std::uint32_t j = bonds.neighbors[b];
        const double xi = bond_length<Dim>(x, i, j);
        stiffness += neighbor_volume(ctx, i, j, xi) * p.stable_micromodulus * bond_scale(ctx, p, b) / xi;
      }
      k[i] = stiffness;
    }
  });
}

void bond_stiffness(const ModelContext& ctx, std::vector<double>& k) {
  const double* x = ctx.disc->x.data();
  const BondList& bonds = *ctx.bonds;
  const auto& blocks = ctx.disc->block;
  k.assign(bonds.num_bonds(), 0.0);
  for_each_block_geometry(ctx, [&](auto dim, const MaterialParams& p, BlockRange range) {
    constexpr int Dim = decltype(dim)::value;
    // pmb: its own micromodulus c0 ω(ξ) on the bonds within the block (t_ij + t_ji = c0 ω G e/ξ there).
    const bool pmb = is_model<Pmb>(p);
    const double c0 = pmb ? ctx.model_params_of<Pmb>(static_cast<std::size_t>(blocks[range.begin])).micromodulus : 0.0;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i)
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        if (bonds.broken[b]) continue;
        const std::uint32_t j = bonds.neighbors[b];
        const double xi = bond_length<Dim>(x, i, j);
        const double c = pmb && blocks[j] == blocks[i] ? c0 * influence(p.influence, xi, p.horizon) : p.stable_micromodulus;
        k[b] = neighbor_volume(ctx, i, j, xi) * c * bond_scale(ctx, p, b) / xi;
      }
  });
}

double stable_time_step(const ModelContext& ctx) {
  std::vector<double> k;
  stiffness_bound(ctx, k);
  double dt = std::numeric_limits<double>::infinity();
  for (std::size_t b = 0; b < ctx.ranges.size(); ++b) {
    const BlockRange range = ctx.ranges[b];
    const MaterialParams& p = ctx.params[b];
#pragma omp parallel for schedule(static) reduction(min : dt)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      const double stiffness = k[i];
      if (stiffness == 0) continue;
      double dt_i = std::sqrt(2 * p.density / stiffness);
      // A dashpot c_v beside each spring c (correspondence hourglass damping): central differences with
      // damping ratio ζ are stable for Δt ≤ (2/ω)(√(1 + ζ²) − ζ), ω = 2/dt_i the highest frequency of the
      // sums above; the sums of c_v/ξ are c_v/c times those of c/ξ, so ζ = (c_v/c)/dt_i (assumes the
      // highest mode is damped in full: conservative).
      if (p.stable_damping > 0) {
        const double zeta = p.stable_damping / p.stable_micromodulus / dt_i;
        dt_i *= std::sqrt(1 + zeta * zeta) - zeta;
      }
      // A linear bulk viscosity q = C_l ρ c ℓ |tr D| damps the highest mode with ratio C_l (the hydrocodes'
      // Δt = ℓ/(Q + √(Q² + c²)), Q = C_l c). Its quadratic part grows with the compression rate and is left
      // to the safety factor.
      if (p.stable_bulk_viscosity > 0)
        dt_i *= std::sqrt(1 + p.stable_bulk_viscosity * p.stable_bulk_viscosity) - p.stable_bulk_viscosity;
      dt = std::min(dt, dt_i);
    }
  }
  // OpenMP starts each thread's min at the largest finite double (clang) or at +∞ (GCC): no bond anywhere is
  // +∞ with either.
  return dt < std::numeric_limits<double>::max() ? dt : std::numeric_limits<double>::infinity();
}

}  // namespace peridot
#endif  // HWY_ONCE
