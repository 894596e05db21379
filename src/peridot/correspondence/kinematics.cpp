// Shape tensor, deformation gradient and its rate: Foster, Silling & Chen (2010) eqs 10, 13, 14.
#include "peridot/correspondence/kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "peridot/core/error.hpp"
#include "peridot/core/simd.hpp"
#include "peridot/neighbor/influence.hpp"
#include "peridot/neighbor/neighborhood.hpp"
#include "peridot/state/bond_runs.hpp"
#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>  // before the per-target code below: every header is compiled for the baseline only
#endif

// The bond loops below are compiled once per SIMD target (core/simd.hpp, solvers/internal_force.cpp says how).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "peridot/correspondence/kinematics.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

// What the per-target passes share, compiled once (on the first inclusion), for the baseline.
#ifndef PERIDOT_KINEMATICS_SHARED
#define PERIDOT_KINEMATICS_SHARED
namespace peridot::correspondence {
namespace {


[[noreturn]] void throw_singular_shape_tensor(const CorrespondenceContext& ctx, std::size_t i, const Mat3& K) {
  const Discretization& disc = *ctx.disc;
  const BondList& bonds = *ctx.bonds;
  std::size_t intact = 0;
  for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) intact += bonds.broken[b] ? 0 : 1;
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(K, Eigen::EigenvaluesOnly);
  const double lmax = eig.eigenvalues()(2);
  const double ratio = lmax > 0 ? eig.eigenvalues()(0) / lmax : 0.0;
  const std::uint32_t id = i < disc.input_id.size() ? disc.input_id[i] : static_cast<std::uint32_t>(i);
  throw NumericalError(fmt::format(
      "correspondence model: point {} (input id {}) at ({:g}, {:g}, {:g}) m has a singular shape tensor K "
      "(eq 10): {} intact bonds, λ_min/λ_max = {:.3g} < {:g}; the point needs at least three non-coplanar "
      "intact bonds",
      i, id, disc.x(i, 0), disc.x(i, 1), disc.x(i, 2), intact, ratio, ctx.min_reciprocal_condition));
}

/// Whether the symmetric positive semi-definite K has λ_min/λ_max ≥ `threshold`. Since λ_max ≤ tr K and
/// λ_min ≥ det K/(λ_mid λ_max) ≥ det K/(tr K)², λ_min/λ_max ≥ det K/(tr K)³: a K that passes this bound needs
/// no eigenvalues (every point of a regular family does; K ≈ (tr K/3) I gives 1/27). The others get them in
/// closed form (computeDirect: error about 1e-15 λ_max, far below the threshold).
bool well_conditioned(const Mat3& K, double threshold) {
  const double trace = K.trace();
  if (trace > 0 && K.determinant() >= threshold * trace * trace * trace) return true;
  Eigen::SelfAdjointEigenSolver<Mat3> eig;
  eig.computeDirect(K, Eigen::EigenvaluesOnly);
  const double lmin = eig.eigenvalues()(0), lmax = eig.eigenvalues()(2);
  return lmax > 0 && lmin >= threshold * lmax;
}

/// K of point i from its intact bonds at their current weights, mirror bonds included while active.
Mat3 shape_tensor_of(const CorrespondenceContext& ctx, std::size_t i) {
  const Discretization& disc = *ctx.disc;
  const BondList& bonds = *ctx.bonds;
  const MirrorBonds& mirror = ctx.mirror;
  const auto& x = disc.x;
  Mat3 K = Mat3::Zero();
  for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
    if (bonds.broken[b]) continue;
    const std::size_t j = bonds.neighbors[b];
    const Vec3d xi(x(j, 0) - x(i, 0), x(j, 1) - x(i, 1), x(j, 2) - x(i, 2));
    K += ctx.weighted_volume[b] * xi * xi.transpose();
  }
  if (mirror.active && mirror.offsets.size() > i + 1 && mirror.planes[mirror.plane_of[i]].active)
    for (std::uint64_t b = mirror.offsets[i]; b < mirror.offsets[i + 1]; ++b) {
      const Vec3 offset = reflect_point(mirror.planes[mirror.plane_of[i]], disc.x.get(mirror.source[b])) - disc.x.get(i);
      const Vec3d xi(offset.x, offset.y, offset.z);
      K += mirror.weight[b] * disc.volume[mirror.source[b]] * xi * xi.transpose();
    }
  return K;
}

}  // namespace
}  // namespace peridot::correspondence
#endif  // PERIDOT_KINEMATICS_SHARED

