#include "peridot/damage/critical_stretch.hpp"

#include "peridot/solvers/bond_loop.hpp"

namespace peridot {

using namespace bond_loop;

std::uint64_t break_bonds(const ModelContext& ctx, const VectorField& u) {
  const double* x = ctx.disc->x.data();
  const double* up = u.data();
  BondList& bonds = *ctx.bonds;
  const auto& blocks = ctx.disc->block;
  const bool has_no_fail = !ctx.no_fail.empty();
  std::uint64_t broken_now = 0;
  for_each_block(ctx, [&](auto dim, auto, const MaterialParams& p, BlockRange range) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static) reduction(+ : broken_now)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      if (has_no_fail && ctx.no_fail[i]) continue;
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        if (bonds.broken[b]) continue;
        const std::uint32_t j = bonds.neighbors[b];
        // The decision is symmetric (same stretch bits, min of the two critical stretches, either end
        // no-fail), so bond j → i breaks in the same step without any communication.
        double critical = p.critical_stretch;
        if (j < range.begin || j >= range.end) critical = std::min(critical, ctx.params[blocks[j]].critical_stretch);
        if (!std::isfinite(critical) || (has_no_fail && ctx.no_fail[j])) continue;
        const BondGeometry<Dim> g = bond_geometry<Dim>(x, up, i, j);
        if (g.e > critical * g.xi) {
          bonds.broken[b] = 1;
          ++broken_now;
        }
      }
    }
  });
  return broken_now;
}

void compute_damage(const ModelContext& ctx, std::vector<double>& damage) {
  const double* x = ctx.disc->x.data();
  const BondList& bonds = *ctx.bonds;
  damage.resize(ctx.disc->num_points());
  for_each_block(ctx, [&](auto dim, auto, const MaterialParams&, BlockRange range) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      double all = 0, intact = 0;
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        const std::uint32_t j = bonds.neighbors[b];
        const double v = neighbor_volume(ctx, i, j, bond_length<Dim>(x, i, j));
        all += v;
        if (!bonds.broken[b]) intact += v;
      }
      damage[i] = all > 0 ? 1 - intact / all : 0.0;
    }
  });
}

}  // namespace peridot
