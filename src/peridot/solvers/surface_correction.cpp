#include "peridot/solvers/surface_correction.hpp"

#include <algorithm>
#include <cmath>

#include "peridot/materials/bond_loop.hpp"
#include "peridot/materials/models.hpp"
#include "peridot/solvers/internal_force.hpp"

namespace peridot {

double uniaxial_strain_energy(const MaterialParams& p, const Problem& problem, double strain) {
  const bool bond_based = with_model(p.model, [](auto model) { return decltype(model)::info().bond_based; });
  double modulus = 0;
  if (p.dimension == 1) {
    modulus = p.elastic.youngs_modulus;  // a bar
  } else if (p.dimension == 3) {
    const double K = p.elastic.bulk_modulus;
    modulus = bond_based ? 1.8 * K : K + 4 * p.elastic.shear_modulus / 3;  // ν = 1/4: G = 3K/5
  } else {
    const double K2 = planar_bulk_modulus(p.elastic, problem.plane);
    modulus = bond_based ? 1.5 * K2 : K2 + p.elastic.shear_modulus;  // in-plane ν′ = 1/3: G = K′/2
  }
  return 0.5 * modulus * strain * strain;
}

namespace {

/// G of every bond of the owned points of corrected blocks from the ends' factors (1 elsewhere).
void set_bond_scale(ModelContext& ctx, const std::vector<std::vector<double>>& factor, std::size_t owned) {
  const Discretization& disc = *ctx.disc;
  const BondList& bonds = *ctx.bonds;
  const int dim = disc.dimension;
  ctx.bond_scale.assign(bonds.num_bonds(), 1.0);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < owned; ++i) {
    if (!ctx.params[static_cast<std::size_t>(disc.block[i])].surface_correction) continue;
    for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
      const std::uint32_t j = bonds.neighbors[b];
      double xi2 = 0, sum = 0;
      for (int d = 0; d < dim; ++d) {
        const double c = disc.x(j, d) - disc.x(i, d);
        xi2 += c * c;
      }
      for (int d = 0; d < dim; ++d) {
        const double c = disc.x(j, d) - disc.x(i, d);
        const double mean = 0.5 * (factor[d][i] + factor[d][j]);
        sum += c * c / (xi2 * mean * mean);
      }
      ctx.bond_scale[b] = 1 / std::sqrt(sum);
    }
  }
}

}  // namespace

SurfaceCorrectionResult correct_surfaces(ModelContext& ctx, const Problem& problem, MaterialHistory& history,
                                         std::size_t owned, const std::function<void(std::vector<double>&)>& exchange,
                                         const Communicator& comm) {
  const bool any = std::any_of(ctx.params.begin(), ctx.params.end(),
                               [](const MaterialParams& p) { return p.surface_correction; });
  if (!comm.any(any)) return {};
  const Discretization& disc = *ctx.disc;
  const std::size_t n = disc.num_points();
  const int dim = disc.dimension;
  // A small strain: the bond loops are geometrically exact, so W/W_classical carries an error of order ε.
  constexpr double strain = 1e-7;
  std::vector<double> classical(ctx.params.size());
  for (std::size_t b = 0; b < ctx.params.size(); ++b)
    classical[b] = uniaxial_strain_energy(ctx.params[b], problem, strain);
  VectorField u(n);
  std::vector<double> theta, energy;
  // W_d of every owned point under the uniaxial strain along d, with the bond factors as they are.
  auto uniaxial_energy = [&](int d) {
    for (std::size_t i = 0; i < n; ++i)
      for (int a = 0; a < 3; ++a) u(i, a) = a == d ? strain * disc.x(i, a) : 0.0;
    compute_dilatation(ctx, u, theta, false, &history);
    compute_strain_energy_density(ctx, u, theta, energy, &history);
  };
  auto corrected = [&](std::size_t i) {
    return ctx.params[static_cast<std::size_t>(disc.block[i])].surface_correction && energy[i] > 0;  // not bondless
  };
  std::vector<std::vector<double>> factor(static_cast<std::size_t>(dim), std::vector<double>(n, 1.0));
  SurfaceCorrectionResult result;
  for (int d = 0; d < dim; ++d) {
    uniaxial_energy(d);
    for (std::size_t i = 0; i < owned; ++i) {
      if (!corrected(i)) continue;
      factor[d][i] = classical[static_cast<std::size_t>(disc.block[i])] / energy[i];
      result.largest_uncorrected = std::max(result.largest_uncorrected, std::abs(1 / factor[d][i] - 1));
    }
    exchange(factor[d]);
  }
  set_bond_scale(ctx, factor, owned);
  calibrate_models(ctx);  // constants that read the bond factors (lps: κ)
  // What is left: the corrected energies, for the log.
  for (int d = 0; d < dim; ++d) {
    uniaxial_energy(d);
    for (std::size_t i = 0; i < owned; ++i)
      if (corrected(i))
        result.largest_deviation =
            std::max(result.largest_deviation, std::abs(energy[i] / classical[static_cast<std::size_t>(disc.block[i])] - 1));
  }
  result.applied = true;
  result.largest_uncorrected = comm.max(result.largest_uncorrected);
  return result;
}

}  // namespace peridot
