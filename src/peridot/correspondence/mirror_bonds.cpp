// Bonds to mirror images across symmetry planes (mirror_bonds.hpp).
#include "peridot/correspondence/mirror_bonds.hpp"

#include <algorithm>

#include "peridot/core/error.hpp"
#include "peridot/neighbor/influence.hpp"
#include "peridot/neighbor/neighborhood.hpp"

namespace peridot::correspondence {

MirrorBonds build_mirror_bonds(const Discretization& disc, const BondList& bonds, std::size_t owned,
                               const std::vector<MirrorPlane>& planes, const MirrorBondOptions& options) {
  MirrorBonds m;
  m.planes = planes;
  if (planes.empty()) return m;
  PERIDOT_REQUIRE(planes.size() < 256, "more than 255 symmetry planes");
  const std::size_t n = disc.num_points();
  const double beyond = options.bond_beyond_horizon ? options.partial_volume_radius : 0.0;
  m.offsets.assign(n + 1, 0);
  m.plane_of.assign(n, 0);
  // The mirror partners of i across plane k, in the order i itself, then its family (sorted): the same
  // order on every rank, since a family is sorted by global index.
  auto for_each_partner = [&](std::size_t i, std::size_t k, auto&& visit) {
    const MirrorPlane& plane = planes[k];
    const Vec3 xi = disc.x.get(i);
    const double horizon_i = options.horizon_of_block[disc.block[i]];
    auto consider = [&](std::size_t j) {
      if (!options.block_is_mirrored[disc.block[j]]) return;
      const double horizon = std::max(horizon_i, options.horizon_of_block[disc.block[j]]);
      const Vec3 bond = reflect_point(plane, disc.x.get(j)) - xi;
      const double length = norm(bond);
      if (length == 0 || length > horizon + beyond) return;
      const double factor = partial_volume_factor(length, horizon, options.partial_volume_radius);
      if (beyond > 0 && factor <= 0) return;
      visit(j, length, horizon, factor);
    };
    consider(i);
    for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) consider(bonds.neighbors[b]);
  };
  for (std::size_t i = 0; i < owned; ++i) {
    if (!options.block_is_mirrored[disc.block[i]]) continue;
    std::size_t count = 0, planes_touched = 0;
    for (std::size_t k = 0; k < planes.size(); ++k) {
      std::size_t here = 0;
      for_each_partner(i, k, [&](std::size_t, double, double, double) { ++here; });
      if (here == 0) continue;
      ++planes_touched;
      count += here;
      m.plane_of[i] = static_cast<std::uint8_t>(k);
    }
    PERIDOT_REQUIRE(planes_touched <= 1, "a point has mirror bonds across two symmetry planes");
    m.offsets[i + 1] = count;
  }
  for (std::size_t i = 0; i < n; ++i) m.offsets[i + 1] += m.offsets[i];
  const std::size_t total = m.offsets[n];
  m.source.resize(total);
  m.weight.resize(total);
  m.partner_weight.resize(total);
  for (std::size_t i = 0; i < owned; ++i) {
    if (m.offsets[i] == m.offsets[i + 1]) continue;
    std::uint64_t b = m.offsets[i];
    const InfluenceKind own = options.influence_of_block[disc.block[i]];
    for_each_partner(i, m.plane_of[i], [&](std::size_t j, double length, double, double factor) {
      const InfluenceKind other = options.influence_of_block[disc.block[j]];
      m.source[b] = static_cast<std::uint32_t>(j);
      m.weight[b] = influence(own, length, options.horizon_of_block[disc.block[i]]) * factor;
      m.partner_weight[b] = influence(other, length, options.horizon_of_block[disc.block[j]]) * factor;
      ++b;
    });
  }
  for (MirrorPlane& plane : m.planes) plane.block_touches.assign(options.horizon_of_block.size(), 0);
  for (std::size_t i = 0; i < owned; ++i)
    if (m.offsets[i] < m.offsets[i + 1]) m.planes[m.plane_of[i]].block_touches[disc.block[i]] = 1;
  m.active = total > 0;
  return m;
}

}  // namespace peridot::correspondence
