#include "peridot/parallel/domain.hpp"

#include <algorithm>

#include "peridot/parallel/partition.hpp"

namespace peridot {

LocalDomain decompose(const Communicator& comm, const Discretization& global, const NeighborhoodOptions& options) {
  const std::size_t n = global.num_points();
  const std::size_t begin = slice_begin(n, comm.rank(), comm.size()), end = slice_begin(n, comm.rank() + 1, comm.size());
  const std::vector<int> owner = partition_points(comm, global, count_bonds(global, options, begin, end));

  LocalDomain d;
  std::vector<std::uint32_t> owned;
  for (std::size_t i = 0; i < n; ++i)
    if (owner[i] == comm.rank()) owned.push_back(static_cast<std::uint32_t>(i));
  const BondList families = build_neighborhood(global, options, owned);

  // Ghosts: partners owned elsewhere, grouped by owner rank, increasing global index within a group.
  std::vector<std::uint32_t> ghosts;
  for (std::uint32_t j : families.neighbors)
    if (owner[j] != comm.rank()) ghosts.push_back(j);
  std::sort(ghosts.begin(), ghosts.end(), [&](std::uint32_t a, std::uint32_t b) {
    return owner[a] != owner[b] ? owner[a] < owner[b] : a < b;
  });
  ghosts.erase(std::unique(ghosts.begin(), ghosts.end()), ghosts.end());
  std::vector<int> ghost_owner;
  for (std::uint32_t g : ghosts) ghost_owner.push_back(owner[g]);

  d.owned = owned.size();
  d.global_index = owned;
  d.global_index.insert(d.global_index.end(), ghosts.begin(), ghosts.end());
  const std::size_t local = d.global_index.size();
  std::vector<std::uint32_t> local_of(n, UINT32_MAX);
  for (std::size_t l = 0; l < local; ++l) local_of[d.global_index[l]] = static_cast<std::uint32_t>(l);

  d.disc.dimension = global.dimension;
  d.disc.block_names = global.block_names;
  d.disc.x.resize(local);
  d.disc.volume.resize(local);
  d.disc.block.resize(local);
  d.disc.input_id.resize(local);
  for (std::size_t l = 0; l < local; ++l) {
    const std::uint32_t g = d.global_index[l];
    d.disc.x.set(l, global.x.get(g));
    d.disc.volume[l] = global.volume[g];
    d.disc.block[l] = global.block[g];
    d.disc.input_id[l] = global.input_id.empty() ? g : global.input_id[g];
  }

  d.bonds.offsets.assign(local + 1, families.offsets.back());
  std::copy(families.offsets.begin(), families.offsets.end(), d.bonds.offsets.begin());
  d.bonds.neighbors.resize(families.neighbors.size());
  for (std::size_t b = 0; b < families.neighbors.size(); ++b) d.bonds.neighbors[b] = local_of[families.neighbors[b]];
  d.bonds.broken.assign(families.neighbors.size(), 0);
  d.halo = Halo(comm, owned, ghosts, ghost_owner);
  return d;
}

}  // namespace peridot
