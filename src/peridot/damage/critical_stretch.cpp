#include "peridot/damage/critical_stretch.hpp"

#include "peridot/materials/bond_loop.hpp"

namespace peridot {

using namespace bond_loop;

void compute_damage(const ModelContext& ctx, std::vector<double>& damage) {
  const double* x = ctx.disc->x.data();
  const BondList& bonds = *ctx.bonds;
  damage.resize(ctx.disc->num_points());
  for_each_block_geometry(ctx, [&](auto dim, const MaterialParams&, BlockRange range) {
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
