#pragma once
// Bond lists: every pair of points closer than the horizon, found with a cell list, stored in CSR and
// sorted by neighbour index; bonds crossing a pre-crack are left out.
#include <vector>

#include "peridot/deck/problem.hpp"
#include "peridot/state/fields.hpp"

namespace peridot {

struct NeighborhoodOptions {
  std::vector<double> horizon_of_block;  ///< δ per block (m); a pair bonds within max(δ_i, δ_j)
  /// With partial volumes (r = ½Δx > 0) the neighbour volume is scaled by partial_volume_factor(), and
  /// with bond_beyond_horizon the cells centred in (δ, δ + r) are bonded too.
  double partial_volume_radius = 0;
  bool bond_beyond_horizon = false;
  std::vector<PrecrackSpec> precracks;
};

BondList build_neighborhood(const Discretization& disc, const NeighborhoodOptions& options);
/// The families of the points `of` only (any order): CSR over `of`, the k-th family that of point of[k],
/// neighbours (indices into disc) sorted; each family is exactly the one the full build gives that point.
BondList build_neighborhood(const Discretization& disc, const NeighborhoodOptions& options,
                            const std::vector<std::uint32_t>& of);
/// Bond count of every point of [begin, end), without storing a bond.
std::vector<std::uint64_t> count_bonds(const Discretization& disc, const NeighborhoodOptions& options,
                                       std::size_t begin, std::size_t end);

/// Fills bonds.reverse: for bond i → j the index of bond j → i (families are symmetric and sorted, so a
/// binary search in j's list finds it). 4 bytes per bond; only models with per-bond history need it.
void build_reverse_bonds(BondList& bonds);

/// Fraction of a neighbour cell of half-width r at distance ξ inside a horizon δ: a linear ramp, 1 up to
/// δ − r, ½ on the horizon, 0 at δ + r. r = 0 means no correction.
inline double partial_volume_factor(double xi, double horizon, double r) {
  if (r <= 0 || xi <= horizon - r) return 1.0;
  if (xi >= horizon + r) return 0.0;
  return (horizon + r - xi) * (0.5 / r);  // 0.5/r is loop-invariant: a bond loop multiplies
}

/// True when the segment p → q crosses the pre-crack (2D segment or 3D rectangle).
bool bond_crosses(const PrecrackSpec& crack, Vec3 p, Vec3 q, int dimension);

}  // namespace peridot
