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

// -- distributed generation (parallel/domain.hpp) ------------------------------------------------------------
// A distributed run is generated piece by piece: each rank makes the sites of its box of the lattice only
// (bisected_site_box), and keeps a share of the points of point files and meshes (read_file_bodies). What the whole-problem order needs of a point is then
// derived from its site alone, so that every rank count gives the serial order and ids:
//   generation order (the input id's order): block, then shape points before the body's volume-constraint
//       layer, then the site's linear index (k, j, i raster: the order fill_shape visits them in);
//   storage order (discretize's): block, then the Morton code of the point's cell (morton_key, from the
//       lowest coordinate and the smallest spacing of all points), then generation order.

/// Every lattice site any body may make (its bounding box widened by its volume-constraint layer), and the
/// linear index of a site within it.
struct LatticeExtent {
  long lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};  ///< inclusive
  long count(int d) const { return hi[d] - lo[d] + 1; }
  std::uint64_t site(long i, long j, long k) const {
    return (static_cast<std::uint64_t>(k - lo[2]) * static_cast<std::uint64_t>(count(1)) + static_cast<std::uint64_t>(j - lo[1])) *
               static_cast<std::uint64_t>(count(0)) + static_cast<std::uint64_t>(i - lo[0]);
  }
};

LatticeExtent lattice_extent(const Problem& problem);

struct LatticePoints {
  Discretization disc;               ///< x, volume, block of the window's points (no input id, no mesh set)
  std::vector<std::uint64_t> site;   ///< each point's LatticeExtent::site
  std::vector<std::uint8_t> layer;   ///< 1 for a volume-constraint layer's point
};
/// A box of lattice sites, half-open along each axis: lo[d] ≤ index < hi[d].
struct SiteBox {
  long lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
  bool holds(long i, long j, long k) const {
    return i >= lo[0] && i < hi[0] && j >= lo[1] && j < hi[1] && k >= lo[2] && k < hi[2];
  }
};

/// Rank `rank`'s box of a recursive coordinate bisection of the lattice extent into `ranks` boxes that tile it:
/// each box is cut across its longest axis where the bodies' estimated site counts (each body's sites taken
/// as spread evenly over its bounding box, layer included) split in proportion to the ranks on either side.
SiteBox bisected_site_box(const Problem& problem, int rank, int ranks);

/// The points of the sites inside `window` of the bodies that are shapes on the lattice, in generation order:
/// the same points (same bits) discretize() makes there. Checks the problem's size as discretize() does; an
/// empty body is the caller's to find (it needs every window).
LatticePoints discretize_window(const Problem& problem, const SiteBox& window);

/// The points of the bodies read from point files or meshes that rank `rank` of `ranks` keeps: a body's k-th
/// point (file order, its place) when k mod ranks = rank, so that no rank holds a whole file's points (a rank
/// still parses every line, and a mesh is read whole during the call). The generation order of such a body is
/// its file order; Zoltan then moves each point to its owner, wherever it was read.
struct FilePoints {
  Discretization disc;                        ///< x, volume, block of the points kept (body order, then place)
  std::vector<std::uint64_t> place;           ///< each kept point's place in its body
  std::vector<std::uint64_t> body_points;     ///< per block: the points its file gives (0 for a shape body)
  std::vector<Discretization::MeshSet> sets;  ///< the meshes' sets, input_ids the places of all their points
};
FilePoints read_file_bodies(const Problem& problem, int rank, int ranks);

/// The storage-order key of a point: the Morton code of its cell on a grid of `spacing` from `lo`.
std::uint64_t morton_key(Vec3 x, Vec3 lo, double spacing, int dimension);
/// The lattice spacing a point of volume V stands for (the side of its cell).
double cell_side(double volume, const Problem& problem);

/// Deterministic uniform deviate in [0, 1) from a 64-bit state (splitmix64), identical on every platform.
double uniform01(std::uint64_t& state);

}  // namespace peridot
