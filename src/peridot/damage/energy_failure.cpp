#include "peridot/damage/energy_failure.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "peridot/materials/bond_loop.hpp"

namespace peridot {

using namespace bond_loop;

double crack_crossing_bonds(int dimension, double m) {
  // The lattice vectors n (in units of Δx) of a family, |n| ≤ m within the neighbour search's allowance
  // (neighbor/neighborhood.cpp: 1e-10 relative). For each n with n_⊥ > 0, the bonds of vector n that cross
  // the crack plane start on the n_⊥ rows below it; on each row their crossing points form a unit lattice in
  // the plane, so exactly one per cell when the cell's edges count ½ and its corners ¼.
  const double cutoff = m * (1 + 1e-10), cutoff2 = cutoff * cutoff;
  const long r = static_cast<long>(std::floor(cutoff));
  double sum = 0;
  for (long normal = 1; normal <= r; ++normal) {
    if (dimension == 1) {  // a bar: the bonds of length n Δx crossing a point between two points
      sum += static_cast<double>(normal);
      continue;
    }
    for (long a = -r; a <= r; ++a) {
      if (dimension == 2) {
        if (static_cast<double>(normal * normal + a * a) <= cutoff2) sum += static_cast<double>(normal);
        continue;
      }
      for (long b = -r; b <= r; ++b)
        if (static_cast<double>(normal * normal + a * a + b * b) <= cutoff2) sum += static_cast<double>(normal);
    }
  }
  return sum;
}

EnergyFailure::EnergyFailure(const ModelContext& ctx, double spacing, double cross_section) {
  const std::size_t blocks = ctx.params.size();
  count_.assign(blocks, 0.0);
  threshold_.assign(blocks, std::numeric_limits<double>::infinity());
  for (std::size_t b = 0; b < blocks; ++b) {
    const MaterialParams& p = ctx.params[b];
    if (!(p.fracture_energy > 0)) continue;
    count_[b] = crack_micropotentials(p.dimension, p.horizon / spacing);
    // A_c: the crack plane's cell, the bar's section in 1D
    const double area = p.dimension == 1 ? cross_section : p.dimension == 2 ? spacing * cross_section : spacing * spacing;
    threshold_[b] = count_[b] > 0 ? 2 * p.fracture_energy * area / count_[b] : 0.0;
  }
  const std::size_t n = ctx.bonds->num_bonds();
  work_.assign(n, 0.0);
  force_.assign(n, 0.0);
  extension_.assign(n, 0.0);
}

namespace {

/// τ of a bond of a point of block `block` to j: the smaller of the two blocks'.
inline double pair_threshold(const ModelContext& ctx, const std::vector<double>& threshold, std::int32_t block,
                             std::uint32_t j) {
  const std::int32_t other = ctx.disc->block[j];
  const double own = threshold[static_cast<std::size_t>(block)];
  return other == block ? own : std::min(own, threshold[static_cast<std::size_t>(other)]);
}

/// T = t_ij + t_ji of bond b (i → j) from the kernels, each end with its own model, parameters, influence and
/// mechanical extension, as the general path of the force loop computes them (solvers/internal_force.cpp).
template <int Dim, class Model>
double bond_force_states(const ModelContext& ctx, const MaterialParams& p, const typename Model::Params& mp,
                         const KernelFields& s, std::size_t i, std::uint64_t b, std::uint32_t j,
                         const BondGeometry<Dim>& g) {
  const bool any_history = !ctx.bonds->reverse.empty();
  const std::uint64_t partner_bond = any_history ? ctx.bonds->reverse[b] : 0;
  // The surface correction's factor, as the force loop applies it (G_ij = G_ji to the bit).
  const double omega = influence(p.influence, g.xi, p.horizon) * bond_scale(ctx, p, b);
  const double t_ij = end_force_scalar<Model>(p, mp, s, i, b, mechanical_extension(ctx, i, g), g.xi, omega);
  const double e_j = mechanical_extension(ctx, j, g);
  const auto other = static_cast<std::size_t>(ctx.disc->block[j]);
  double t_ji;
  if (ctx.disc->block[j] == ctx.disc->block[i]) {
    t_ji = end_force_scalar<Model>(p, mp, s, j, partner_bond, e_j, g.xi, omega);
  } else {
    const MaterialParams& pj = ctx.params[other];
    t_ji = with_model(pj.model, [&](auto model) -> double {
      using Other = decltype(model);
      if constexpr (!Other::has_bond_kernel)
        throw std::logic_error("energy failure: model " + std::string(Other::name) + " has no bond kernel");
      else
        return end_force_scalar<Other>(pj, ctx.model_params_of<Other>(other), s, j, partner_bond, e_j, g.xi,
                                   influence(pj.influence, g.xi, pj.horizon) * bond_scale(ctx, pj, b));
    });
  }
  return t_ij + t_ji;  // from j: t_ji + t_ij, the same bits
}

/// Runs body(Dim, Model, params, model_params, range, block) for the blocks whose bonds the criterion may
/// concern: a block with it, or one with an interface (whose bonds may reach a block with it).
template <class Body>
void for_each_concerned_block(const ModelContext& ctx, const std::vector<double>& threshold, Body&& body) {
  for_each_block(ctx, [&](auto dim, auto model, const MaterialParams& p, const auto& mp, BlockRange range) {
    const auto block = static_cast<std::size_t>(ctx.disc->block[range.begin]);
    const bool interface = ctx.family_in_block.empty() || !ctx.family_in_block[block];
    if (std::isfinite(threshold[block]) || interface) body(dim, model, p, mp, range, block);
  });
}

}  // namespace

void EnergyFailure::accumulate(const ModelContext& ctx, const VectorField& u, const KernelFields& fields) {
  const double* x = ctx.disc->x.data();
  const double* up = u.data();
  const BondList& bonds = *ctx.bonds;
  for_each_concerned_block(ctx, threshold_, [&](auto dim, auto model, const MaterialParams& p, const auto& mp,
                                                BlockRange range, std::size_t block) {
    constexpr int Dim = decltype(dim)::value;
    using Model = decltype(model);
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i)
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        if (bonds.broken[b]) continue;
        const std::uint32_t j = bonds.neighbors[b];
        if (!std::isfinite(pair_threshold(ctx, threshold_, static_cast<std::int32_t>(block), j))) continue;
        const BondGeometry<Dim> g = bond_geometry<Dim>(x, up, i, j);
        const double e = bond_mechanical_extension(ctx, i, j, g.e, g.xi);
        const double T = bond_force_states<Dim, Model>(ctx, p, mp, fields, i, b, j, g);
        work_[b] += 0.5 * (force_[b] + T) * (e - extension_[b]);
        force_[b] = T;
        extension_[b] = e;
      }
  });
}

