#include "peridot/solvers/internal_force.hpp"

#include <algorithm>
#include <cmath>

#include "peridot/solvers/bond_loop.hpp"

namespace peridot {

bool ModelContext::any_dilatation() const {
  return std::any_of(params.begin(), params.end(),
                     [](const MaterialParams& p) { return with_model(p.model, [](auto m) { return m.uses_dilatation; }); });
}

bool ModelContext::any_damage() const {
  return std::any_of(params.begin(), params.end(), [](const MaterialParams& p) { return std::isfinite(p.critical_stretch); });
}

using namespace bond_loop;

namespace {

/// t_ji for a neighbour in another block (interfaces only): dispatch on the neighbour's model.
inline double other_block_force_scalar(const MaterialParams& pj, double e, double xi, double theta_j, double m_j) {
  const double omega = influence(pj.influence, xi, pj.horizon);
  return with_model(pj.model, [&](auto model) { return model.force_scalar(pj, e, xi, omega, theta_j, m_j); });
}

}  // namespace

void compute_weighted_volume(const ModelContext& ctx, std::vector<double>& m) {
  const std::size_t n = ctx.disc->num_points();
  m.assign(n, 0.0);
  const double* x = ctx.disc->x.data();
  const BondList& bonds = *ctx.bonds;
  for_each_block(ctx, [&](auto dim, auto, const MaterialParams& p, BlockRange range) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      double sum = 0;
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        const std::uint32_t j = bonds.neighbors[b];
        const double xi = bond_length<Dim>(x, i, j);
        sum += influence(p.influence, xi, p.horizon) * xi * xi * neighbor_volume(ctx, i, j, xi);
      }
      m[i] = sum;
    }
  });
}

void compute_dilatation(const ModelContext& ctx, const VectorField& u, const std::vector<double>& m,
                        std::vector<double>& theta) {
  const double* x = ctx.disc->x.data();
  const double* up = u.data();
  const BondList& bonds = *ctx.bonds;
  theta.resize(ctx.disc->num_points());
  for_each_block(ctx, [&](auto dim, auto, const MaterialParams& p, BlockRange range) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      double sum = 0;
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        if (bonds.broken[b]) continue;
        const std::uint32_t j = bonds.neighbors[b];
        const BondGeometry<Dim> g = bond_geometry<Dim>(x, up, i, j);
        sum += influence(p.influence, g.xi, p.horizon) * g.xi * g.e * neighbor_volume(ctx, i, j, g.xi);
      }
      theta[i] = m[i] > 0 ? p.dilatation_factor * sum / m[i] : 0.0;
    }
  });
}

void compute_internal_force(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                            const std::vector<double>& m, VectorField& f) {
  const double* x = ctx.disc->x.data();
  const double* up = u.data();
  double* fp = f.data();
  const BondList& bonds = *ctx.bonds;
  const auto& blocks = ctx.disc->block;
  for_each_block(ctx, [&](auto dim, auto model, const MaterialParams& p, BlockRange range) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      double force[3] = {0, 0, 0};
      const double theta_i = theta[i], m_i = m[i];
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        if (bonds.broken[b]) continue;
        const std::uint32_t j = bonds.neighbors[b];
        const BondGeometry<Dim> g = bond_geometry<Dim>(x, up, i, j);
        const double omega = influence(p.influence, g.xi, p.horizon);
        double t = model.force_scalar(p, g.e, g.xi, omega, theta_i, m_i);
        if (j >= range.begin && j < range.end)
          t += model.force_scalar(p, g.e, g.xi, omega, theta[j], m[j]);
        else
          t += other_block_force_scalar(ctx.params[blocks[j]], g.e, g.xi, theta[j], m[j]);
        const double scale = t * neighbor_volume(ctx, i, j, g.xi) / g.length;
        for (int d = 0; d < Dim; ++d) force[d] += scale * g.y[d];
      }
      for (int d = 0; d < 3; ++d) fp[3 * i + d] = force[d];
    }
  });
}

void compute_strain_energy_density(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                                   const std::vector<double>& m, std::vector<double>& W) {
  const double* x = ctx.disc->x.data();
  const double* up = u.data();
  const BondList& bonds = *ctx.bonds;
  W.resize(ctx.disc->num_points());
  for_each_block(ctx, [&](auto dim, auto model, const MaterialParams& p, BlockRange range) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      double sum = model.point_energy(p, theta[i]);
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        if (bonds.broken[b]) continue;
        const std::uint32_t j = bonds.neighbors[b];
        const BondGeometry<Dim> g = bond_geometry<Dim>(x, up, i, j);
        const double omega = influence(p.influence, g.xi, p.horizon);
        sum += model.bond_energy(p, g.e, g.xi, omega, theta[i], m[i]) * neighbor_volume(ctx, i, j, g.xi);
      }
      W[i] = sum;
    }
  });
}

double stable_time_step(const ModelContext& ctx) {
  const double* x = ctx.disc->x.data();
  const BondList& bonds = *ctx.bonds;
  double dt = std::numeric_limits<double>::infinity();
  for_each_block(ctx, [&](auto dim, auto, const MaterialParams& p, BlockRange range) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static) reduction(min : dt)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      double stiffness = 0;
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        const std::uint32_t j = bonds.neighbors[b];
        const double xi = bond_length<Dim>(x, i, j);
        stiffness += neighbor_volume(ctx, i, j, xi) * p.stable_micromodulus / xi;
      }
      if (stiffness > 0) dt = std::min(dt, std::sqrt(2 * p.density / stiffness));
    }
  });
  return dt;
}

}  // namespace peridot