HWY_BEFORE_NAMESPACE();
#include "peridot/core/simd_bonds.hpp"
namespace peridot::correspondence {
namespace HWY_NAMESPACE {

/// The AVX-512 loops read the bond list in place (state/bond_runs.hpp).
constexpr bool runs_in_place = HWY_TARGET == HWY_AVX3;

namespace {

/// What the vectorised kinematics loop reads, by value (private copies: state/bond_runs.hpp says why).
struct KinematicsRun {
  const double* x;
  const double* u;
  const double* v;
  WeightedRun bonds;  ///< the run, weights ω V_j (state/bond_runs.hpp)
};

/// The bond sums of point i over its run: ω V ξ⊗ξ (the six components of K: 00 01 02 11 12 22),
/// ω V (u_j − u_i)⊗ξ (H) and ω V (v_j − v_i)⊗ξ (Ṅ), each added to what the arrays hold.
[[maybe_unused]] void run_kinematics(const KinematicsRun& run_in, std::size_t i, double K[6], double H[9], double Ndot[9]) {
  const KinematicsRun run = run_in;
  const double xi0 = run.x[3 * i], xi1 = run.x[3 * i + 1], xi2 = run.x[3 * i + 2];
  const double ui0 = run.u[3 * i], ui1 = run.u[3 * i + 1], ui2 = run.u[3 * i + 2];
  const double vi0 = run.v[3 * i], vi1 = run.v[3 * i + 1], vi2 = run.v[3 * i + 2];
  const std::uint32_t* const neighbor = run.bonds.neighbor;
  const double* const weight = run.bonds.weight;
  const std::uint64_t count = run.bonds.count;
  double k00 = 0, k01 = 0, k02 = 0, k11 = 0, k12 = 0, k22 = 0;
  double h00 = 0, h01 = 0, h02 = 0, h10 = 0, h11 = 0, h12 = 0, h20 = 0, h21 = 0, h22 = 0;
  double n00 = 0, n01 = 0, n02 = 0, n10 = 0, n11 = 0, n12 = 0, n20 = 0, n21 = 0, n22 = 0;
#pragma omp simd reduction(+ : k00, k01, k02, k11, k12, k22, h00, h01, h02, h10, h11, h12, h20, h21, h22, n00, \
                               n01, n02, n10, n11, n12, n20, n21, n22)
  for (std::uint64_t k = 0; k < count; ++k) {
    const std::uint32_t j = neighbor[k];
    const double w = weight[k];
    const double dx0 = run.x[3 * j] - xi0, dx1 = run.x[3 * j + 1] - xi1, dx2 = run.x[3 * j + 2] - xi2;
    const double du0 = run.u[3 * j] - ui0, du1 = run.u[3 * j + 1] - ui1, du2 = run.u[3 * j + 2] - ui2;
    const double dv0 = run.v[3 * j] - vi0, dv1 = run.v[3 * j + 1] - vi1, dv2 = run.v[3 * j + 2] - vi2;
    const double wx0 = w * dx0, wx1 = w * dx1, wx2 = w * dx2;
    k00 += wx0 * dx0, k01 += wx0 * dx1, k02 += wx0 * dx2, k11 += wx1 * dx1, k12 += wx1 * dx2, k22 += wx2 * dx2;
    h00 += du0 * wx0, h01 += du0 * wx1, h02 += du0 * wx2;
    h10 += du1 * wx0, h11 += du1 * wx1, h12 += du1 * wx2;
    h20 += du2 * wx0, h21 += du2 * wx1, h22 += du2 * wx2;
    n00 += dv0 * wx0, n01 += dv0 * wx1, n02 += dv0 * wx2;
    n10 += dv1 * wx0, n11 += dv1 * wx1, n12 += dv1 * wx2;
    n20 += dv2 * wx0, n21 += dv2 * wx1, n22 += dv2 * wx2;
  }
  const double k_run[6] = {k00, k01, k02, k11, k12, k22};
  const double h_run[9] = {h00, h01, h02, h10, h11, h12, h20, h21, h22};
  const double n_run[9] = {n00, n01, n02, n10, n11, n12, n20, n21, n22};
  for (int c = 0; c < 6; ++c) K[c] += k_run[c];
  for (int c = 0; c < 9; ++c) H[c] += h_run[c], Ndot[c] += n_run[c];
}

PERIDOT_SIMD_BONDS_BEGIN
/// run_kinematics in Highway's vectors (core/simd_bonds.hpp), a group of bonds per iteration; each bond's
/// terms are the same operations as above, only the order of the sums over bonds differs.
[[maybe_unused]] void run_kinematics_vector(const KinematicsRun& run, std::size_t i, double K[6], double H[9], double Ndot[9]) {
  namespace sb = ::peridot::HWY_NAMESPACE::simd_bonds;
  namespace hn = hwy::HWY_NAMESPACE;
  using V = sb::V;
  const sb::D d;
  V x_i[3], u_i[3], v_i[3];
  for (int c = 0; c < 3; ++c)
    x_i[c] = hn::Set(d, run.x[3 * i + c]), u_i[c] = hn::Set(d, run.u[3 * i + c]), v_i[c] = hn::Set(d, run.v[3 * i + c]);
  V k[6], h[9], n[9];
  for (int c = 0; c < 6; ++c) k[c] = hn::Zero(d);
  for (int c = 0; c < 9; ++c) h[c] = hn::Zero(d), n[c] = hn::Zero(d);
  const WeightedRun bonds = run.bonds;
  std::uint32_t tail[sb::max_lanes];
  for (std::uint64_t b = 0; b < bonds.count; b += hn::Lanes(d)) {
    const std::uint32_t* j;
    const V w = sb::group_weights(d, bonds.neighbor, bonds.broken, bonds.weight, b, bonds.count, tail, j);
    V dx[3], du[3], dv[3], wx[3];
    sb::load_vec3(d, run.x, j, dx);
    sb::load_vec3(d, run.u, j, du);
    sb::load_vec3(d, run.v, j, dv);
    for (int c = 0; c < 3; ++c) dx[c] = dx[c] - x_i[c], du[c] = du[c] - u_i[c], dv[c] = dv[c] - v_i[c];
    for (int c = 0; c < 3; ++c) wx[c] = w * dx[c];
    k[0] = k[0] + wx[0] * dx[0], k[1] = k[1] + wx[0] * dx[1], k[2] = k[2] + wx[0] * dx[2];
    k[3] = k[3] + wx[1] * dx[1], k[4] = k[4] + wx[1] * dx[2], k[5] = k[5] + wx[2] * dx[2];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) h[3 * r + c] = h[3 * r + c] + du[r] * wx[c], n[3 * r + c] = n[3 * r + c] + dv[r] * wx[c];
  }
  for (int c = 0; c < 6; ++c) K[c] += sb::sum_lanes(d, k[c]);
  for (int c = 0; c < 9; ++c) H[c] += sb::sum_lanes(d, h[c]), Ndot[c] += sb::sum_lanes(d, n[c]);
}
PERIDOT_SIMD_BONDS_END

/// The run's sums: the vector loop, or the portable one on the one-lane scalar target.
inline void run_kinematics_sums(const KinematicsRun& run, std::size_t i, double K[6], double H[9], double Ndot[9]) {
#if HWY_TARGET == HWY_SCALAR || HWY_TARGET == HWY_EMU128
  run_kinematics(run, i, K, H, Ndot);
#else
  run_kinematics_vector(run, i, K, H, Ndot);
#endif
}

}  // namespace

