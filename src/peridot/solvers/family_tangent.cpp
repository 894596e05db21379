#include "peridot/solvers/family_tangent.hpp"

#include <cmath>

#include "peridot/materials/bond_loop.hpp"
#include "peridot/materials/lps.hpp"
#include "peridot/materials/pmb.hpp"

namespace peridot {

std::string_view model_without_exact_tangent(const ModelContext& ctx) {
  for (const MaterialParams& p : ctx.params)
    if (!is_model<Pmb>(p) && !is_model<Lps>(p)) return model_name(p.model);
  return {};
}

void family_tangent(const ModelContext& ctx, const double* u, std::size_t i, FamilyTangent& out) {
  using bond_loop::bond_scale;
  using bond_loop::neighbor_volume;
  const BondList& bonds = *ctx.bonds;
  const double* x = ctx.disc->x.data();
  const std::size_t block = static_cast<std::size_t>(ctx.disc->block[i]);
  const MaterialParams& p = ctx.params[block];
  const bool lps = is_model<Lps>(p);
  const double volume_i = ctx.disc->volume[i];
  const double thermal = bond_loop::thermal_stretch(ctx, i);

  // Per intact bond: direction M, |y|, t, the axial stiffness b = ∂t/∂e, a = ∂t/∂θ, the weights of its force
  // on i and on j, and γ = ∂θ_i/∂u_j (lps).
  struct Bond {
    double m[3], length, t, b, a, on_i, on_j, gamma;
  };
  thread_local std::vector<Bond> family;
  family.clear();
  out.points.assign(1, static_cast<std::uint32_t>(i));
  double dilatation_sum = 0;  // Σ ω̃ ξ e V
  for (std::uint64_t k = bonds.offsets[i]; k < bonds.offsets[i + 1]; ++k) {
    if (bonds.broken[k]) continue;
    const std::uint32_t j = bonds.neighbors[k];
    const auto g = bond_loop::bond_geometry<3>(x, u, i, j);
    const double omega = influence(p.influence, g.xi, p.horizon) * bond_scale(ctx, p, k);
    const double v_j = neighbor_volume(ctx, i, j, g.xi);
    const double e = g.e - thermal * g.xi;
    Bond bond{};
    for (int d = 0; d < 3; ++d) bond.m[d] = g.y[d] / g.length;
    bond.length = g.length;
    bond.on_i = volume_i * v_j;
    bond.on_j = ctx.disc->volume[j] * neighbor_volume(ctx, j, i, g.xi);
    if (lps) {
      dilatation_sum += omega * g.xi * e * v_j;
      bond.t = e;  // t needs θ: finished below
      bond.b = omega;
      bond.a = g.xi;
      bond.gamma = omega * g.xi * v_j;
    } else {
      const double c = ctx.model_params_of<Pmb>(block).micromodulus;
      bond.b = 0.5 * c * omega / g.xi;
      bond.t = bond.b * e;
    }
    family.push_back(bond);
    out.points.push_back(j);
  }
  if (lps) {
    const Lps::Params& mp = ctx.model_params_of<Lps>(block);
    const double inverse_m = ctx.inverse_weighted_volume[i];
    const double kappa = mp.surface_correction ? ctx.point_constants[0][i] : 1.0;
    const double theta = mp.dilatation_factor * dilatation_sum * inverse_m;
    const double reduced = kappa * mp.inverse_dilatation_factor;  // κ/n
    for (Bond& bond : family) {
      const double omega = bond.b, xi = bond.a, e = bond.t;
      bond.t = omega * inverse_m * (mp.alpha_volumetric * theta * xi + mp.alpha_deviatoric * (e - reduced * theta * xi));
      bond.b = omega * inverse_m * mp.alpha_deviatoric;
      bond.a = omega * inverse_m * (mp.alpha_volumetric - mp.alpha_deviatoric * reduced) * xi;
      bond.gamma *= mp.dilatation_factor * inverse_m;
    }
  }

  const std::size_t n = out.points.size();
  out.coupled = lps;
  out.blocks.assign(9 * n * n, 0.0);
  const auto at = [&](std::size_t r, std::size_t c) { return out.blocks.data() + 9 * (r * n + c); };
  // The bond's own blocks: ∂(t M)/∂u_j = b M⊗M + (t/|y|)(I − M⊗M), and minus that for u_i; on row i with
  // −W_ij (R = −f V), on row j with +W_ji.
  for (std::size_t q = 0; q < family.size(); ++q) {
    const Bond& bond = family[q];
    const std::size_t j = q + 1;
    const double turning = bond.t / bond.length;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        const double d = (bond.b - turning) * bond.m[r] * bond.m[c] + (r == c ? turning : 0.0);
        at(0, 0)[3 * r + c] += bond.on_i * d;
        at(0, j)[3 * r + c] -= bond.on_i * d;
        at(j, 0)[3 * r + c] -= bond.on_j * d;
        at(j, j)[3 * r + c] += bond.on_j * d;
      }
  }
  if (!lps) return;
  // The dilatation's part ρ γᵀ: ρ_j = W_ji a_j M_j (row j), ρ_i = −Σ_j W_ij a_j M_j; γ_l = ∂θ_i/∂u_l, γ_i = −Σ γ_l.
  thread_local std::vector<double> rho, gamma;
  rho.assign(3 * n, 0.0);
  gamma.assign(3 * n, 0.0);
  for (std::size_t q = 0; q < family.size(); ++q) {
    const Bond& bond = family[q];
    for (int d = 0; d < 3; ++d) {
      rho[3 * (q + 1) + d] = bond.on_j * bond.a * bond.m[d];
      rho[d] -= bond.on_i * bond.a * bond.m[d];
      gamma[3 * (q + 1) + d] = bond.gamma * bond.m[d];
      gamma[d] -= bond.gamma * bond.m[d];
    }
  }
  for (std::size_t r = 0; r < n; ++r)
    for (std::size_t c = 0; c < n; ++c) {
      double* k = at(r, c);
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) k[3 * a + b] += rho[3 * r + a] * gamma[3 * c + b];
    }
}

}  // namespace peridot
