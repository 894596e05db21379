#pragma once
// The candidates of a distributed contact search: the points of other ranks that a rank's own points may
// touch. Points move far from where the partition put them (fragments fly, bodies collide), so the halo of
// the bonds is no guide; what counts is where the points are now. Each rank's box around its owned
// deformed positions, widened by the search reach, goes to every rank (6 numbers per rank), and every rank
// sends back its owned points inside that box. Nothing of the whole problem is held anywhere.
#include "peridot/contact/short_range.hpp"
#include "peridot/parallel/communicator.hpp"

namespace peridot {

/// `mine`: this rank's owned points (every owner field this rank). Returns them followed by the other ranks'
/// owned points whose deformed position lies within `reach` of the box around `mine`'s deformed positions,
/// in increasing global index. Collective.
ContactCandidates gather_contact_candidates(const Communicator& comm, ContactCandidates mine, double reach);

}  // namespace peridot