void kinematics_pass(const CorrespondenceContext& ctx, const VectorField& u, const VectorField& v, KinematicFields& out,
                     BlockRange range) {
  const Discretization& disc = *ctx.disc;
  const BondList& bonds = *ctx.bonds;
  const std::size_t n = disc.num_points();
  if (out.shape_inverse.size() != n) {
    out.shape_inverse = TensorField(n);
    out.deformation_gradient = TensorField(n);
    out.deformation_gradient_rate = TensorField(n);
  }
  const double* x = disc.x.data();
  const double* up = u.data();
  const double* vp = v.data();
  // A failure inside the parallel loop cannot throw across OpenMP; the lowest bad index is reported after
  // the loop, which makes the message independent of the thread count.
  std::size_t first_bad = std::numeric_limits<std::size_t>::max();
  const MirrorBonds& mirror = ctx.mirror;
  const bool mirrored = mirror.active;
#pragma omp parallel reduction(min : first_bad)
  {
    RunScratch scratch;
    KinematicsRun run{x, up, vp, {}};
#pragma omp for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      if (!ctx.failed_point.empty() && ctx.failed_point[i]) {
        out.shape_inverse.set(i, Mat3::Zero());
        out.deformation_gradient_rate.set(i, Mat3::Zero());
        continue;
      }
      // K (six components, symmetric), H = Σ ω V (u_j − u_i)⊗ξ and Ṅ; F = (K + H) K⁻¹ = I + H K⁻¹,
      // which keeps the digits of a small strain that N K⁻¹ with N = K + H would lose to cancellation.
      double K[6] = {}, H[9] = {}, Ndot[9] = {};
      std::uint64_t b_begin, b_end;
      find_same_block_run(bonds, disc.block, i, b_begin, b_end);
      run.bonds = weighted_run<runs_in_place>(scratch, bonds, ctx.weighted_volume.data(), b_begin, b_end);
      run_kinematics_sums(run, i, K, H, Ndot);
      // Bonds to other correspondence blocks and to mirror images, one at a time: weight w (ω V_j), reference
      // offset ξ, relative displacement and velocity.
      auto add_bond = [&](double w, const double* xi, const double* du, const double* dv) {
        const double wx[3] = {w * xi[0], w * xi[1], w * xi[2]};
        K[0] += wx[0] * xi[0], K[1] += wx[0] * xi[1], K[2] += wx[0] * xi[2];
        K[3] += wx[1] * xi[1], K[4] += wx[1] * xi[2], K[5] += wx[2] * xi[2];
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) H[3 * r + c] += du[r] * wx[c], Ndot[3 * r + c] += dv[r] * wx[c];
      };
      double xi[3], du[3], dv[3];
      auto other_block_bond = [&](std::uint64_t b) {
        if (bonds.broken[b]) return;
        const std::size_t j = bonds.neighbors[b];
        bond_offsets(x, up, vp, i, j, xi, du, dv);
        add_bond(ctx.weighted_volume[b], xi, du, dv);
      };
      for (std::uint64_t b = bonds.offsets[i]; b < b_begin; ++b) other_block_bond(b);
      for (std::uint64_t b = b_end; b < bonds.offsets[i + 1]; ++b) other_block_bond(b);
      if (mirrored && mirror.planes[mirror.plane_of[i]].active) {
        const MirrorPlane& plane = mirror.planes[mirror.plane_of[i]];
        for (std::uint64_t b = mirror.offsets[i]; b < mirror.offsets[i + 1]; ++b) {
          const std::size_t j = mirror.source[b];
          mirror_bond_offsets(plane, x, up, vp, i, j, xi, du, dv);
          add_bond(mirror.weight[b] * disc.volume[j], xi, du, dv);
        }
      }
      Mat3 Km;
      Km << K[0], K[1], K[2], K[1], K[3], K[4], K[2], K[4], K[5];
      if (!well_conditioned(Km, ctx.min_reciprocal_condition)) {
        first_bad = std::min(first_bad, i);
        continue;
      }
      const Mat3 Kinv = Km.inverse();
      const Mat3 F = Mat3::Identity() + Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(H) * Kinv;
      const Mat3 Fdot = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(Ndot) * Kinv;
      out.shape_inverse.set(i, Kinv);
      out.deformation_gradient.set(i, F);
      out.deformation_gradient_rate.set(i, Fdot);
    }
  }
  // Recompute K of that point alone for the message.
  if (first_bad != std::numeric_limits<std::size_t>::max())
    throw_singular_shape_tensor(ctx, first_bad, shape_tensor_of(ctx, first_bad));
}

}  // namespace HWY_NAMESPACE
}  // namespace peridot::correspondence
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace peridot::correspondence {

CorrespondenceContext make_correspondence_context(const Discretization& disc, const BondList& bonds,
                                                  const std::vector<BlockGeometry>& blocks,
                                                  double partial_volume_radius) {
  PERIDOT_REQUIRE(disc.dimension == 3, "the correspondence model is implemented in 3D only");
  const std::size_t n = disc.num_points();
  PERIDOT_REQUIRE(bonds.offsets.size() == n + 1, "bond list does not match the discretization");
  CorrespondenceContext ctx;
  ctx.disc = &disc;
  ctx.bonds = &bonds;
  ctx.blocks = blocks;
  ctx.partial_volume_radius = partial_volume_radius;
  ctx.weighted_volume.resize(bonds.num_bonds());
  ctx.hourglass_stiffness.assign(blocks.size(), 0.0);
  ctx.hourglass_damping.assign(blocks.size(), 0.0);
  ctx.bulk_viscosity_linear.assign(blocks.size(), 0.0);
  ctx.bulk_viscosity_quadratic.assign(blocks.size(), 0.0);
  const auto& x = disc.x;
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
      const std::uint32_t j = bonds.neighbors[b];
      const double xi = norm(x.get(j) - x.get(i));
      ctx.weighted_volume[b] = pair_weight(ctx, disc.block[i], disc.block[j], xi) * disc.volume[j];
    }
  return ctx;
}

