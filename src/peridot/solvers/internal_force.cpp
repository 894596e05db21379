#include "peridot/solvers/internal_force.hpp"

#include <algorithm>
#include <cmath>

#include "peridot/core/error.hpp"
#include "peridot/damage/critical_stretch.hpp"
#include "peridot/solvers/bond_loop.hpp"

namespace peridot {

bool ModelContext::any_dilatation() const {
  return std::any_of(params.begin(), params.end(),
                     [](const MaterialParams& p) { return with_model(p.model, [](auto m) { return m.uses_dilatation; }); });
}

bool ModelContext::any_damage() const {
  return std::any_of(params.begin(), params.end(), [](const MaterialParams& p) { return std::isfinite(p.critical_stretch); });
}

int ModelContext::bond_history_arrays() const {
  int arrays = 0;
  for (const MaterialParams& p : params)
    arrays = std::max(arrays, with_model(p.model, [](auto m) { return decltype(m)::bond_history_arrays; }));
  return arrays;
}

void calibrate_models(ModelContext& ctx) {
  const bool plastic = std::any_of(ctx.params.begin(), ctx.params.end(),
                                   [](const MaterialParams& p) { return p.model == ModelKind::lps_plastic; });
  ctx.yield_norm_factor.assign(plastic ? ctx.disc->num_points() : 0, 0.0);
  for (std::size_t b = 0; b < ctx.ranges.size(); ++b)
    if (ctx.params[b].model == ModelKind::lps_plastic && ctx.ranges[b].begin < ctx.ranges[b].end)
      LpsPlastic::calibrate(ctx, ctx.params[b], ctx.ranges[b]);
}

KernelFields kernel_fields(const ModelContext& ctx, const std::vector<double>& theta, const MaterialHistory* history) {
  KernelFields s;
  s.theta = theta.data();
  s.inverse_m = ctx.inverse_weighted_volume.data();
  if (history) {
    s.yield_scale = history->yield_scale.data();
    s.deviatoric_moment = history->deviatoric_moment.data();
    s.released_extension = history->released_extension.data();
    s.bond0 = history->bond[0].empty() ? nullptr : history->bond[0].data();
    s.bond1 = history->bond[1].empty() ? nullptr : history->bond[1].data();
  }
  PERIDOT_REQUIRE(ctx.bond_history_arrays() == 0 || (s.bond0 && s.yield_scale),
                  "an inelastic model needs the material history");
  return s;
}

using namespace bond_loop;

namespace {

/// t_ji for a neighbour in another block (interfaces only): dispatch on the neighbour's model.
inline double other_block_force_scalar(const MaterialParams& pj, const KernelFields& s, std::size_t j,
                                       std::uint64_t reverse_bond, double e, double xi) {
  const double omega = influence(pj.influence, xi, pj.horizon);
  // Bonds between a correspondence block and another model's block are refused at set-up
  // (CorrespondenceBlocks), so an interface bond never reaches a correspondence neighbour.
  return with_bond_model(pj.model, [&](auto model) { return model.force_scalar(pj, s, j, reverse_bond, e, xi, omega); });
}

/// Critical stretch of a bond of a point of block `block`: the smaller of its two blocks'.
inline double pair_critical_stretch(const ModelContext& ctx, const MaterialParams& p, std::int32_t block, std::uint32_t j) {
  const std::int32_t other = ctx.disc->block[j];
  if (other == block) return p.critical_stretch;
  return std::min(p.critical_stretch, ctx.params[other].critical_stretch);
}

}  // namespace

void compute_weighted_volume(const ModelContext& ctx, std::vector<double>& m) {
  const std::size_t n = ctx.disc->num_points();
  m.assign(n, 0.0);
  const double* x = ctx.disc->x.data();
  const BondList& bonds = *ctx.bonds;
  for_each_block_geometry(ctx, [&](auto dim, const MaterialParams& p, BlockRange range) {
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

void compute_dilatation(const ModelContext& ctx, const VectorField& u, std::vector<double>& theta, bool fail_bonds,
                        MaterialHistory* history) {
  double* released = history && !history->released_extension.empty() ? history->released_extension.data() : nullptr;
  const BondFailure failure(ctx);
  const std::vector<double>& inverse_m = ctx.inverse_weighted_volume;
  const double* x = ctx.disc->x.data();
  const double* up = u.data();
  BondList& bonds = *ctx.bonds;  // broken flags are written when fail_bonds
  const auto& blocks = ctx.disc->block;
  theta.resize(ctx.disc->num_points());
  const KernelFields fields = kernel_fields(ctx, theta, history);
  for_each_block(ctx, [&](auto dim, auto model, const MaterialParams& p, BlockRange range) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      double sum = 0, lost = 0;
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        if (bonds.broken[b]) continue;
        const std::uint32_t j = bonds.neighbors[b];
        const BondGeometry<Dim> g = bond_geometry<Dim>(x, up, i, j);
        const double term = influence(p.influence, g.xi, p.horizon) * g.xi * model.dilatation_extension(fields, b, g.e) *
                            neighbor_volume(ctx, i, j, g.xi);
        if (fail_bonds && failure.fails(i, j, g.e, g.xi, pair_critical_stretch(ctx, p, blocks[i], j))) {
          bonds.broken[b] = 1;
          lost += term;
          continue;
        }
        sum += term;
      }
      theta[i] = p.dilatation_factor * sum * inverse_m[i];
      if (released && fail_bonds) released[i] = lost * inverse_m[i];
    }
  });
}

void prepare_history(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                     MaterialHistory& history) {
  for_each_block(ctx, [&](auto, auto model, const MaterialParams& p, BlockRange range) {
    if constexpr (decltype(model)::bond_history_arrays > 0) model.prepare(ctx, u, theta, history, p, range);
  });
}

void commit_history(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                    MaterialHistory& history, double dt) {
  for_each_block(ctx, [&](auto, auto model, const MaterialParams& p, BlockRange range) {
    if constexpr (decltype(model)::bond_history_arrays > 0) model.commit(ctx, u, theta, history, p, range, dt);
  });
}

void compute_internal_force(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                            VectorField& f, bool fail_bonds, const MaterialHistory* history) {
  const BondFailure failure(ctx);
  const KernelFields fields = kernel_fields(ctx, theta, history);
  const double* x = ctx.disc->x.data();
  const double* up = u.data();
  double* fp = f.data();
  const BondList& bonds = *ctx.bonds;
  const auto& blocks = ctx.disc->block;
  const double* volume = ctx.disc->volume.data();
  const std::uint32_t* neighbors = bonds.neighbors.data();
  const std::uint32_t* reverse = bonds.reverse.data();
  std::uint8_t* broken = ctx.bonds->broken.data();
  const bool any_history = ctx.bond_history_arrays() > 0;
  const bool after_force = ctx.bond_failure_after_force;
  for_each_block(ctx, [&](auto dim, auto model, const MaterialParams& p, BlockRange range) {
    constexpr int Dim = decltype(dim)::value;
    // The partner's bond j → i, for models that keep per-bond history; never read by the others.
    constexpr bool reads_partner_bond = decltype(model)::bond_history_arrays > 0;
    const bool partial_volume = ctx.partial_volume_radius > 0;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      double x_i[3], u_i[3];  // position and displacement of point i
      for (int d = 0; d < 3; ++d) x_i[d] = x[3 * i + d], u_i[d] = up[3 * i + d];
      // Neighbours are sorted by global index, and every block is a contiguous global index range, so
      // the bonds to this block form one run [b_begin, b_end) between the bonds to lower and to higher
      // blocks: a branch-free loop that vectorises. Bonds to other blocks (interfaces only) take the
      // general path below. (Found by block, not index: a rank's ghosts sit after its owned points.)
      const std::int32_t block_i = blocks[i];
      std::uint64_t b_begin = bonds.offsets[i], b_end = bonds.offsets[i + 1];
      while (b_begin < b_end && blocks[neighbors[b_begin]] < block_i) ++b_begin;
      while (b_end > b_begin && blocks[neighbors[b_end - 1]] > block_i) --b_end;
      double fx = 0, fy = 0, fz = 0;
#pragma omp simd reduction(+ : fx, fy, fz)
      for (std::uint64_t b = b_begin; b < b_end; ++b) {
        const std::uint32_t j = neighbors[b];
        double dy[3], xi2 = 0, y2 = 0;
        for (int d = 0; d < Dim; ++d) {
          const double dx = x[3 * j + d] - x_i[d];
          dy[d] = dx + (up[3 * j + d] - u_i[d]);
          xi2 += dx * dx;
          y2 += dy[d] * dy[d];
        }
        const double xi = std::sqrt(xi2), length = std::sqrt(y2), e = length - xi;
        const double omega = influence(p.influence, xi, p.horizon);
        const std::uint64_t partner_bond = reads_partner_bond ? reverse[b] : 0;
        const double t = model.force_scalar(p, fields, i, b, e, xi, omega) +
                         model.force_scalar(p, fields, j, partner_bond, e, xi, omega);
        double v = volume[j];
        if (partial_volume) v *= partial_volume_factor(xi, p.horizon, ctx.partial_volume_radius);
        const bool was_broken = broken[b];
        const bool breaks = fail_bonds && !was_broken && failure.fails(i, j, e, xi, p.critical_stretch);
        if (breaks) broken[b] = 1;
        const bool carries = !(was_broken || (breaks && !after_force));
        const double scale = carries ? t * v / length : 0.0;
        fx += scale * dy[0];
        fy += scale * dy[1];
        if constexpr (Dim == 3) fz += scale * dy[2];
      }
      // Interface bonds: t_ji from the neighbour's own model and parameters.
      auto interface_bond = [&](std::uint64_t b) {
        if (broken[b]) return;
        const std::uint32_t j = neighbors[b];
        const BondGeometry<Dim> g = bond_geometry<Dim>(x, up, i, j);
        if (fail_bonds && failure.fails(i, j, g.e, g.xi, pair_critical_stretch(ctx, p, blocks[i], j))) {
          broken[b] = 1;
          if (!after_force) return;
        }
        const double omega = influence(p.influence, g.xi, p.horizon);
        const double t = model.force_scalar(p, fields, i, b, g.e, g.xi, omega) +
                         other_block_force_scalar(ctx.params[blocks[j]], fields, j, any_history ? reverse[b] : 0, g.e, g.xi);
        const double scale = t * neighbor_volume(ctx, i, j, g.xi) / g.length;
        fx += scale * g.y[0];
        fy += scale * g.y[1];
        if constexpr (Dim == 3) fz += scale * g.y[2];
      };
      for (std::uint64_t b = bonds.offsets[i]; b < b_begin; ++b) interface_bond(b);
      for (std::uint64_t b = b_end; b < bonds.offsets[i + 1]; ++b) interface_bond(b);
      fp[3 * i] = fx;
      fp[3 * i + 1] = fy;
      fp[3 * i + 2] = fz;
    }
  });
}

