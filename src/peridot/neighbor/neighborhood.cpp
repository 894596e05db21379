#include "peridot/neighbor/neighborhood.hpp"

#include "peridot/core/error.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <utility>

namespace peridot {

namespace {

double orientation(Vec3 a, Vec3 b, Vec3 c) { return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x); }

bool segments_cross(Vec3 p, Vec3 q, Vec3 a, Vec3 b) {
  double d1 = orientation(a, b, p), d2 = orientation(a, b, q);
  double d3 = orientation(p, q, a), d4 = orientation(p, q, b);
  return ((d1 < 0 && d2 > 0) || (d1 > 0 && d2 < 0)) && ((d3 <= 0 && d4 >= 0) || (d3 >= 0 && d4 <= 0));
}

bool crosses_rectangle(Vec3 p, Vec3 q, const PrecrackSpec& c) {
  Vec3 n = cross(c.edge1, c.edge2);
  double dp = dot(n, p - c.origin), dq = dot(n, q - c.origin);
  if (!((dp < 0 && dq > 0) || (dp > 0 && dq < 0))) return false;
  Vec3 hit = p + (dp / (dp - dq)) * (q - p);
  Vec3 r = hit - c.origin;
  // Solve r = s·e1 + t·e2 in the plane through the 2×2 Gram system.
  double a11 = dot(c.edge1, c.edge1), a12 = dot(c.edge1, c.edge2), a22 = dot(c.edge2, c.edge2);
  double b1 = dot(r, c.edge1), b2 = dot(r, c.edge2);
  double det = a11 * a22 - a12 * a12;
  double s = (b1 * a22 - b2 * a12) / det, t = (a11 * b2 - a12 * b1) / det;
  return s >= 0 && s <= 1 && t >= 0 && t <= 1;
}

/// Points binned in cubic cells. Dense (a CSR over every cell of the bounding box) unless the box holds far
/// more cells than points (bodies far apart): then only the occupied cells, sorted, found by binary search.
struct CellGrid {
  using Cell = std::array<long, 3>;  // (k, j, i): sorted like the dense index
  Vec3 lo;
  double size = 1;
  long n[3] = {1, 1, 1};
  bool dense = true;
  std::vector<std::uint64_t> start;   // CSR over cells (dense) or over `occupied` (sparse)
  std::vector<Cell> occupied;         // sparse only
  std::vector<std::uint32_t> points;  // point indices, by cell, increasing within a cell

