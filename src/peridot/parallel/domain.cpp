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
  d.ghost_owner = ghost_owner;
  d.halo = Halo(comm, owned, ghosts, ghost_owner);
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
  std::vector<std::uint64_t> to_ghost;
  for (std::size_t i = 0; i < d.owned; ++i)
    for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
      const std::uint32_t j = bonds.neighbors[b];
      if (j < d.owned) bonds.reverse[b] = static_cast<std::uint32_t>(find_bond(d, j, d.global_index[i]));
      else to_ghost.push_back(b);
    }
  auto owner_of = [&](std::uint64_t b) { return d.ghost_owner[bonds.neighbors[b] - d.owned]; };
  std::stable_sort(to_ghost.begin(), to_ghost.end(), [&](std::uint64_t a, std::uint64_t b) { return owner_of(a) < owner_of(b); });
  PERIDOT_REQUIRE(nnz + to_ghost.size() <= UINT32_MAX, "more than 2^32 bonds on a rank: reverse bond indices need 64 bits");
  bonds.partner_slots = to_ghost.size();

  const int size = comm.size();
  std::vector<int> request_count(size, 0), asked_count;
  std::vector<std::uint32_t> requests;  // (global j, global i) of every slot, in slot order
  for (std::size_t k = 0; k < to_ghost.size(); ++k) {
    const std::uint64_t b = to_ghost[k];
    bonds.reverse[b] = static_cast<std::uint32_t>(nnz + k);
    request_count[owner_of(b)] += 2;
    const std::size_t i = static_cast<std::size_t>(std::upper_bound(bonds.offsets.begin(), bonds.offsets.begin() +
                                                                    static_cast<std::ptrdiff_t>(d.owned) + 1, b) -
                                                   bonds.offsets.begin()) - 1;
    requests.push_back(d.global_index[bonds.neighbors[b]]);
    requests.push_back(d.global_index[i]);
  }
  const std::vector<std::uint32_t> asked = comm.all_to_all(requests, request_count, asked_count);
  const std::vector<int> request_displ = Communicator::offsets(request_count), asked_displ = Communicator::offsets(asked_count);

  const auto owned_begin = d.global_index.begin(), owned_end = owned_begin + static_cast<std::ptrdiff_t>(d.owned);
  std::vector<Halo::Peer> peers;
  for (int r = 0; r < size; ++r) {
    if (request_count[r] == 0 && asked_count[r] == 0) continue;
    Halo::Peer peer;
    peer.rank = r;
    peer.receive_begin = static_cast<std::size_t>(request_displ[r] / 2);
    peer.receive_count = static_cast<std::size_t>(request_count[r] / 2);
    for (int k = asked_displ[r]; k < asked_displ[r] + asked_count[r]; k += 2) {
      const auto j = std::lower_bound(owned_begin, owned_end, asked[k]);
      PERIDOT_REQUIRE(j != owned_end && *j == asked[k], "a partner bond was asked of a rank that does not own it");
      peer.send.push_back(static_cast<std::uint32_t>(find_bond(d, static_cast<std::size_t>(j - owned_begin), asked[k + 1])));
    }
    peers.push_back(std::move(peer));
  }
  return Halo(comm, nnz, to_ghost.size(), std::move(peers));
}

}  // namespace peridot