void compute_strain_energy_density(const ModelContext& ctx, const VectorField& u, const std::vector<double>& theta,
                                   std::vector<double>& W, const MaterialHistory* history) {
  const KernelFields fields = kernel_fields(ctx, theta, history);
  const double* x = ctx.disc->x.data();
  const double* up = u.data();
  const BondList& bonds = *ctx.bonds;
  W.resize(ctx.disc->num_points());
  for_each_block(ctx, [&](auto dim, auto model, const MaterialParams& p, BlockRange range) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      double sum = model.point_energy(p, fields, i);
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        if (bonds.broken[b]) continue;
        const std::uint32_t j = bonds.neighbors[b];
        const BondGeometry<Dim> g = bond_geometry<Dim>(x, up, i, j);
        const double omega = influence(p.influence, g.xi, p.horizon);
        sum += model.bond_energy(p, fields, i, b, g.e, g.xi, omega) * neighbor_volume(ctx, i, j, g.xi);
      }
      W[i] = sum;
    }
  });
}

double stable_time_step(const ModelContext& ctx) {
  const double* x = ctx.disc->x.data();
  const BondList& bonds = *ctx.bonds;
  double dt = std::numeric_limits<double>::infinity();
  for_each_block_geometry(ctx, [&](auto dim, const MaterialParams& p, BlockRange range) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static) reduction(min : dt)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      double stiffness = 0;
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        const std::uint32_t j = bonds.neighbors[b];
        const double xi = bond_length<Dim>(x, i, j);
        stiffness += neighbor_volume(ctx, i, j, xi) * p.stable_micromodulus / xi;
      }
      if (stiffness == 0) continue;
      double dt_i = std::sqrt(2 * p.density / stiffness);
      // A dashpot c_v beside each spring c (correspondence hourglass damping): central differences with
      // damping ratio ζ are stable for Δt ≤ (2/ω)(√(1 + ζ²) − ζ), ω = 2/dt_i the highest frequency of the
      // sums above; the sums of c_v/ξ are c_v/c times those of c/ξ, so ζ = (c_v/c)/dt_i (assumes the
      // highest mode is damped in full: conservative).
      if (p.stable_damping > 0) {
        const double zeta = p.stable_damping / p.stable_micromodulus / dt_i;
        dt_i *= std::sqrt(1 + zeta * zeta) - zeta;
      }
      dt = std::min(dt, dt_i);
    }
  });
  return dt;
}

}  // namespace peridot