  long coord(double x, int d) const {
    return std::clamp(static_cast<long>(std::min((x - lo[d]) / size, 0x1p50)), 0L, n[d] - 1);
  }
  long index(long i, long j, long k) const { return (k * n[1] + j) * n[0] + i; }
  /// [begin, end) in `points` of cell (i, j, k).
  std::pair<std::uint64_t, std::uint64_t> range(long i, long j, long k) const {
    if (dense) {
      const long cell = index(i, j, k);
      return {start[cell], start[cell + 1]};
    }
    const Cell key{k, j, i};
    const auto it = std::lower_bound(occupied.begin(), occupied.end(), key);
    if (it == occupied.end() || *it != key) return {0, 0};
    const std::size_t c = static_cast<std::size_t>(it - occupied.begin());
    return {start[c], start[c + 1]};
  }
};

CellGrid bin_points(const Discretization& disc, double cell_size) {
  CellGrid grid;
  const std::size_t count = disc.num_points();
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (std::size_t i = 0; i < count; ++i)
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], disc.x(i, d));
      hi[d] = std::max(hi[d], disc.x(i, d));
    }
  grid.lo = lo;
  grid.size = cell_size;
  double cells_in_box = 1;
  for (int d = 0; d < 3; ++d) {
    const double cells = std::min((hi[d] - lo[d]) / cell_size, 0x1p50) + 1;
    grid.n[d] = std::max(1L, static_cast<long>(cells));
    cells_in_box *= static_cast<double>(grid.n[d]);
  }
  if (cells_in_box > 8.0 * static_cast<double>(count) + 1024) {
    grid.dense = false;
    std::vector<CellGrid::Cell> cell(count);
    for (std::size_t i = 0; i < count; ++i)
      cell[i] = {grid.coord(disc.x(i, 2), 2), grid.coord(disc.x(i, 1), 1), grid.coord(disc.x(i, 0), 0)};
    grid.points.resize(count);
    std::iota(grid.points.begin(), grid.points.end(), 0u);
    std::stable_sort(grid.points.begin(), grid.points.end(), [&](std::uint32_t a, std::uint32_t b) { return cell[a] < cell[b]; });
    for (std::size_t s = 0; s < count; ++s)
      if (s == 0 || cell[grid.points[s]] != grid.occupied.back()) {
        grid.occupied.push_back(cell[grid.points[s]]);
        grid.start.push_back(s);
      }
    grid.start.push_back(count);
    return grid;
  }
  const std::size_t cells = static_cast<std::size_t>(grid.n[0] * grid.n[1] * grid.n[2]);
  std::vector<std::uint64_t> cell_of(count);
  grid.start.assign(cells + 1, 0);
  for (std::size_t i = 0; i < count; ++i) {
    cell_of[i] = grid.index(grid.coord(disc.x(i, 0), 0), grid.coord(disc.x(i, 1), 1), grid.coord(disc.x(i, 2), 2));
    ++grid.start[cell_of[i] + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) grid.start[c + 1] += grid.start[c];
  grid.points.resize(count);
  std::vector<std::uint64_t> fill(grid.start.begin(), grid.start.end() - 1);
  for (std::size_t i = 0; i < count; ++i) grid.points[fill[cell_of[i]]++] = static_cast<std::uint32_t>(i);
  return grid;
}

}  // namespace

bool bond_crosses(const PrecrackSpec& crack, Vec3 p, Vec3 q, int dimension) {
  if (crack.is_point) return dimension == 1 && (p.x - crack.at) * (q.x - crack.at) < 0;
  if (crack.is_segment) return dimension == 2 && segments_cross(p, q, crack.a, crack.b);
  return dimension == 3 && crosses_rectangle(p, q, crack);
}

namespace {

/// The neighbour search: a cell list of every point, and the bonds of one point visited in a fixed order.
class NeighborSearch {
 public:
  NeighborSearch(const Discretization& disc, const NeighborhoodOptions& options) : disc_(disc), options_(options) {
    const double max_horizon = *std::max_element(options.horizon_of_block.begin(), options.horizon_of_block.end());
    beyond_ = options.bond_beyond_horizon ? options.partial_volume_radius : 0.0;
    // Cells a little larger than the widened cutoff below, so that every bond it admits is in the 3×3(×3) block.
    grid_ = bin_points(disc, (max_horizon + beyond_) * (1 + 4 * cutoff_tolerance));
  }

  /// A bond of length δ within this relative round-off is in the family. Without it, a horizon that is a
  /// whole number of spacings (δ = 3Δx, as in many papers) keeps or drops the bonds of length exactly δ by the
  /// round-off of each point's coordinates, and the families differ from point to point (a plate under uniform
  /// strain then relaxes to a striped strain field).
  static constexpr double cutoff_tolerance = 1e-10;

