#pragma once
// Building blocks shared by every bond loop (forces, energy, damage): the geometry of a bond, the
// neighbour volume it sees, and the per-block dispatch to compile-time dimension and model types.
#include <algorithm>
#include <cmath>
#include <type_traits>

#include "peridot/neighbor/neighborhood.hpp"
#include "peridot/materials/model_context.hpp"

namespace peridot::bond_loop {

/// The surface correction's factor G of bond b of a block (ModelContext::bond_scale; 1 where the block has none).
inline double bond_scale(const ModelContext& ctx, const MaterialParams& p, std::uint64_t b) {
  return p.surface_correction && !ctx.bond_scale.empty() ? ctx.bond_scale[b] : 1.0;
}

/// The scalar force state of a bond end: the model's corrected_force_scalar where the block has the surface
/// correction and the model has one (lps: its κ term), else its force_scalar. Corrected is known at compile time
/// in the vectorised loops (their Scaled flag).
template <bool Corrected, class Model, class Params>
inline double end_force_scalar(const Params& mp, const KernelFields& s, std::size_t i, std::uint64_t b, double e,
                               double xi, double omega) {
  if constexpr (Corrected && requires { &Model::corrected_force_scalar; })
    return Model::corrected_force_scalar(mp, s, i, b, e, xi, omega);
  else
    return Model::force_scalar(mp, s, i, b, e, xi, omega);
}

/// The same, with the block's surface_correction read at run time (the general bond paths).
template <class Model, class Params>
inline double end_force_scalar(const MaterialParams& block, const Params& mp, const KernelFields& s, std::size_t i,
                               std::uint64_t b, double e, double xi, double omega) {
  return block.surface_correction ? end_force_scalar<true, Model>(mp, s, i, b, e, xi, omega)
                                  : end_force_scalar<false, Model>(mp, s, i, b, e, xi, omega);
}

/// Geometry of one bond i → j in the current configuration.
template <int Dim>
struct BondGeometry {
  double xi;       ///< reference length |ξ| (m)
  double e;        ///< extension |Y| − |ξ| (m)
  double y[Dim];   ///< deformed bond Y
  double length;   ///< |Y|
};

template <int Dim>
inline BondGeometry<Dim> bond_geometry(const double* x, const double* u, std::size_t i, std::size_t j) {
  BondGeometry<Dim> g;
  double xi2 = 0, y2 = 0;
  for (int d = 0; d < Dim; ++d) {
    const double dx = x[3 * j + d] - x[3 * i + d];
    const double dy = dx + (u[3 * j + d] - u[3 * i + d]);
    xi2 += dx * dx;
    y2 += dy * dy;
    g.y[d] = dy;
  }
  g.xi = std::sqrt(xi2);
  g.length = std::sqrt(y2);
  g.e = g.length - g.xi;
  return g;
}

/// Reference bond length only (for set-up loops).
template <int Dim>
inline double bond_length(const double* x, std::size_t i, std::size_t j) {
  double xi2 = 0;
  for (int d = 0; d < Dim; ++d) {
    const double dx = x[3 * j + d] - x[3 * i + d];
    xi2 += dx * dx;
  }
  return std::sqrt(xi2);
}

/// α (T − T_ref) of point i: the stretch of its free thermal expansion (0 without a temperature field).
inline double thermal_stretch(const ModelContext& ctx, std::size_t i) {
  return ctx.thermal_stretch.empty() ? 0.0 : ctx.thermal_stretch[i];
}

/// The extension of bond i → j that point i's model sees: e − α_i (T_i − T_ref) ξ. A free body heated
/// uniformly expands by αΔT in every direction without force; a constrained one carries the force of −αΔT.
template <int Dim>
inline double mechanical_extension(const ModelContext& ctx, std::size_t i, const BondGeometry<Dim>& g) {
  return g.e - thermal_stretch(ctx, i) * g.xi;
}

/// The extension the failure rule sees, the same from either end: e − ½(α_i ΔT_i + α_j ΔT_j) ξ.
inline double bond_mechanical_extension(const ModelContext& ctx, std::size_t i, std::size_t j, double e, double xi) {
  if (ctx.thermal_stretch.empty()) return e;
  return e - 0.5 * (ctx.thermal_stretch[i] + ctx.thermal_stretch[j]) * xi;
}

/// Neighbour volume seen by a bond, with the partial-volume factor when enabled (the pair horizon is the
/// larger of the two blocks', as in the neighbour search) and the isotropic quadrature's direction weight of
/// point i's block when its deck asks for it.
inline double neighbor_volume(const ModelContext& ctx, std::size_t i, std::size_t j, double xi) {
  double v = ctx.disc->volume[j];
  const auto& blocks = ctx.disc->block;
  const MaterialParams& p = ctx.params[blocks[i]];
  if (p.quadrature.on) {
    const double* x = ctx.disc->x.data();
    v *= quadrature_weight(p.quadrature, x[3 * j] - x[3 * i], x[3 * j + 1] - x[3 * i + 1], x[3 * j + 2] - x[3 * i + 2], xi);
  }
  if (ctx.partial_volume_radius <= 0) return v;
  const double horizon = std::max(p.horizon, ctx.params[blocks[j]].horizon);
  return v * partial_volume_factor(xi, horizon, ctx.partial_volume_radius);
}

/// Runs body(Dim, Model, params, model_params, range) for every block of a model with a bond kernel, with
/// the dimension and the block's model as compile-time types and model_params its Model::Params. Blocks of
/// a model without one (correspondence: solvers/correspondence_blocks.hpp computes their force) are skipped.
template <class Body>
void for_each_block(const ModelContext& ctx, Body&& body) {
  for (std::size_t b = 0; b < ctx.ranges.size(); ++b) {
    const MaterialParams& p = ctx.params[b];
    const BlockRange range = ctx.ranges[b];
    if (range.begin == range.end) continue;
    with_dimension(ctx.disc->dimension, [&](auto dim) {
      with_model(p.model, [&](auto model) {
        using Model = decltype(model);
        if constexpr (Model::has_bond_kernel) body(dim, model, p, ctx.model_params_of<Model>(b), range);
      });
    });
  }
}

/// Runs body(Dim, params, range) for every block, whatever its model (loops over geometry only: weighted
/// volume, damage, stable time step).
template <class Body>
void for_each_block_geometry(const ModelContext& ctx, Body&& body) {
  for (std::size_t b = 0; b < ctx.ranges.size(); ++b) {
    const BlockRange range = ctx.ranges[b];
    if (range.begin == range.end) continue;
    with_dimension(ctx.disc->dimension, [&](auto dim) { body(dim, ctx.params[b], range); });
  }
}

}  // namespace peridot::bond_loop
