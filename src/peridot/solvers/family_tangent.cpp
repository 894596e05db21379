#include "peridot/solvers/family_tangent.hpp"

#include <cmath>
#include <string>

#include "peridot/core/error.hpp"
#include "peridot/materials/bond_loop.hpp"
#include "peridot/materials/lps.hpp"
#include "peridot/materials/pmb.hpp"

namespace peridot {

bool has_exact_tangent(std::string_view model) { return model == Pmb::name || model == Lps::name; }

void FamilyTangent::add_block(std::size_t r, std::size_t c, double k[9]) const {
  const auto bond = [&](std::size_t q, double weight) {  // weight × D of partner slot q
    const double* m = direction.data() + 3 * (q - 1);
    const double a = weight * axial[q - 1], t = weight * turning[q - 1];
    for (int x = 0; x < 3; ++x)
      for (int y = 0; y < 3; ++y) k[3 * x + y] += a * m[x] * m[y] + (x == y ? t : 0.0);
  };
  if (r == 0 && c == 0) {
    for (std::size_t q = 1; q < points.size(); ++q) bond(q, on_i[q - 1]);
  } else if (r == 0) {
    bond(c, -on_i[c - 1]);
  } else if (c == 0) {
    bond(r, -on_j[r - 1]);
  } else if (r == c) {
    bond(r, on_j[r - 1]);
  }
  if (rho.empty()) return;
  for (int x = 0; x < 3; ++x)
    for (int y = 0; y < 3; ++y) k[3 * x + y] += rho[3 * r + x] * gamma[3 * c + y];
}

void family_tangent(const ModelContext& ctx, const double* u, std::size_t i, FamilyTangent& out) {
  using bond_loop::bond_scale;
  using bond_loop::neighbor_volume;
  const BondList& bonds = *ctx.bonds;
  const double* x = ctx.disc->x.data();
  const std::size_t block = static_cast<std::size_t>(ctx.disc->block[i]);
  const MaterialParams& p = ctx.params[block];
  const bool lps = is_model<Lps>(p);
  PERIDOT_REQUIRE(lps || is_model<Pmb>(p), "family_tangent: no exact tangent for model " + std::string(model_name(p.model)));
  const double volume_i = ctx.disc->volume[i];
  const double thermal = bond_loop::thermal_stretch(ctx, i);
  out.points.assign(1, static_cast<std::uint32_t>(i));
  for (auto* v : {&out.direction, &out.axial, &out.turning, &out.on_i, &out.on_j, &out.rho, &out.gamma}) v->clear();
  // Per intact bond: M, and for now e, ω̃, ξ, V_j (lps) or b, t (pmb); |y| in `turning`.
  thread_local std::vector<double> extension, omega_xi_v, xi;
  extension.clear();
  omega_xi_v.clear();
  xi.clear();
  double dilatation_sum = 0;  // Σ ω̃ ξ e V
  for (std::uint64_t k = bonds.offsets[i]; k < bonds.offsets[i + 1]; ++k) {
    if (bonds.broken[k]) continue;
    const std::uint32_t j = bonds.neighbors[k];
    const auto g = bond_loop::bond_geometry<3>(x, u, i, j);
    const double omega = influence(p.influence, g.xi, p.horizon) * bond_scale(ctx, p, k);
    const double v_j = neighbor_volume(ctx, i, j, g.xi);
    const double e = g.e - thermal * g.xi;
    for (int d = 0; d < 3; ++d) out.direction.push_back(g.y[d] / g.length);
    out.on_i.push_back(volume_i * v_j);
    out.on_j.push_back(ctx.disc->volume[j] * neighbor_volume(ctx, j, i, g.xi));
    out.points.push_back(j);
    if (lps) {
      dilatation_sum += omega * g.xi * e * v_j;
      extension.push_back(e);
      omega_xi_v.push_back(omega * g.xi * v_j);
      out.axial.push_back(omega);     // ω̃ for now
      out.turning.push_back(g.length);  // |y| for now
      xi.push_back(g.xi);
    } else {
      const double b = 0.5 * ctx.model_params_of<Pmb>(block).micromodulus * omega / g.xi, t = b * e;
      out.axial.push_back(b - t / g.length);
      out.turning.push_back(t / g.length);
    }
  }
  if (!lps) return;
  const Lps::Params& mp = ctx.model_params_of<Lps>(block);
  const double inverse_m = ctx.inverse_weighted_volume[i];
  const double kappa = mp.surface_correction ? ctx.point_constants[0][i] : 1.0;
  const double theta = mp.dilatation_factor * dilatation_sum * inverse_m;
  const double reduced = kappa * mp.inverse_dilatation_factor;  // κ/n
  const std::size_t n = out.points.size() - 1;
  out.rho.assign(3 * (n + 1), 0.0);
  out.gamma.assign(3 * (n + 1), 0.0);
  for (std::size_t q = 0; q < n; ++q) {
    const double omega = out.axial[q], length = out.turning[q], e = extension[q];
    // t = (ω̃/m)[α_v θ ξ + α_d (e − κθξ/n)], b = ∂t/∂e = ω̃ α_d/m, a = ∂t/∂θ = (ω̃/m)(α_v − κα_d/n) ξ.
    const double t = omega * inverse_m * (mp.alpha_volumetric * theta * xi[q] + mp.alpha_deviatoric * (e - reduced * theta * xi[q]));
    const double b = omega * inverse_m * mp.alpha_deviatoric;
    const double a = omega * inverse_m * (mp.alpha_volumetric - mp.alpha_deviatoric * reduced) * xi[q];
    const double gamma = mp.dilatation_factor * inverse_m * omega_xi_v[q];  // ∂θ_i/∂e_q
    out.axial[q] = b - t / length;
    out.turning[q] = t / length;
    const double* m = out.direction.data() + 3 * q;
    for (int d = 0; d < 3; ++d) {
      out.rho[3 * (q + 1) + d] = out.on_j[q] * a * m[d];
      out.rho[d] -= out.on_i[q] * a * m[d];
      out.gamma[3 * (q + 1) + d] = gamma * m[d];
      out.gamma[d] -= gamma * m[d];
    }
  }
}

}  // namespace peridot
