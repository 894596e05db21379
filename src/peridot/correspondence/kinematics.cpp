// Shape tensor, deformation gradient and its rate: Foster, Silling & Chen (2010) eqs 10, 13, 14.
#include "peridot/correspondence/kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "peridot/core/error.hpp"
#include "peridot/materials/material.hpp"
#include "peridot/neighbor/neighborhood.hpp"

namespace peridot::correspondence {

CorrespondenceContext make_correspondence_context(const Discretization& disc, const BondList& bonds,
                                                  const std::vector<BlockGeometry>& blocks,
                                                  double partial_volume_radius) {
  PERIDOT_REQUIRE(disc.dimension == 3, "the correspondence model is implemented in 3D only");
  const std::size_t n = disc.num_points();
  PERIDOT_REQUIRE(bonds.offsets.size() == n + 1, "bond list does not match the discretization");
  PERIDOT_REQUIRE(bonds.reverse.size() == bonds.num_bonds(), "the correspondence gather needs build_reverse_bonds");
  CorrespondenceContext ctx;
  ctx.disc = &disc;
  ctx.bonds = &bonds;
  const std::size_t nnz = bonds.num_bonds();
  ctx.bond_weight.resize(nnz + bonds.partner_slots);
  ctx.hourglass_stiffness.assign(blocks.size(), 0.0);
  ctx.hourglass_damping.assign(blocks.size(), 0.0);
  const auto& x = disc.x;
  // ω⟨ξ⟩ of a bond from a point of block `own` to one of block `other`, with its partial-volume factor.
  auto weight = [&](const BlockGeometry& own, const BlockGeometry& other, double xi) {
    return influence(own.influence, xi, own.horizon) *
           partial_volume_factor(xi, std::max(own.horizon, other.horizon), partial_volume_radius);
  };
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const BlockGeometry& gi = blocks[disc.block[i]];
    for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
      const std::uint32_t j = bonds.neighbors[b];
      const BlockGeometry& gj = blocks[disc.block[j]];
      ctx.bond_weight[b] = weight(gi, gj, norm(x.get(j) - x.get(i)));
      // A ghost partner's bond j → i (its slot past the rank's own bonds), as j's rank computes it.
      if (bonds.reverse[b] >= nnz) ctx.bond_weight[bonds.reverse[b]] = weight(gj, gi, norm(x.get(i) - x.get(j)));
    }
  }
  return ctx;
}

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

}  // namespace

void compute_kinematics(const CorrespondenceContext& ctx, const VectorField& u, const VectorField& v,
                        KinematicFields& out) {
  compute_kinematics(ctx, u, v, out, BlockRange{0, ctx.disc->num_points()});
}

void compute_kinematics(const CorrespondenceContext& ctx, const VectorField& u, const VectorField& v,
                        KinematicFields& out, BlockRange range) {
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
#pragma omp parallel for schedule(static) reduction(min : first_bad)
  for (std::size_t i = range.begin; i < range.end; ++i) {
    double K[9] = {}, N[9] = {}, Ndot[9] = {};
    // One bond of weight w (ω V_j) to a partner at reference offset ξ, relative displacement and velocity.
    auto add_bond = [&](double w, const double* xi, const double* du, const double* dv) {
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
          const double y = xi[r] + du[r];
          K[3 * r + c] += w * xi[r] * xi[c];
          N[3 * r + c] += w * y * xi[c];
          Ndot[3 * r + c] += w * dv[r] * xi[c];
        }
    };
    double xi[3], du[3], dv[3];
    for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
      if (bonds.broken[b]) continue;
      const std::size_t j = bonds.neighbors[b];
      bond_offsets(x, up, vp, i, j, xi, du, dv);
      add_bond(ctx.bond_weight[b] * disc.volume[j], xi, du, dv);
    }
    if (mirrored && mirror.planes[mirror.plane_of[i]].active) {
      const MirrorPlane& plane = mirror.planes[mirror.plane_of[i]];
      for (std::uint64_t b = mirror.offsets[i]; b < mirror.offsets[i + 1]; ++b) {
        const std::size_t j = mirror.source[b];
        mirror_bond_offsets(plane, x, up, vp, i, j, xi, du, dv);
        add_bond(mirror.weight[b] * disc.volume[j], xi, du, dv);
      }
    }
    const Mat3 Km = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(K);
    // K is symmetric positive semi-definite; its extreme eigenvalues measure how far it is from singular.
    const Eigen::SelfAdjointEigenSolver<Mat3> eig(Km, Eigen::EigenvaluesOnly);
    const double lmin = eig.eigenvalues()(0), lmax = eig.eigenvalues()(2);
    if (!(lmax > 0) || !(lmin >= ctx.min_reciprocal_condition * lmax)) {
      first_bad = std::min(first_bad, i);
      continue;
    }
    const Mat3 Kinv = Km.inverse();
    const Mat3 F = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(N) * Kinv;
    const Mat3 Fdot = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(Ndot) * Kinv;
    out.shape_inverse.set(i, Kinv);
    out.deformation_gradient.set(i, F);
    out.deformation_gradient_rate.set(i, Fdot);
  }
  if (first_bad != std::numeric_limits<std::size_t>::max()) {
    // Recompute K of that point alone for the message.
    Mat3 K = Mat3::Zero();
    for (std::uint64_t b = bonds.offsets[first_bad]; b < bonds.offsets[first_bad + 1]; ++b) {
      if (bonds.broken[b]) continue;
      const std::size_t j = bonds.neighbors[b];
      const Vec3d xi(x[3 * j] - x[3 * first_bad], x[3 * j + 1] - x[3 * first_bad + 1],
                     x[3 * j + 2] - x[3 * first_bad + 2]);
      K += ctx.bond_weight[b] * disc.volume[j] * xi * xi.transpose();
    }
    if (mirrored && mirror.planes[mirror.plane_of[first_bad]].active)
      for (std::uint64_t b = mirror.offsets[first_bad]; b < mirror.offsets[first_bad + 1]; ++b) {
        const Vec3 offset = reflect_point(mirror.planes[mirror.plane_of[first_bad]], disc.x.get(mirror.source[b])) -
                            disc.x.get(first_bad);
        const Vec3d xi(offset.x, offset.y, offset.z);
        K += mirror.weight[b] * disc.volume[mirror.source[b]] * xi * xi.transpose();
      }
    throw_singular_shape_tensor(ctx, first_bad, K);
  }
}

Mat3 mid_step_velocity_gradient(const Mat3& F_end, const Mat3& F_rate, double dt) {
  const Mat3 F_mid = F_end - 0.5 * dt * F_rate;
  return F_rate * F_mid.inverse();
}

}  // namespace peridot::correspondence
