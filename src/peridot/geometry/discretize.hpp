#pragma once
// Turns the bodies of a deck into points: shapes filled on a cell-centred lattice (optionally jittered),
// point files or meshes (geometry/mesh.hpp). Points are then ordered by block, and within a block along a Morton (Z-order) curve,
// so that each block is one contiguous range and neighbours sit close in memory.
#include <cstdint>
#include <vector>

#include "peridot/deck/problem.hpp"
#include "peridot/state/fields.hpp"

namespace peridot {

struct BlockRange {
  std::size_t begin = 0, end = 0;  ///< points [begin, end) belong to this block
};

/// Throws InputError (at the body's deck position) for an unreadable point file or a body with no point.
Discretization discretize(const Problem& problem);

/// [begin, end) of every block among the first `count` points (all by default); valid because discretize()
/// sorts points by block (and a rank's owned points keep that order, parallel/domain.hpp).
std::vector<BlockRange> block_ranges(const Discretization& disc, std::size_t count = SIZE_MAX);

/// Deterministic uniform deviate in [0, 1) from a 64-bit state (splitmix64), identical on every platform.
double uniform01(std::uint64_t& state);

}  // namespace peridot
