#include "peridot/parallel/domain.hpp"

#include <algorithm>

#include "peridot/core/error.hpp"
#include "peridot/parallel/partition.hpp"

namespace peridot {

LocalDomain decompose(const Communicator& comm, const Discretization& global, const NeighborhoodOptions& options,
                      PartitionMethod method) {
  const std::size_t n = global.num_points();
  const std::size_t begin = slice_begin(n, comm.rank(), comm.size()), end = slice_begin(n, comm.rank() + 1, comm.size());
  const std::vector<int> owner = partition_points(comm, global, count_bonds(global, options, begin, end), method);

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
  // Each owner is asked for the points this rank holds as ghosts: one global index per ghost.
  std::vector<int> count(static_cast<std::size_t>(comm.size()), 0);
  for (int r : ghost_owner) ++count[r];
  d.halo = Halo::serve(comm, d.owned, ghosts, count, 1, [&](const std::uint32_t* global) {
    const auto found = std::lower_bound(owned.begin(), owned.end(), *global);
    PERIDOT_REQUIRE(found != owned.end() && *found == *global, "a ghost was asked of a rank that does not own it");
    return static_cast<std::uint32_t>(found - owned.begin());
  });
  d.ghost_owner = std::move(ghost_owner);
  return d;
}

namespace {

/// The bond of local point i (owned) to the point of global index `partner`, found by binary search: a
/// family is sorted by global index.
std::uint64_t find_bond(const LocalDomain& d, std::size_t i, std::uint32_t partner) {
  const auto& nb = d.bonds.neighbors;
  std::uint64_t lo = d.bonds.offsets[i], hi = d.bonds.offsets[i + 1];
  while (lo < hi) {
    const std::uint64_t mid = (lo + hi) / 2;
    if (d.global_index[nb[mid]] < partner) lo = mid + 1;
    else hi = mid;
  }
  PERIDOT_REQUIRE(lo < d.bonds.offsets[i + 1] && d.global_index[nb[lo]] == partner, "bond families are not symmetric");
  return lo;
}

}  // namespace

Halo build_partner_bonds(const Communicator& comm, LocalDomain& d) {
  BondList& bonds = d.bonds;
  const std::size_t nnz = bonds.num_bonds();
  PERIDOT_REQUIRE(nnz <= UINT32_MAX, "more than 2^32 bonds on a rank: reverse bond indices need 64 bits");
  bonds.reverse.assign(nnz, 0);
  // Bonds to ghosts, grouped by the ghost's owner, in bond order within a group: one slot each.
  struct ToGhost {
    std::uint64_t bond;
    std::uint32_t point;  ///< its owned end
  };
  std::vector<ToGhost> to_ghost;
  for (std::size_t i = 0; i < d.owned; ++i)
    for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
      const std::uint32_t j = bonds.neighbors[b];
      if (j < d.owned) bonds.reverse[b] = static_cast<std::uint32_t>(find_bond(d, j, d.global_index[i]));
      else to_ghost.push_back({b, static_cast<std::uint32_t>(i)});
    }
  auto owner_of = [&](const ToGhost& t) { return d.ghost_owner[bonds.neighbors[t.bond] - d.owned]; };
  std::stable_sort(to_ghost.begin(), to_ghost.end(), [&](const ToGhost& a, const ToGhost& b) { return owner_of(a) < owner_of(b); });
  PERIDOT_REQUIRE(nnz + to_ghost.size() <= UINT32_MAX, "more than 2^32 bonds and partner slots on a rank");
  bonds.partner_slots = to_ghost.size();

  // Each owner is asked for the bond j → i of every slot: (global j, global i).
  std::vector<int> count(static_cast<std::size_t>(comm.size()), 0);
  std::vector<std::uint32_t> requests;
  for (std::size_t k = 0; k < to_ghost.size(); ++k) {
    const ToGhost& t = to_ghost[k];
    bonds.reverse[t.bond] = static_cast<std::uint32_t>(nnz + k);
    ++count[owner_of(t)];
    requests.push_back(d.global_index[bonds.neighbors[t.bond]]);
    requests.push_back(d.global_index[t.point]);
  }
  const auto owned_begin = d.global_index.begin(), owned_end = owned_begin + static_cast<std::ptrdiff_t>(d.owned);
  return Halo::serve(comm, nnz, requests, count, 2, [&](const std::uint32_t* pair) {
    const auto j = std::lower_bound(owned_begin, owned_end, pair[0]);
    PERIDOT_REQUIRE(j != owned_end && *j == pair[0], "a partner bond was asked of a rank that does not own it");
    return static_cast<std::uint32_t>(find_bond(d, static_cast<std::size_t>(j - owned_begin), pair[1]));
  });
}

}  // namespace peridot