double pair_weight(const CorrespondenceContext& ctx, std::size_t own, std::size_t other, double xi) {
  const BlockGeometry& g = ctx.blocks[own];
  return influence(g.influence, xi, g.horizon) *
         partial_volume_factor(xi, std::max(g.horizon, ctx.blocks[other].horizon), ctx.partial_volume_radius);
}

void compute_kinematics(const CorrespondenceContext& ctx, const VectorField& u, const VectorField& v,
                        KinematicFields& out) {
  compute_kinematics(ctx, u, v, out, BlockRange{0, ctx.disc->num_points()});
}

HWY_EXPORT(kinematics_pass);

void compute_kinematics(const CorrespondenceContext& ctx, const VectorField& u, const VectorField& v,
                        KinematicFields& out, BlockRange range) {
  simd::apply_environment();
  HWY_DYNAMIC_DISPATCH(kinematics_pass)(ctx, u, v, out, range);
}

bool shape_tensor_well_conditioned(const CorrespondenceContext& ctx, std::size_t i) {
  return well_conditioned(shape_tensor_of(ctx, i), ctx.min_reciprocal_condition);
}

Mat3 mid_step_velocity_gradient(const Mat3& F_end, const Mat3& F_rate, double dt) {
  const Mat3 F_mid = F_end - 0.5 * dt * F_rate;
  return F_rate * F_mid.inverse();
}

}  // namespace peridot::correspondence
#endif  // HWY_ONCE
