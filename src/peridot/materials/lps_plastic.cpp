#include "peridot/materials/lps_plastic.hpp"

#include <cmath>
#include <numbers>

#include "peridot/solvers/bond_loop.hpp"

namespace peridot {

using namespace bond_loop;

double plastic_yield_norm_factor(InfluenceKind influence, double horizon, int dimension, PlaneKind plane,
                                 double thickness) {
  constexpr double pi = std::numbers::pi;
  double psi_per_sigma2 = 0;  // ψ0/σ_Y²
  if (dimension == 3) {
    const double m = 4 * pi * influence_moment(influence, horizon, 4);
    psi_per_sigma2 = 10 * pi * influence_squared_moment(influence, horizon, 4) / (m * m);  // (C1)
  } else {
    const double m = 2 * pi * thickness * influence_moment(influence, horizon, 3);
    const double factor = plane == PlaneKind::stress ? 2 * pi : 8 * pi / 3;  // (C2) | (C3)
    psi_per_sigma2 = factor * thickness * influence_squared_moment(influence, horizon, 3) / (m * m);
  }
  return std::sqrt(2 * psi_per_sigma2);
}

void LpsPlastic::prepare(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                         MaterialHistory& history, const MaterialParams& p, BlockRange range) {
  const double* x = ctx.disc->x.data();
  const double* up = u.data();
  const BondList& bonds = *ctx.bonds;
  const double* plastic_extension = history.bond[0].data();
  const double k = p.yield_norm_factor, H = p.hardening_modulus;
  with_dimension(ctx.disc->dimension, [&](auto dim) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      const double alpha = p.alpha_deviatoric * ctx.inverse_weighted_volume[i];
      double norm2 = 0, weighted = 0;  // ‖t^d_tr‖² and S = Σ (t^d_tr)²/ω V
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        if (bonds.broken[b]) continue;
        const std::uint32_t j = bonds.neighbors[b];
        const BondGeometry<Dim> g = bond_geometry<Dim>(x, up, i, j);
        const double omega = influence(p.influence, g.xi, p.horizon);
        const double ed = g.e - theta[i] * g.xi / p.dilatation_factor;
        const double t = alpha * omega * (ed - plastic_extension[b]);
        const double v = neighbor_volume(ctx, i, j, g.xi);
        norm2 += t * t * v;
        weighted += t * t / omega * v;
      }
      const double norm = std::sqrt(norm2);
      const double yield_n = p.yield_stress + H * history.plastic_strain[i];
      if (!(norm > k * yield_n)) {  // elastic (also a point without intact bonds)
        history.yield_scale[i] = 1;
        history.plastic_strain_increment[i] = 0;
        continue;
      }
      const double g = k * weighted / (alpha * norm);
      const double increment = g * (1 - k * yield_n / norm) / (1 + g * k * H / norm);  // (P5)
      history.plastic_strain_increment[i] = increment;
      history.yield_scale[i] = k * (yield_n + H * increment) / norm;
    }
  });
}

void LpsPlastic::commit(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                        MaterialHistory& history, const MaterialParams& p, BlockRange range, double /*dt*/) {
  const double* x = ctx.disc->x.data();
  const double* up = u.data();
  const BondList& bonds = *ctx.bonds;
  double* plastic_extension = history.bond[0].data();
  with_dimension(ctx.disc->dimension, [&](auto dim) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      const double r = history.yield_scale[i];
      if (r == 1) continue;  // elastic step: nothing changes
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        if (bonds.broken[b]) continue;
        const BondGeometry<Dim> g = bond_geometry<Dim>(x, up, i, bonds.neighbors[b]);
        const double ed = g.e - theta[i] * g.xi / p.dilatation_factor;
        plastic_extension[b] += (1 - r) * (ed - plastic_extension[b]);  // (P4)
      }
      const double increment = history.plastic_strain_increment[i];
      history.plastic_strain[i] += increment;
      // W_p increment = σ_Y,n+1 Δε̄p (P5)
      history.dissipation[i] += (p.yield_stress + p.hardening_modulus * history.plastic_strain[i]) * increment;
      history.yield_scale[i] = 1;
      history.plastic_strain_increment[i] = 0;
    }
  });
}

}  // namespace peridot
