// Discretization and neighbourhood: shapes, lattice fill, jitter, point files, Morton order by block,
// CSR bond lists (symmetric, sorted, the right count), pre-crack filters and partial volumes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <set>

#include <unistd.h>

#include "peridot/geometry/discretize.hpp"
#include "peridot/neighbor/neighborhood.hpp"
#include "support/problems.hpp"

namespace peridot {
namespace {

Shape sphere(Vec3 c, double r) {
  Shape s;
  s.kind = Shape::Kind::sphere;
  s.center = c;
  s.radius = r;
  return s;
}

Shape tube(double inner, double outer, double length) {
  Shape s;
  s.kind = Shape::Kind::tube;
  s.inner_radius = inner;
  s.radius = outer;
  s.length = length;
  return s;
}

Problem single_body(int dimension, Shape shape, double spacing = 1e-3) {
  testing::BlockSetup setup;
  setup.dimension = dimension;
  setup.spacing = spacing;
  Problem p = testing::box_problem(setup);
  p.bodies[0].shape = shape;
  return p;
}

TEST(Shapes, ContainmentOfPrimitivesAndCombinations) {
  const Shape box = testing::box_shape({0, 0, 0}, {1, 1, 1});
  EXPECT_TRUE(box.contains({0.5, 0.5, 0.5}, 3));
  EXPECT_FALSE(box.contains({0.5, 0.5, 1.5}, 3));
  EXPECT_TRUE(box.contains({0.5, 0.5, 1.5}, 2));  // z is ignored in 2D
  const Shape t = tube(0.2, 0.25, 1.0);
  EXPECT_TRUE(t.contains({0.22, 0, 0.5}, 3));
  EXPECT_FALSE(t.contains({0.1, 0, 0.5}, 3));
  EXPECT_FALSE(t.contains({0.22, 0, 1.5}, 3));
  Shape tilted = tube(0, 1, 2);
  tilted.kind = Shape::Kind::cylinder;
  tilted.axis = {1 / std::sqrt(2.0), 1 / std::sqrt(2.0), 0};
  EXPECT_TRUE(tilted.contains({1, 1, 0.5}, 3));
  EXPECT_FALSE(tilted.contains({1, -1, 0}, 3));
  Shape holed;
  holed.kind = Shape::Kind::difference;
  holed.children = {box, sphere({0.5, 0.5, 0.5}, 0.3)};
  EXPECT_FALSE(holed.contains({0.5, 0.5, 0.5}, 3));
  EXPECT_TRUE(holed.contains({0.05, 0.05, 0.05}, 3));
  Shape both;
  both.kind = Shape::Kind::union_of;
  both.children = {sphere({0, 0, 0}, 1), sphere({3, 0, 0}, 1)};
  EXPECT_TRUE(both.contains({3.5, 0, 0}, 3));
  EXPECT_FALSE(both.contains({1.5, 0, 0}, 3));
  const BoundingBox bb = tilted.bounds(3);
  EXPECT_NEAR(bb.hi.x, 2 / std::sqrt(2.0) + 1 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(bb.hi.z, 1.0, 1e-12);
}

TEST(Discretize, LatticeFillApproximatesVolumes) {
  const double dx = 1e-3, r = 10e-3;
  const Discretization s = discretize(single_body(3, sphere({0, 0, 0}, r), dx));
  const double sphere_volume = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  EXPECT_NEAR(s.num_points() * dx * dx * dx, sphere_volume, 0.02 * sphere_volume);
  const Discretization t = discretize(single_body(3, tube(20e-3, 25e-3, 0.1), dx));
  const double tube_volume = std::numbers::pi * (25e-3 * 25e-3 - 20e-3 * 20e-3) * 0.1;
  EXPECT_NEAR(t.num_points() * dx * dx * dx, tube_volume, 0.02 * tube_volume);
  const Discretization disc = discretize(single_body(2, sphere({0, 0, 0}, r), dx));  // a disc in 2D
  EXPECT_NEAR(disc.num_points() * dx * dx, std::numbers::pi * r * r, 0.02 * std::numbers::pi * r * r);
  for (std::size_t i = 0; i < disc.num_points(); ++i) EXPECT_EQ(disc.x(i, 2), 0.0);
}

TEST(Discretize, BoxFillIsExactAndCellCentred) {
  testing::BlockSetup setup;
  setup.cells[0] = 5, setup.cells[1] = 4, setup.cells[2] = 3;
  const Discretization disc = discretize(testing::box_problem(setup));
  EXPECT_EQ(disc.num_points(), 60u);
  double sum = 0;
  for (std::size_t i = 0; i < disc.num_points(); ++i) sum += disc.x(i, 0);
  EXPECT_NEAR(sum / 60, 2.5e-3, 1e-15);
}

TEST(Discretize, JitterIsSeededAndBounded) {
  testing::BlockSetup setup;
  setup.jitter = 0.2;
  Problem p = testing::box_problem(setup);
  const Discretization a = discretize(p), b = discretize(p);
  p.seed = 2;
  const Discretization c = discretize(p);
  bool differs = false;
  for (std::size_t i = 0; i < a.num_points(); ++i)
    for (int d = 0; d < 3; ++d) {
      EXPECT_EQ(a.x(i, d), b.x(i, d));
      differs = differs || a.x(i, d) != c.x(i, d);
      const double cell = std::floor(a.x(i, d) / 1e-3);
      EXPECT_LE(std::abs(a.x(i, d) - (cell + 0.5) * 1e-3), 0.2 * 1e-3 + 1e-15);
    }
  EXPECT_TRUE(differs);
}

TEST(Discretize, BodiesAreContiguousBlocksAndFirstBodyWinsOverlaps) {
  testing::BlockSetup setup;
  Problem p = testing::box_problem(setup);  // 10 × 10 × 10 box
  BodySpec ball = p.bodies[0];
  ball.name = "ball";
  ball.shape = sphere({5e-3, 5e-3, 5e-3}, 3e-3);
  p.bodies.insert(p.bodies.begin(), ball);  // the ball is body 0 and takes its points from the box
  const Discretization disc = discretize(p);
  EXPECT_EQ(disc.num_points(), 1000u);
  const auto ranges = block_ranges(disc);
  ASSERT_EQ(ranges.size(), 2u);
  EXPECT_EQ(ranges[0].begin, 0u);
  EXPECT_EQ(ranges[0].end, ranges[1].begin);
  EXPECT_EQ(ranges[1].end, 1000u);
  EXPECT_GT(ranges[0].end, 50u);
  std::set<std::uint32_t> ids(disc.input_id.begin(), disc.input_id.end());
  EXPECT_EQ(ids.size(), 1000u);
}

TEST(Discretize, ReadsPointFilesWithBlockFilter) {
  const auto path = std::filesystem::temp_directory_path() / ("peridot_points_" + std::to_string(::getpid()) + ".txt");
  std::ofstream(path) << "# x y z volume block\n0 0 0 1e-9 1\n0.001 0 0 1e-9 2\n0.002 0 0 2e-9 1\n";
  testing::BlockSetup setup;
  Problem p = testing::box_problem(setup);
  p.bodies[0].shape.reset();
  p.bodies[0].points_file = path.string();
  p.bodies[0].block_filter = 1;
  const Discretization disc = discretize(p);
  ASSERT_EQ(disc.num_points(), 2u);
  EXPECT_DOUBLE_EQ(disc.volume[0] + disc.volume[1], 3e-9);
  std::ofstream(path) << "0 0 0\n";
  try {
    discretize(p);
    FAIL() << "a short row must be an input error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.diagnostics()[0].pos.line, 1);
    EXPECT_NE(e.diagnostics()[0].message.find("expected 4 or 5 columns"), std::string::npos);
  }
  std::filesystem::remove(path);
}

NeighborhoodOptions options_for(const Problem& p) {
  NeighborhoodOptions o;
  for (const BodySpec& b : p.bodies) o.horizon_of_block.push_back(b.horizon);
  o.precracks = p.precracks;
  o.partial_volume_radius = p.partial_volume != PartialVolumeKind::none ? p.spacing / 2 : 0;
  o.bond_beyond_horizon = p.partial_volume == PartialVolumeKind::extended;
  return o;
}

TEST(Neighborhood, SimpleCubicFamilyHas122BondsAndListsAreSymmetricAndSorted) {
  testing::BlockSetup setup;  // δ = 3.015Δx
  setup.cells[0] = setup.cells[1] = setup.cells[2] = 11;
  const Problem p = testing::box_problem(setup);
  const Discretization disc = discretize(p);
  const BondList bonds = build_neighborhood(disc, options_for(p));
  std::size_t most = 0;
  std::set<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (std::size_t i = 0; i < disc.num_points(); ++i) {
    most = std::max<std::size_t>(most, bonds.offsets[i + 1] - bonds.offsets[i]);
    for (auto b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
      if (b > bonds.offsets[i]) {
        EXPECT_LT(bonds.neighbors[b - 1], bonds.neighbors[b]);
      }
      pairs.insert({static_cast<std::uint32_t>(i), bonds.neighbors[b]});
    }
  }
  // Lattice vectors with |n| ≤ 3.015, n ≠ 0: 122 of them.
  EXPECT_EQ(most, 122u);
  for (auto [i, j] : pairs) EXPECT_TRUE(pairs.count({j, i})) << i << " → " << j << " has no reverse";
}

// Two bodies a kilometre apart: the cell grid keeps only the occupied cells (a dense one over the bounding box
// would need 1e17 cells; it threw bad_alloc), and each body has the bonds it has alone.
TEST(Neighborhood, BodiesFarApartKeepTheirOwnFamilies) {
  testing::BlockSetup setup;
  setup.cells[0] = setup.cells[1] = setup.cells[2] = 7;
  const Problem alone = testing::box_problem(setup);
  Problem apart = alone;
  apart.bodies.push_back(apart.bodies[0]);
  apart.bodies[1].name = "far";
  apart.bodies[1].shape->lo = apart.bodies[1].shape->lo + Vec3{1000, 1000, 1000};
  apart.bodies[1].shape->hi = apart.bodies[1].shape->hi + Vec3{1000, 1000, 1000};
  const Discretization one = discretize(alone), two = discretize(apart);
  const BondList single = build_neighborhood(one, options_for(alone));
  const BondList both = build_neighborhood(two, options_for(apart));
  ASSERT_EQ(two.num_points(), 2 * one.num_points());
  EXPECT_EQ(both.num_bonds(), 2 * single.num_bonds());
  for (std::size_t i = 0; i < two.num_points(); ++i)
    for (auto b = both.offsets[i]; b < both.offsets[i + 1]; ++b) EXPECT_EQ(two.block[both.neighbors[b]], two.block[i]);
}

// δ a whole number of spacings (δ = 3Δx, as Madenci & Oterkus use): the bonds of length exactly δ are in every
// family, whatever the round-off of the coordinates (before the search widened its cutoff by 1e-10, a 2D plate at
// δ = 2Δx had families of 10 to 12 bonds in stripes, and a uniform strain relaxed to a striped strain field).
TEST(Neighborhood, WholeNumberHorizonGivesEveryInteriorPointTheSameFamily) {
  for (int m : {2, 3}) {
    testing::BlockSetup setup;
    setup.dimension = 2;
    setup.cells[0] = 40, setup.cells[1] = 20;
    setup.spacing = 0.0075;  // coordinates (i + ½)·0.0075 are not exact in binary
    setup.horizon_factor = m;
    const Problem p = testing::box_problem(setup);
    const Discretization disc = discretize(p);
    const BondList bonds = build_neighborhood(disc, options_for(p));
    const double delta = m * setup.spacing;
    // Lattice vectors of |n| ≤ m in 2D: 12 for m = 2, 28 for m = 3.
    const std::size_t full = m == 2 ? 12 : 28;
    int interior = 0;
    for (std::size_t i = 0; i < disc.num_points(); ++i) {
      const Vec3 x = disc.x.get(i);
      if (x.x < delta || x.y < delta || x.x > 40 * setup.spacing - delta || x.y > 20 * setup.spacing - delta) continue;
      EXPECT_EQ(bonds.offsets[i + 1] - bonds.offsets[i], full) << "m = " << m << ", point " << i;
      ++interior;
    }
    EXPECT_GT(interior, 100);
  }
}

TEST(Neighborhood, PrecracksRemoveEveryCrossingBond) {
  testing::BlockSetup setup;
  setup.dimension = 2;
  setup.cells[0] = setup.cells[1] = 20;
  Problem p = testing::box_problem(setup);
  PrecrackSpec crack;
  crack.is_segment = true;
  crack.a = {0, 10e-3, 0};
  crack.b = {10e-3, 10e-3, 0};
  p.precracks = {crack};
  const Discretization disc = discretize(p);
  const BondList bonds = build_neighborhood(disc, options_for(p));
  std::size_t crossing_left = 0, crossing_right = 0;
  for (std::size_t i = 0; i < disc.num_points(); ++i)
    for (auto b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
      const Vec3 xi = disc.x.get(i), xj = disc.x.get(bonds.neighbors[b]);
      if ((xi.y - 10e-3) * (xj.y - 10e-3) >= 0) continue;
      const double x_at_crack = xi.x + (xj.x - xi.x) * (10e-3 - xi.y) / (xj.y - xi.y);
      (x_at_crack < 10e-3 ? crossing_left : crossing_right)++;
    }
  EXPECT_EQ(crossing_left, 0u);   // cut by the crack
  EXPECT_GT(crossing_right, 0u);  // beyond its tip the bonds remain

  // 3D: a rectangle in the plane z = 5 mm over x ∈ [0, 5 mm], y ∈ [0, 10 mm].
  PrecrackSpec rect;
  rect.is_segment = false;
  rect.origin = {0, 0, 5e-3};
  rect.edge1 = {5e-3, 0, 0};
  rect.edge2 = {0, 10e-3, 0};
  EXPECT_TRUE(bond_crosses(rect, {2e-3, 3e-3, 4.5e-3}, {3e-3, 3e-3, 5.5e-3}, 3));
  EXPECT_FALSE(bond_crosses(rect, {6e-3, 3e-3, 4.5e-3}, {6e-3, 3e-3, 5.5e-3}, 3));
  EXPECT_FALSE(bond_crosses(rect, {2e-3, 3e-3, 4.5e-3}, {2e-3, 3e-3, 4.9e-3}, 3));
}

TEST(Neighborhood, PartialVolumeFactorIsALinearRamp) {
  EXPECT_EQ(partial_volume_factor(2.0, 3.0, 0.5), 1.0);
  EXPECT_EQ(partial_volume_factor(3.0, 3.0, 0.5), 0.5);
  EXPECT_EQ(partial_volume_factor(3.25, 3.0, 0.5), 0.25);
  EXPECT_EQ(partial_volume_factor(3.6, 3.0, 0.5), 0.0);
  EXPECT_EQ(partial_volume_factor(3.4, 3.0, 0.0), 1.0);
}

}  // namespace
}  // namespace peridot
