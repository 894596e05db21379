#include "peridot/materials/lps_viscoelastic.hpp"

#include <cmath>

#include "peridot/materials/bond_loop.hpp"

namespace peridot {

using namespace bond_loop;

void LpsViscoelastic::commit(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                             MaterialHistory& history, const MaterialParams& p, BlockRange range, double dt) {
  const double* x = ctx.disc->x.data();
  const double* up = u.data();
  const BondList& bonds = *ctx.bonds;
  KernelFields s;
  s.bond0 = history.bond[0].data();
  s.bond1 = history.bond[1].data();
  double* back = history.bond[0].data();
  double* previous = history.bond[1].data();
  const double tau = p.relaxation_time;
  // 1 − ε and 1 − ε² with expm1, so that Δt ≪ τ_b keeps its digits.
  const double one_minus_decay = -std::expm1(-dt / tau), one_minus_decay2 = -std::expm1(-2 * dt / tau);
  with_dimension(ctx.disc->dimension, [&](auto dim) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      const double dashpot = p.relaxing_fraction * p.alpha_deviatoric * ctx.inverse_weighted_volume[i] / tau;
      double dissipated = 0;
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        if (bonds.broken[b]) continue;
        const std::uint32_t j = bonds.neighbors[b];
        const BondGeometry<Dim> g = bond_geometry<Dim>(x, up, i, j);
        const double ed = g.e - theta[i] * g.xi * p.inverse_dilatation_factor;
        if (dt > 0) {  // (V4)
          const double rate_tau = (ed - previous[b]) / dt * tau;  // ρτ
          const double z0 = previous[b] - back[b] - rate_tau;
          const double integral = rate_tau * rate_tau * dt + 2 * rate_tau * tau * z0 * one_minus_decay +
                                  z0 * z0 * 0.5 * tau * one_minus_decay2;
          dissipated += dashpot * influence(p.influence, g.xi, p.horizon) * integral * neighbor_volume(ctx, i, j, g.xi);
        }
        back[b] = back_extension(p, s, b, ed);  // reads bond b only, then overwrites it
        previous[b] = ed;
      }
      history.dissipation[i] += dissipated;
    }
  });
}

}  // namespace peridot
