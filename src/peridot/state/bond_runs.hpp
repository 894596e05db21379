#pragma once
// What the vectorised bond loops (solvers/internal_force.cpp, correspondence/kinematics.cpp and force.cpp)
// share: a point's run of bonds to its own block, and the per-thread scratch that holds the run's
// neighbours and flags as doubles.
//
// Why the scratch: GCC 12 vectorises a bond loop only when it reads private copies and no byte array.
// Read through a lambda's references or a struct the OpenMP threads share, every pointer is reloaded after
// each store, and the loop stays scalar although -fopt-info reports it vectorised; with the broken flags
// (bytes) in it, GCC either refuses (mask conversions it cannot do for 256-bit vectors) or takes 32 bonds
// per iteration, which leaves a quarter of a 122-bond family to the scalar remainder.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "peridot/state/fields.hpp"

namespace peridot {

/// Point i's run of bonds to its own block, [b_begin, b_end). Neighbours are sorted by global index, and
/// every block is a contiguous global index range, so the bonds to this block form one run between the
/// bonds to lower and to higher blocks. (Found by block, not index: a rank's ghosts sit after its owned
/// points.) Bonds to other blocks (interfaces only) are the callers' general path.
inline void find_same_block_run(const BondList& bonds, const std::vector<std::int32_t>& blocks, std::size_t i,
                                std::uint64_t& b_begin, std::uint64_t& b_end) {
  const std::int32_t block_i = blocks[i];
  b_begin = bonds.offsets[i], b_end = bonds.offsets[i + 1];
  while (b_begin < b_end && blocks[bonds.neighbors[b_begin]] < block_i) ++b_begin;
  while (b_end > b_begin && blocks[bonds.neighbors[b_end - 1]] > block_i) --b_end;
}

/// Loops over a padded run take a multiple of this many bonds: the bonds past the run repeat its last
/// neighbour with weight or intact flag 0, so they add nothing (an empty run has none), and no
/// bond is left to the scalar remainder loop (GCC 12 takes 16 bonds per iteration at 512 bits; a 122-bond
/// family would leave 10 to it, a third of the time). Loops that read per-bond arrays at the bond index
/// are not padded.
constexpr std::uint64_t run_padding = 16;
inline std::uint64_t padded_length(std::uint64_t n) { return (n + run_padding - 1) / run_padding * run_padding; }

/// One thread's copy of one run: neighbours, intact flags (1 intact, 0 broken) or intact × a per-bond
/// weight, and breaking flags (1 where the bond breaks now), padded; it grows to the longest run.
struct RunScratch {
  std::vector<std::uint32_t> neighbor;
  std::vector<double> intact, breaking;

  /// Copies the neighbours of the bonds [b_begin, b_end) and their intact flags, or with `weight` their
  /// weights: intact[k] = weight[b] for an intact bond b, 0 for a broken one.
  void load(const std::uint32_t* neighbors, const std::uint8_t* broken, std::uint64_t b_begin, std::uint64_t b_end,
            const double* weight = nullptr) {
    const std::uint64_t n = b_end - b_begin;
    if (neighbor.size() < padded_length(n))
      neighbor.resize(padded_length(n)), intact.resize(padded_length(n)), breaking.resize(padded_length(n));
    std::copy(neighbors + b_begin, neighbors + b_end, neighbor.begin());
    std::uint32_t* to = neighbor.data();  // local pointers: through `this` they are reloaded after each store
    double* flags = intact.data();
    const std::uint8_t* from = broken + b_begin;
    if (weight)
      for (std::uint64_t k = 0; k < n; ++k) flags[k] = from[k] ? 0.0 : weight[b_begin + k];
    else
      for (std::uint64_t k = 0; k < n; ++k) flags[k] = 1 - from[k];  // flags are 0 or 1; arithmetic vectorises
    for (std::uint64_t k = n; k < padded_length(n); ++k) to[k] = to[n - 1], flags[k] = 0;
  }
  /// Sets the broken flag of every bond of [b_begin, b_end) whose breaking flag is set.
  void store(std::uint8_t* broken, std::uint64_t b_begin, std::uint64_t b_end) const {
    for (std::uint64_t b = b_begin; b < b_end; ++b)
      if (breaking[b - b_begin] != 0) broken[b] = 1;
  }
};

/// Where a weighted loop (the correspondence kinematics and force) reads the bonds of a run. With AVX-512
/// the loops read the bond list in place: the run's neighbours, broken flags and weights, `count` = the
/// run's length, the last group masked. The other targets read this thread's RunScratch: neighbours and
/// weights (0 where broken), `count` padded to whole groups, `broken` unused.
struct WeightedRun {
  const std::uint32_t* neighbor = nullptr;
  const std::uint8_t* broken = nullptr;
  const double* weight = nullptr;
  std::uint64_t count = 0;
};

/// The WeightedRun of the bonds [b_begin, b_end) of `bonds` with the per-bond weights `weight`: in place
/// (InPlace, the AVX-512 loops) or copied to `scratch`.
template <bool InPlace>
WeightedRun weighted_run(RunScratch& scratch, const BondList& bonds, const double* weight, std::uint64_t b_begin,
                         std::uint64_t b_end) {
  if constexpr (InPlace) {
    (void)scratch;
    return {bonds.neighbors.data() + b_begin, bonds.broken.data() + b_begin, weight + b_begin, b_end - b_begin};
  } else {
    scratch.load(bonds.neighbors.data(), bonds.broken.data(), b_begin, b_end, weight);
    return {scratch.neighbor.data(), nullptr, scratch.intact.data(), padded_length(b_end - b_begin)};
  }
}

}  // namespace peridot
