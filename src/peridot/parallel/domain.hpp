#pragma once
// One rank's share of a problem (docs/design.md "Determinism"; docs/parallel.md). Lattice bodies are made
// piece by piece and point files and meshes read in shares (decompose: no rank holds the whole problem). The
// points, bonds, state and work are then split:
//  - owned points: those the partition (partition.hpp) gives this rank, in increasing global index, so
//    that each block stays one contiguous range and the point order is the serial one;
//  - ghosts: every bond partner of an owned point that another rank owns (halo.hpp), after the owned points;
//  - bonds: the family of every owned point, exactly the serial family (same neighbours, same order:
//    increasing global index), its neighbours renumbered locally; ghosts have empty families.
// A bond loop over the owned points therefore adds the same terms in the same order as a serial run, and
// every owned point's value is bitwise the serial value, once the ghosts hold their owners' values.
#include <cstdint>
#include <vector>

#include "peridot/deck/problem.hpp"
#include "peridot/neighbor/neighborhood.hpp"
#include "peridot/parallel/halo.hpp"
#include "peridot/state/fields.hpp"

namespace peridot {

struct LocalDomain {
  Discretization disc;  ///< owned points, then ghosts
  BondList bonds;       ///< CSR over every local point; ghosts' families are empty
  std::size_t owned = 0;
  std::vector<std::uint32_t> global_index;  ///< local → global point index
  std::vector<int> ghost_owner;             ///< owner rank of ghost owned + g
  Halo halo;
  std::size_t global_points = 0;            ///< of all ranks
};

/// This rank's domain: the same owned points, families and ghosts, in the same order, with the serial global
/// indices and input ids, as a serial run's discretize() and build_neighborhood() give, without any rank
/// holding the whole problem:
///  1. rank r makes the sites of its box of the lattice (geometry/discretize.hpp, bisected_site_box: a
///     recursive bisection weighted by the bodies' estimated site counts), plus one reach (δ + r) of planes
///     on every side, and counts the bonds of its box's points; it keeps every r-th point of the point files
///     and meshes (read_file_bodies), weighted by a full family's estimated bond count;
///  2. the serial storage order and generation order are found from the points' sites (lattice) or places
///     in their files (global_order.hpp): the global index and the input id;
///  3. Zoltan partitions these points by bond count; each point moves once, to its owner;
///  4. each owner's bounding box widened by the reach is sent to every rank, which sends back its points in
///     that box: the candidates for ghosts, from which the owned points' families are built.
/// The volume-constraint layers (<body>_constraint) and the meshes' sets are the discretization's mesh sets,
/// by input id, over the rank's points (owned and ghosts). Throws InputError (on every rank) for an empty
/// body or layer, or a file that cannot be read. Collective.
LocalDomain decompose(const Communicator& comm, const Problem& problem, const NeighborhoodOptions& options,
                      PartitionMethod method = PartitionMethod::rcb);

/// For the models that read their partner's bond (history, correspondence weights): fills
/// domain.bonds.reverse — the local bond j → i where j is owned, else a partner-bond slot (fields.hpp) —
/// and returns the exchange that copies the owners' values of bond j → i into the slots of a per-bond
/// array sized num_bonds() + partner_slots. Slots are grouped by owner rank. Collective.
Halo build_partner_bonds(const Communicator& comm, LocalDomain& domain);

}  // namespace peridot
