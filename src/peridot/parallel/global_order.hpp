#pragma once
// The position of every point in an order that no rank sees whole: distributed generation
// (parallel/domain.hpp) numbers the points each rank made by their place among the points of all ranks.
#include <array>
#include <cstdint>
#include <vector>

#include "peridot/parallel/communicator.hpp"

namespace peridot {

using OrderKey = std::array<std::uint64_t, 3>;  ///< compared lexicographically; unique over all ranks

/// For each of this rank's keys, the number of keys of all ranks that are smaller: a sample sort (every
/// rank sends each key to the rank whose range of splitters holds it, which ranks its share and sends the
/// positions back). Memory O(keys per rank + ranks²). Collective.
std::vector<std::uint64_t> global_ranks(const Communicator& comm, const std::vector<OrderKey>& keys);

}  // namespace peridot
