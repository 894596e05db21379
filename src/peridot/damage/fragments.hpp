#pragma once
// Fragments: the connected sets of points through intact bonds (a point whose bonds are all broken is a
// fragment of its own). Found with a union–find over the bonds in index order; every fragment is named by
// the smallest input id (order of generation, 0-based) among its points, so labels do not depend on the
// thread count, the space-filling-curve order or when they are computed.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "peridot/state/fields.hpp"

namespace peridot {

/// Writes each point's fragment label (the smallest input id of its fragment) and returns the number of
/// fragments. `input_id` may be empty: point indices are used then.
std::size_t label_fragments(const BondList& bonds, const std::vector<std::uint32_t>& input_id,
                            std::vector<double>& label);

/// Distributed labelling, to the same labels: `bonds` are one rank's (families of its `owned` points, then
/// ghosts without families; input_id per local point). Each rank labels its own points and ghosts, then
/// rounds of exchange(label) (ghost entries refreshed from their owners) and any(changed) (collective or)
/// carry each fragment's smallest id across rank boundaries until no rank lowers a label.
void label_fragments(const BondList& bonds, const std::vector<std::uint32_t>& input_id, std::vector<double>& label,
                     std::size_t owned, const std::function<void(std::vector<double>&)>& exchange,
                     const std::function<bool(bool)>& any);

/// Sizes (point counts) of the fragments, largest first.
std::vector<std::size_t> fragment_sizes(const std::vector<double>& label);

}  // namespace peridot