  /// Calls visit(j) for every neighbour j of point i (unsorted).
  template <class Visit>
  void for_each_neighbor(std::size_t i, Visit&& visit) const {
    const Vec3 xi = disc_.x.get(i);
    const double horizon_i = options_.horizon_of_block[disc_.block[i]];
    long c[3];
    for (int d = 0; d < 3; ++d) c[d] = grid_.coord(xi[d], d);
    for (long k = std::max(0L, c[2] - 1); k <= std::min(grid_.n[2] - 1, c[2] + 1); ++k)
      for (long j = std::max(0L, c[1] - 1); j <= std::min(grid_.n[1] - 1, c[1] + 1); ++j)
        for (long l = std::max(0L, c[0] - 1); l <= std::min(grid_.n[0] - 1, c[0] + 1); ++l) {
          const auto [begin, end] = grid_.range(l, j, k);
          for (std::uint64_t s = begin; s < end; ++s) {
            const std::uint32_t other = grid_.points[s];
            if (other == i) continue;
            const Vec3 xj = disc_.x.get(other);
            const double horizon = std::max(horizon_i, options_.horizon_of_block[disc_.block[other]]);
            const double cutoff = (horizon + beyond_) * (1 + cutoff_tolerance);
            const Vec3 bond = xj - xi;
            if (dot(bond, bond) > cutoff * cutoff) continue;
            if (beyond_ > 0 && partial_volume_factor(norm(bond), horizon, options_.partial_volume_radius) <= 0) continue;
            bool cut = false;
            for (const PrecrackSpec& crack : options_.precracks) cut = cut || bond_crosses(crack, xi, xj, disc_.dimension);
            if (!cut) visit(other);
          }
        }
  }

  std::uint64_t count(std::size_t i) const {
    std::uint64_t n = 0;
    for_each_neighbor(i, [&](std::uint32_t) { ++n; });
    return n;
  }

 private:
  const Discretization& disc_;
  const NeighborhoodOptions& options_;
  double beyond_ = 0;
  CellGrid grid_;
};

/// CSR of the families of `count` points, the k-th being point_of(k); neighbours sorted.
template <class PointOf>
BondList build_families(const NeighborSearch& search, std::size_t count, PointOf&& point_of) {
  BondList bonds;
  bonds.offsets.assign(count + 1, 0);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t k = 0; k < count; ++k) bonds.offsets[k + 1] = search.count(point_of(k));
  for (std::size_t k = 0; k < count; ++k) bonds.offsets[k + 1] += bonds.offsets[k];
  bonds.neighbors.resize(bonds.offsets[count]);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t k = 0; k < count; ++k) {
    std::uint32_t* out = bonds.neighbors.data() + bonds.offsets[k];
    std::size_t n = 0;
    search.for_each_neighbor(point_of(k), [&](std::uint32_t j) { out[n++] = j; });
    std::sort(out, out + n);
  }
  bonds.broken.assign(bonds.neighbors.size(), 0);
  return bonds;
}

}  // namespace

BondList build_neighborhood(const Discretization& disc, const NeighborhoodOptions& options) {
  const NeighborSearch search(disc, options);
  return build_families(search, disc.num_points(), [](std::size_t k) { return k; });
}

BondList build_neighborhood(const Discretization& disc, const NeighborhoodOptions& options,
                            const std::vector<std::uint32_t>& of) {
  const NeighborSearch search(disc, options);
  return build_families(search, of.size(), [&](std::size_t k) { return static_cast<std::size_t>(of[k]); });
}

std::vector<std::uint64_t> count_bonds(const Discretization& disc, const NeighborhoodOptions& options,
                                       std::size_t begin, std::size_t end) {
  const NeighborSearch search(disc, options);
  std::vector<std::uint64_t> counts(end - begin);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = begin; i < end; ++i) counts[i - begin] = search.count(i);
  return counts;
}

void build_reverse_bonds(BondList& bonds) {
  const std::size_t n = bonds.offsets.size() - 1;
  PERIDOT_REQUIRE(bonds.num_bonds() <= UINT32_MAX, "more than 2^32 bonds: reverse bond indices need 64 bits");
  bonds.reverse.resize(bonds.num_bonds());
  const std::uint32_t* neighbors = bonds.neighbors.data();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
      const std::uint32_t j = neighbors[b];
      const std::uint32_t* first = neighbors + bonds.offsets[j];
      const std::uint32_t* last = neighbors + bonds.offsets[j + 1];
      const std::uint32_t* found = std::lower_bound(first, last, static_cast<std::uint32_t>(i));
      PERIDOT_REQUIRE(found != last && *found == i, "bond families are not symmetric");
      bonds.reverse[b] = static_cast<std::uint32_t>(bonds.offsets[j] + (found - first));
    }
}

}  // namespace peridot
