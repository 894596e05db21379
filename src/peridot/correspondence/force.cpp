// Correspondence force state and gather (Foster, Silling & Chen 2010 eqs 4, 25) and hourglass control
// (docs/algorithms.md §7).
#include "peridot/correspondence/force.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "peridot/core/simd.hpp"
#include "peridot/state/bond_runs.hpp"
#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>  // before the per-target code below: every header is compiled for the baseline only
#endif

// The bond loops below are compiled once per SIMD target (core/simd.hpp, solvers/internal_force.cpp says how).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "peridot/correspondence/force.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
#include "peridot/core/simd_bonds.hpp"
namespace peridot::correspondence {
namespace HWY_NAMESPACE {

/// The AVX-512 loops read the bond list in place (state/bond_runs.hpp).
constexpr bool runs_in_place = HWY_TARGET == HWY_AVX3;

namespace {

/// What the vectorised force loop reads, by value (private copies: state/bond_runs.hpp says why).
struct ForceRun {
  const double* x;
  const double* u;
  const double* v;
  const double* A;     ///< force tensors P K⁻¹, nine per point
  const double* F;     ///< deformation gradients
  const double* Fdot;  ///< their rates
  double stiffness;    ///< c_hg of the run's block
  double damping;      ///< c_hv of the run's block
  WeightedRun bonds;   ///< the run, weights ω V_j (state/bond_runs.hpp)
};

/// The force on point i from its bonds to its own block: Σ ω V A_j ξ and Σ ω V ξ (for A_i Σ ω V ξ), and
/// the hourglass force, each added to what the arrays hold. Within one block ω_j⟨−ξ⟩ = ω_i⟨ξ⟩ (the same
/// influence function, horizon and partial-volume factor), c_hg and c_hv are the same at both ends, so
/// the two ends' hourglass states add to ω (c_hg/|ξ|) (2Y − (F_i + F_j) ξ)·n n, and likewise for the
/// dashpots; with n = Y/|Y| that is ω c_hg (2Y − (F_i + F_j) ξ)·Y Y/(|ξ| |Y|²), with no square root of |Y|².
template <bool Hourglass, bool Damping>
void run_force(const ForceRun& run_in, std::size_t i, double sum_Ajxi[3], double sum_xi[3], double fh[3]) {
  // Private copies, one variable each (a copy of the whole struct stays in memory, and the loop scalar).
  const double *const x = run_in.x, *const u = run_in.u, *const v = run_in.v;
  const double *const A = run_in.A, *const F = run_in.F, *const Fdot = run_in.Fdot;
  const double stiffness = run_in.stiffness, damping = run_in.damping;
  const std::uint32_t* const neighbor = run_in.bonds.neighbor;
  const double* const weight = run_in.bonds.weight;
  const std::uint64_t count = run_in.bonds.count;
  double Fi[9], Fdot_i[9];
  for (int c = 0; c < 9; ++c) Fi[c] = F[9 * i + c], Fdot_i[c] = Damping ? Fdot[9 * i + c] : 0.0;
  const double xi0 = x[3 * i], xi1 = x[3 * i + 1], xi2 = x[3 * i + 2];
  const double ui0 = u[3 * i], ui1 = u[3 * i + 1], ui2 = u[3 * i + 2];
  const double vi0 = v[3 * i], vi1 = v[3 * i + 1], vi2 = v[3 * i + 2];
  double t0 = 0, t1 = 0, t2 = 0, m0 = 0, m1 = 0, m2 = 0, h0 = 0, h1 = 0, h2 = 0;
#pragma omp simd reduction(+ : t0, t1, t2, m0, m1, m2, h0, h1, h2)
  for (std::uint64_t k = 0; k < count; ++k) {
    const std::uint32_t j = neighbor[k];
    const double w = weight[k];
    const double dx0 = x[3 * j] - xi0, dx1 = x[3 * j + 1] - xi1, dx2 = x[3 * j + 2] - xi2;
    // j's tensors indexed from A, F, Ḟ: through a pointer A + 9j GCC 12 finds "no vectype" and leaves the
    // loop scalar (while reporting the lane-sum epilogue "vectorized").
    const std::uint64_t a = 9 * std::uint64_t{j};
    t0 += w * (A[a] * dx0 + A[a + 1] * dx1 + A[a + 2] * dx2);
    t1 += w * (A[a + 3] * dx0 + A[a + 4] * dx1 + A[a + 5] * dx2);
    t2 += w * (A[a + 6] * dx0 + A[a + 7] * dx1 + A[a + 8] * dx2);
    m0 += w * dx0, m1 += w * dx1, m2 += w * dx2;
    if constexpr (Hourglass) {
      const double y0 = dx0 + (u[3 * j] - ui0), y1 = dx1 + (u[3 * j + 1] - ui1),
                   y2 = dx2 + (u[3 * j + 2] - ui2);
      // (2Y − (F_i + F_j) ξ)·Y
      const double z0 = 2 * y0 - ((Fi[0] + F[a]) * dx0 + (Fi[1] + F[a + 1]) * dx1 + (Fi[2] + F[a + 2]) * dx2);
      const double z1 = 2 * y1 - ((Fi[3] + F[a + 3]) * dx0 + (Fi[4] + F[a + 4]) * dx1 + (Fi[5] + F[a + 5]) * dx2);
      const double z2 = 2 * y2 - ((Fi[6] + F[a + 6]) * dx0 + (Fi[7] + F[a + 7]) * dx1 + (Fi[8] + F[a + 8]) * dx2);
      double scalar = stiffness * (z0 * y0 + z1 * y1 + z2 * y2);
      if constexpr (Damping) {  // (2(v_j − v_i) − (Ḟ_i + Ḟ_j) ξ)·Y
        const double dv0 = v[3 * j] - vi0, dv1 = v[3 * j + 1] - vi1, dv2 = v[3 * j + 2] - vi2;
        const double r0 =
            2 * dv0 - ((Fdot_i[0] + Fdot[a]) * dx0 + (Fdot_i[1] + Fdot[a + 1]) * dx1 + (Fdot_i[2] + Fdot[a + 2]) * dx2);
        const double r1 =
            2 * dv1 - ((Fdot_i[3] + Fdot[a + 3]) * dx0 + (Fdot_i[4] + Fdot[a + 4]) * dx1 + (Fdot_i[5] + Fdot[a + 5]) * dx2);
        const double r2 =
            2 * dv2 - ((Fdot_i[6] + Fdot[a + 6]) * dx0 + (Fdot_i[7] + Fdot[a + 7]) * dx1 + (Fdot_i[8] + Fdot[a + 8]) * dx2);
        scalar += damping * (r0 * y0 + r1 * y1 + r2 * y2);
      }
      const double xi_length = std::sqrt(dx0 * dx0 + dx1 * dx1 + dx2 * dx2);
      const double y_squared = y0 * y0 + y1 * y1 + y2 * y2;
      // A broken or padding bond (w = 0) may join coincident points: 1 in place of |Y|² keeps its 0 finite.
      const double scale = w * scalar / (xi_length * (y_squared > 0 ? y_squared : 1.0));
      h0 += scale * y0, h1 += scale * y1, h2 += scale * y2;
    }
  }
  sum_Ajxi[0] += t0, sum_Ajxi[1] += t1, sum_Ajxi[2] += t2;
  sum_xi[0] += m0, sum_xi[1] += m1, sum_xi[2] += m2;
  fh[0] += h0, fh[1] += h1, fh[2] += h2;
}

PERIDOT_SIMD_BONDS_BEGIN
/// run_force in Highway's vectors (core/simd_bonds.hpp), a group of bonds per iteration. Each bond's terms
/// are the same operations in the same order as above (no fused multiply-add, CMakeLists.txt); only the
/// order of the sums over the bonds differs.
template <bool Hourglass, bool Damping>
[[maybe_unused]] void run_force_vector(const ForceRun& run, std::size_t i, double sum_Ajxi[3], double sum_xi[3],
                                       double fh[3]) {
  namespace sb = ::peridot::HWY_NAMESPACE::simd_bonds;
  namespace hn = hwy::HWY_NAMESPACE;
  using V = sb::V;
  const sb::D d;
  // Σ_c (P_c + Q_c) ξ_c over one row of two tensors, in the order of the scalar loop.
  const auto row = [](const V* P, const V* Q, const V* dx) {
    return (P[0] + Q[0]) * dx[0] + (P[1] + Q[1]) * dx[1] + (P[2] + Q[2]) * dx[2];
  };
  V x_i[3], u_i[3], v_i[3], F_i[9], Fdot_i[9];
  for (int c = 0; c < 3; ++c)
    x_i[c] = hn::Set(d, run.x[3 * i + c]), u_i[c] = hn::Set(d, run.u[3 * i + c]), v_i[c] = hn::Set(d, run.v[3 * i + c]);
  for (int c = 0; c < 9; ++c)
    F_i[c] = hn::Set(d, run.F[9 * i + c]), Fdot_i[c] = hn::Set(d, Damping ? run.Fdot[9 * i + c] : 0.0);
  const V two = hn::Set(d, 2.0), one = hn::Set(d, 1.0), zero = hn::Zero(d);
  const V stiffness = hn::Set(d, run.stiffness), damping = hn::Set(d, run.damping);
  V t[3] = {zero, zero, zero}, m[3] = {zero, zero, zero}, h[3] = {zero, zero, zero};
  const WeightedRun bonds = run.bonds;
  std::uint32_t tail[sb::max_lanes];
  for (std::uint64_t k = 0; k < bonds.count; k += hn::Lanes(d)) {
    const std::uint32_t* j;
    const V w = sb::group_weights(d, bonds.neighbor, bonds.broken, bonds.weight, k, bonds.count, tail, j);
    V dx[3], a[9];
    sb::load_vec3(d, run.x, j, dx);
    for (int c = 0; c < 3; ++c) dx[c] = dx[c] - x_i[c];
    sb::load_tensor(d, run.A, j, a);
    for (int r = 0; r < 3; ++r) t[r] = t[r] + w * (a[3 * r] * dx[0] + a[3 * r + 1] * dx[1] + a[3 * r + 2] * dx[2]);
    for (int c = 0; c < 3; ++c) m[c] = m[c] + w * dx[c];
    if constexpr (Hourglass) {
      V y[3], Fj[9], z[3];
      sb::load_vec3(d, run.u, j, y);
      for (int c = 0; c < 3; ++c) y[c] = dx[c] + (y[c] - u_i[c]);
      sb::load_tensor(d, run.F, j, Fj);
      for (int r = 0; r < 3; ++r) z[r] = two * y[r] - row(F_i + 3 * r, Fj + 3 * r, dx);
      V scalar = stiffness * (z[0] * y[0] + z[1] * y[1] + z[2] * y[2]);
      if constexpr (Damping) {
        V dv[3], Gj[9], q[3];
        sb::load_vec3(d, run.v, j, dv);
        for (int c = 0; c < 3; ++c) dv[c] = dv[c] - v_i[c];
        sb::load_tensor(d, run.Fdot, j, Gj);
        for (int r = 0; r < 3; ++r) q[r] = two * dv[r] - row(Fdot_i + 3 * r, Gj + 3 * r, dx);
        scalar = scalar + damping * (q[0] * y[0] + q[1] * y[1] + q[2] * y[2]);
      }
      const V xi_length = hn::Sqrt(dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]);
      V y_squared = y[0] * y[0] + y[1] * y[1] + y[2] * y[2];
      y_squared = hn::IfThenElse(hn::Gt(y_squared, zero), y_squared, one);
      const V scale = w * scalar / (xi_length * y_squared);
      for (int c = 0; c < 3; ++c) h[c] = h[c] + scale * y[c];
    }
  }
  for (int c = 0; c < 3; ++c)
    sum_Ajxi[c] += sb::sum_lanes(d, t[c]), sum_xi[c] += sb::sum_lanes(d, m[c]), fh[c] += sb::sum_lanes(d, h[c]);
}
PERIDOT_SIMD_BONDS_END

/// The run's force: the vector loop, or the portable one on the one-lane scalar target.
template <bool Hourglass, bool Damping>
void run_force_sums(const ForceRun& run, std::size_t i, double sum_Ajxi[3], double sum_xi[3], double fh[3]) {
#if HWY_TARGET == HWY_SCALAR || HWY_TARGET == HWY_EMU128
  run_force<Hourglass, Damping>(run, i, sum_Ajxi, sum_xi, fh);
#else
  run_force_vector<Hourglass, Damping>(run, i, sum_Ajxi, sum_xi, fh);
#endif
}

}  // namespace

void force_pass(const CorrespondenceContext& ctx, const KinematicFields& kin, const StressFields& s,
                const VectorField& u, const VectorField& v, VectorField& f, BlockRange range,
                VectorField* hourglass_force, VectorField* mirror_force) {
  const Discretization& disc = *ctx.disc;
  const BondList& bonds = *ctx.bonds;
  const std::size_t n = disc.num_points();
  if (f.size() != n) f.resize(n);
  if (hourglass_force && hourglass_force->size() != n) hourglass_force->resize(n);
  if (mirror_force && mirror_force->size() != n) mirror_force->resize(n);
  const auto any_nonzero = [](const std::vector<double>& c) {
    return std::any_of(c.begin(), c.end(), [](double value) { return value != 0; });
  };
  const bool damping = any_nonzero(ctx.hourglass_damping);
  const bool hourglass = damping || any_nonzero(ctx.hourglass_stiffness);
  const double* x = disc.x.data();
  const double* up = u.data();
  const double* vp = v.data();
  const double* Fdot = kin.deformation_gradient_rate.data();
  const double* A = s.force_tensor.data();
  const double* F = kin.deformation_gradient.data();
  const MirrorBonds& mirror = ctx.mirror;
  const bool mirrored = mirror.active;
#pragma omp parallel
  {
  RunScratch scratch;
  ForceRun run{x, up, vp, A, F, Fdot, 0, 0, {}};
#pragma omp for schedule(static)
  for (std::size_t i = range.begin; i < range.end; ++i) {
    const double* Ai = A + 9 * i;
    const double* Fi = F + 9 * i;
    const double* Fdot_i = Fdot + 9 * i;
    const double ci = hourglass ? ctx.hourglass_stiffness[disc.block[i]] : 0.0;
    const double hi = damping ? ctx.hourglass_damping[disc.block[i]] : 0.0;
    double fi[3] = {0, 0, 0}, fh[3] = {0, 0, 0};
    // One bond to a partner j at reference offset ξ with relative displacement du = u_j − u_i and velocity
    // dv, j's force tensor Aj, F_j, Ḟ_j and block, wi = ω_i V_j and wj = ω_j V_j (ω_j of the bond j → i).
    auto add_bond = [&](const double* xi, const double* du, const double* dv, const double* Aj, const double* Fj,
                        const double* Fdot_j, std::size_t block_j, double wi, double wj) {
      // T_i⟨ξ⟩ − T_j⟨−ξ⟩ = (ω_i P_i K_i⁻¹ + ω_j P_j K_j⁻¹) ξ
      double t[3];
      for (int r = 0; r < 3; ++r)
        t[r] = wi * (Ai[3 * r] * xi[0] + Ai[3 * r + 1] * xi[1] + Ai[3 * r + 2] * xi[2]) +
               wj * (Aj[3 * r] * xi[0] + Aj[3 * r + 1] * xi[1] + Aj[3 * r + 2] * xi[2]);
      if (hourglass) {
        const double cj = ctx.hourglass_stiffness[block_j];
        double y[3];
        for (int d = 0; d < 3; ++d) y[d] = xi[d] + du[d];
        const double y_length = std::sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
        const double xi_length = std::sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
        // (Y − F ξ)·n for the affine prediction of each end: both ends' states act along n.
        double zi_n = 0, zj_n = 0;
        for (int r = 0; r < 3; ++r) {
          const double nr = y[r] / y_length;
          zi_n += (y[r] - (Fi[3 * r] * xi[0] + Fi[3 * r + 1] * xi[1] + Fi[3 * r + 2] * xi[2])) * nr;
          zj_n += (y[r] - (Fj[3 * r] * xi[0] + Fj[3 * r + 1] * xi[1] + Fj[3 * r + 2] * xi[2])) * nr;
        }
        double scalar = wi * ci * zi_n + wj * cj * zj_n;
        if (damping) {  // ż·n with ż = (v_j − v_i) − Ḟ ξ, the affine prediction of each end
          const double hj = ctx.hourglass_damping[block_j];
          double rate_i = 0, rate_j = 0;
          for (int r = 0; r < 3; ++r) {
            const double nr = y[r] / y_length;
            rate_i += (dv[r] - (Fdot_i[3 * r] * xi[0] + Fdot_i[3 * r + 1] * xi[1] + Fdot_i[3 * r + 2] * xi[2])) * nr;
            rate_j += (dv[r] - (Fdot_j[3 * r] * xi[0] + Fdot_j[3 * r + 1] * xi[1] + Fdot_j[3 * r + 2] * xi[2])) * nr;
          }
          scalar += wi * hi * rate_i + wj * hj * rate_j;
        }
        scalar /= xi_length * y_length;
        for (int r = 0; r < 3; ++r) fh[r] += scalar * y[r];
      }
      for (int r = 0; r < 3; ++r) fi[r] += t[r];
    };
    // The bonds to the point's own block, vectorised.
    std::uint64_t b_begin, b_end;
    find_same_block_run(bonds, disc.block, i, b_begin, b_end);
    run.bonds = weighted_run<runs_in_place>(scratch, bonds, ctx.weighted_volume.data(), b_begin, b_end);
    run.stiffness = ci, run.damping = hi;
    {
      double sum_Ajxi[3] = {0, 0, 0}, sum_xi[3] = {0, 0, 0};
      if (damping)
        run_force_sums<true, true>(run, i, sum_Ajxi, sum_xi, fh);
      else if (hourglass)
        run_force_sums<true, false>(run, i, sum_Ajxi, sum_xi, fh);
      else
        run_force_sums<false, false>(run, i, sum_Ajxi, sum_xi, fh);
      for (int r = 0; r < 3; ++r)
        fi[r] = Ai[3 * r] * sum_xi[0] + Ai[3 * r + 1] * sum_xi[1] + Ai[3 * r + 2] * sum_xi[2] + sum_Ajxi[r];
    }
    // Bonds to other correspondence blocks, one at a time.
    double xi[3], du[3], dv[3];
    auto other_block_bond = [&](std::uint64_t b) {
      if (bonds.broken[b]) return;
      const std::size_t j = bonds.neighbors[b];
      bond_offsets(x, up, vp, i, j, xi, du, dv);  // dv is read only with dashpots
      const std::size_t block_j = static_cast<std::size_t>(disc.block[j]);
      double wj = pair_weight(ctx, block_j, static_cast<std::size_t>(disc.block[i]), std::sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2])) * disc.volume[j];
      if (!ctx.bond_integrity.empty()) wj *= ctx.bond_integrity[b];  // the damage of both ends, as in ω_i
      add_bond(xi, du, dv, A + 9 * j, F + 9 * j, Fdot + 9 * j, block_j, ctx.weighted_volume[b], wj);
    };
    for (std::uint64_t b = bonds.offsets[i]; b < b_begin; ++b) other_block_bond(b);
    for (std::uint64_t b = b_end; b < bonds.offsets[i + 1]; ++b) other_block_bond(b);
    if (mirrored && mirror.offsets[i] < mirror.offsets[i + 1] && mirror.planes[mirror.plane_of[i]].active) {
      // The bonds to mirror images: what they add is the plane's force on the point.
      const double before[3] = {fi[0] + fh[0], fi[1] + fh[1], fi[2] + fh[2]};
      const MirrorPlane& plane = mirror.planes[mirror.plane_of[i]];
      for (std::uint64_t b = mirror.offsets[i]; b < mirror.offsets[i + 1]; ++b) {
        const std::size_t j = mirror.source[b];
        mirror_bond_offsets(plane, x, up, vp, i, j, xi, du, dv);
        double Aj[9], Fj[9], Fdot_j[9] = {};  // j′'s state: M A_j M, M F_j M, M Ḟ_j M
        reflect_tensor(plane.normal, A + 9 * j, Aj);
        reflect_tensor(plane.normal, F + 9 * j, Fj);
        if (damping) reflect_tensor(plane.normal, Fdot + 9 * j, Fdot_j);
        add_bond(xi, du, dv, Aj, Fj, Fdot_j, static_cast<std::size_t>(disc.block[j]), mirror.weight[b] * disc.volume[j],
                 mirror.partner_weight[b] * disc.volume[j]);
      }
      if (mirror_force)
        for (int r = 0; r < 3; ++r) (*mirror_force)(i, r) = fi[r] + fh[r] - before[r];
    } else if (mirror_force) {
      for (int r = 0; r < 3; ++r) (*mirror_force)(i, r) = 0;
    }
    for (int r = 0; r < 3; ++r) f(i, r) = fi[r] + fh[r];
    if (hourglass_force)
      for (int r = 0; r < 3; ++r) (*hourglass_force)(i, r) = fh[r];
  }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace peridot::correspondence
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace peridot::correspondence {

double hourglass_stiffness(double coefficient, double bulk_modulus, double horizon) {
  return 18.0 * coefficient * bulk_modulus / (std::numbers::pi * std::pow(horizon, 4));
}

double hourglass_damping(double coefficient, double density, double bulk_modulus, double horizon) {
  return 18.0 * coefficient * std::sqrt(density * bulk_modulus) / (std::numbers::pi * std::pow(horizon, 3));
}

void compute_correspondence_force(const CorrespondenceContext& ctx, const KinematicFields& kin,
                                  const StressFields& s, const VectorField& u, const VectorField& v, VectorField& f) {
  compute_correspondence_force(ctx, kin, s, u, v, f, BlockRange{0, ctx.disc->num_points()});
}

HWY_EXPORT(force_pass);

void compute_correspondence_force(const CorrespondenceContext& ctx, const KinematicFields& kin,
                                  const StressFields& s, const VectorField& u, const VectorField& v, VectorField& f,
                                  BlockRange range, VectorField* hourglass_force,
                                  VectorField* mirror_force) {
  simd::apply_environment();
  HWY_DYNAMIC_DISPATCH(force_pass)(ctx, kin, s, u, v, f, range, hourglass_force, mirror_force);
}

}  // namespace peridot::correspondence
#endif  // HWY_ONCE
