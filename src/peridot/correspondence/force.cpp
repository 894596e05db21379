// Correspondence force state and gather (Foster, Silling & Chen 2010 eqs 4, 25) and hourglass control
// (reference/algorithms.md §2a).
#include "peridot/correspondence/force.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

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

void compute_correspondence_force(const CorrespondenceContext& ctx, const KinematicFields& kin,
                                  const StressFields& s, const VectorField& u, const VectorField& v, VectorField& f,
                                  BlockRange range, VectorField* hourglass_force,
                                  VectorField* mirror_force) {
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
#pragma omp parallel for schedule(static)
  for (std::size_t i = range.begin; i < range.end; ++i) {
    const double* Ai = A + 9 * i;
    const double* Fi = F + 9 * i;
    const double* Fdot_i = Fdot + 9 * i;
    const double ci = hourglass ? ctx.hourglass_stiffness[disc.block[i]] : 0.0;
    const double hi = damping ? ctx.hourglass_damping[disc.block[i]] : 0.0;
    double fi[3] = {0, 0, 0}, fh[3] = {0, 0, 0};
    // One bond to a partner j at reference offset ξ with relative displacement du = u_j − u_i and velocity
    // dv, j's force tensor Aj, F_j, Ḟ_j and block, ω_i = wi and ω_j = wj (the bond j → i), volume vj.
    auto add_bond = [&](const double* xi, const double* du, const double* dv, const double* Aj, const double* Fj,
                        const double* Fdot_j, std::size_t block_j, double wi, double wj, double vj) {
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
        for (int r = 0; r < 3; ++r) fh[r] += scalar * y[r] * vj;
      }
      for (int r = 0; r < 3; ++r) fi[r] += t[r] * vj;
    };
    double xi[3], du[3], dv[3];
    for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
      if (bonds.broken[b]) continue;
      const std::size_t j = bonds.neighbors[b];
      bond_offsets(x, up, vp, i, j, xi, du, dv);  // dv is read only with dashpots
      add_bond(xi, du, dv, A + 9 * j, F + 9 * j, Fdot + 9 * j, static_cast<std::size_t>(disc.block[j]),
               ctx.bond_weight[b], ctx.bond_weight[bonds.reverse[b]], disc.volume[j]);
    }
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
        add_bond(xi, du, dv, Aj, Fj, Fdot_j, static_cast<std::size_t>(disc.block[j]), mirror.weight[b],
                 mirror.partner_weight[b], disc.volume[j]);
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

}  // namespace peridot::correspondence