std::uint64_t EnergyFailure::break_bonds(const ModelContext& ctx, const VectorField& u, const KernelFields* trial) const {
  const double* x = ctx.disc->x.data();
  const double* up = u.data();
  const double* volume = ctx.disc->volume.data();
  const std::uint8_t* no_fail = ctx.no_fail.empty() ? nullptr : ctx.no_fail.data();
  BondList& bonds = *ctx.bonds;
  std::uint64_t broken = 0;
  for_each_concerned_block(ctx, threshold_, [&](auto dim, auto model, const MaterialParams& p, const auto& mp,
                                                BlockRange range, std::size_t block) {
    constexpr int Dim = decltype(dim)::value;
    using Model = decltype(model);
#pragma omp parallel for schedule(static) reduction(+ : broken)
    for (std::size_t i = range.begin; i < range.end; ++i)
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        if (bonds.broken[b]) continue;
        const std::uint32_t j = bonds.neighbors[b];
        const double tau = pair_threshold(ctx, threshold_, static_cast<std::int32_t>(block), j);
        if (!std::isfinite(tau) || (no_fail && (no_fail[i] || no_fail[j]))) continue;
        const BondGeometry<Dim> g = bond_geometry<Dim>(x, up, i, j);
        const double e = bond_mechanical_extension(ctx, i, j, g.e, g.xi);
        if (!(e > 0)) continue;  // compression never breaks a bond
        double W = work_[b];
        if (trial) W += 0.5 * (force_[b] + bond_force_states<Dim, Model>(ctx, p, mp, *trial, i, b, j, g)) *
                        (e - extension_[b]);
        if (W * (volume[i] * volume[j]) >= tau) {  // V_i V_j: the same bits from j
          bonds.broken[b] = 1;
          ++broken;
        }
      }
  });
  return broken;
}

}  // namespace peridot
