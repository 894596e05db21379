#include "peridot/materials/lps_plastic.hpp"

#include <cmath>
#include <numbers>

#include "peridot/materials/bond_loop.hpp"

namespace peridot {

using namespace bond_loop;

double plastic_yield_calibration(int dimension, PlaneKind plane) {
  if (dimension == 3) return 5.0;                      // (C1)
  return plane == PlaneKind::stress ? 2.0 : 8.0 / 3.0;  // (C2) | (C3)
}

void LpsPlastic::calibrate(ModelContext& ctx, const MaterialParams& p, BlockRange range) {
  const double* x = ctx.disc->x.data();
  const BondList& bonds = *ctx.bonds;
  with_dimension(ctx.disc->dimension, [&](auto dim) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      double moment = 0;  // Σ ω² ξ² V over the reference family
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        const std::uint32_t j = bonds.neighbors[b];
        const double xi = bond_length<Dim>(x, i, j), omega = influence(p.influence, xi, p.horizon);
        moment += omega * omega * xi * xi * neighbor_volume(ctx, i, j, xi);
      }
      ctx.yield_norm_factor[i] = std::sqrt(p.yield_calibration * moment) * ctx.inverse_weighted_volume[i];
    }
  });
}

void LpsPlastic::prepare(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                         MaterialHistory& history, const MaterialParams& p, BlockRange range) {
  const double* x = ctx.disc->x.data();
  const double* up = u.data();
  const BondList& bonds = *ctx.bonds;
  const double* plastic_extension = history.bond[0].data();
  const double H = p.hardening_modulus;
  with_dimension(ctx.disc->dimension, [&](auto dim) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      const double alpha = p.alpha_deviatoric * ctx.inverse_weighted_volume[i];
      const double released = history.released_extension[i];  // (P8)
      double norm2 = 0, weighted = 0;  // ‖t^d_tr‖² and S = Σ (t^d_tr)²/ω V
      double along = 0;                // Σ ω ξ (e^d − e^dp_n) V over the intact bonds (P6)
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        if (bonds.broken[b]) continue;
        const std::uint32_t j = bonds.neighbors[b];
        const BondGeometry<Dim> g = bond_geometry<Dim>(x, up, i, j);
        const double omega = influence(p.influence, g.xi, p.horizon);
        const double ed = g.e - theta[i] * g.xi * p.inverse_dilatation_factor;
        const double elastic = ed - plastic_extension[b] - released * g.xi;
        const double t = alpha * omega * elastic;
        const double v = neighbor_volume(ctx, i, j, g.xi);
        norm2 += t * t * v;
        weighted += t * t / omega * v;
        along += omega * g.xi * elastic * v;
      }
      const double norm = std::sqrt(norm2);
      const double k = ctx.yield_norm_factor[i];  // (C)
      const double yield_n = p.yield_stress + H * history.plastic_strain[i];
      if (!(norm > k * yield_n)) {  // elastic (also a point without intact bonds)
        history.yield_scale[i] = 1;
        history.plastic_strain_increment[i] = 0;
        history.deviatoric_moment[i] = along * ctx.inverse_weighted_volume[i];
        continue;
      }
      const double g = k * weighted / (alpha * norm);
      const double increment = g * (1 - k * yield_n / norm) / (1 + g * k * H / norm);  // (P5)
      history.plastic_strain_increment[i] = increment;
      history.yield_scale[i] = k * (yield_n + H * increment) / norm;
      history.deviatoric_moment[i] = history.yield_scale[i] * along * ctx.inverse_weighted_volume[i];
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
      const double r = history.yield_scale[i], released = history.released_extension[i];
      if (r == 1 && released == 0) continue;  // elastic step, no bond broke: nothing changes
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        if (bonds.broken[b]) continue;
        const BondGeometry<Dim> g = bond_geometry<Dim>(x, up, i, bonds.neighbors[b]);
        const double ed = g.e - theta[i] * g.xi * p.inverse_dilatation_factor;
        const double plastic = plastic_extension[b] + released * g.xi;  // (P8)
        plastic_extension[b] = plastic + (1 - r) * (ed - plastic);      // (P4)
      }
      history.released_extension[i] = 0;
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
