// The boxes of the lattice that ranks make their points in (geometry/discretize.hpp): the recursive bisection
// tiles the lattice extent, balances the bodies' sites, and the windows together make exactly the points of
// discretize(), bit for bit. The ranks' shares of point files and meshes (read_file_bodies) likewise.
#include "peridot/geometry/discretize.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <tuple>
#include <vector>

#include "peridot/deck/deck.hpp"
#include "support/scratch_dir.hpp"

namespace {

using peridot::Problem;
using peridot::SiteBox;

/// An L of two boxes (one with a volume-constraint layer), jittered, in 3D.
Problem l_shape() {
  return peridot::parse_deck(R"(
discretization: {dimension: 3, spacing: 1 mm, horizon_factor: 3.015, jitter: 0.2, seed: 7}
materials:
  steel: {model: lps, density: 7800, youngs_modulus: 200 GPa, poisson_ratio: 0.3}
bodies:
  long: {material: steel, shape: {box: {min: [0, 0, 0], max: [40 mm, 6 mm, 6 mm]}}}
  tall: {material: steel, shape: {box: {min: [0, 6 mm, 0], max: [6 mm, 30 mm, 6 mm]}}, volume_constraint: 2 mm}
solver: {num_steps: 1}
)", "l.yaml", ".");
}

}  // namespace

TEST(LatticeWindows, BisectedBoxesTileTheExtentAndTogetherMakeDiscretizesPoints) {
  const Problem problem = l_shape();
  const peridot::Discretization whole = peridot::discretize(problem);
  // Every point of the whole problem by (block, x bits).
  std::map<std::tuple<int, double, double, double>, int> expected;
  for (std::size_t i = 0; i < whole.num_points(); ++i) ++expected[{whole.block[i], whole.x(i, 0), whole.x(i, 1), whole.x(i, 2)}];
  const peridot::LatticeExtent extent = peridot::lattice_extent(problem);
  for (int ranks : {1, 2, 3, 4, 5, 7, 8}) {
    std::map<std::tuple<int, double, double, double>, int> made;
    long sites = 0;
    std::vector<SiteBox> boxes;
    std::size_t largest = 0;
    for (int r = 0; r < ranks; ++r) {
      const SiteBox box = peridot::bisected_site_box(problem, r, ranks);
      long volume = 1;
      for (int d = 0; d < 3; ++d) {
        EXPECT_GE(box.lo[d], extent.lo[d]);
        EXPECT_LE(box.hi[d], extent.hi[d] + 1);
        volume *= std::max(0L, box.hi[d] - box.lo[d]);
      }
      sites += volume;
      for (const SiteBox& other : boxes) {  // disjoint
        bool overlap = true;
        for (int d = 0; d < 3; ++d) overlap = overlap && std::max(box.lo[d], other.lo[d]) < std::min(box.hi[d], other.hi[d]);
        EXPECT_FALSE(overlap) << ranks << " ranks";
      }
      boxes.push_back(box);
      const peridot::LatticePoints points = peridot::discretize_window(problem, box);
      largest = std::max(largest, points.disc.num_points());
      for (std::size_t i = 0; i < points.disc.num_points(); ++i)
        ++made[{points.disc.block[i], points.disc.x(i, 0), points.disc.x(i, 1), points.disc.x(i, 2)}];
    }
    EXPECT_EQ(sites, extent.count(0) * extent.count(1) * extent.count(2)) << ranks << " ranks: the boxes tile the extent";
    EXPECT_EQ(made, expected) << ranks << " ranks: the windows make discretize's points, each once";
    // Balanced by the bodies' estimated sites, far better than equal slabs of planes along the longest axis
    // (the first cut, before Zoltan rebalances): the largest box's points over the mean.
    std::size_t largest_slab = 0;
    for (int r = 0; r < ranks; ++r) {
      SiteBox slab;
      for (int d = 0; d < 3; ++d) slab.lo[d] = extent.lo[d], slab.hi[d] = extent.hi[d] + 1;
      slab.lo[0] = extent.lo[0] + extent.count(0) * r / ranks;
      slab.hi[0] = extent.lo[0] + extent.count(0) * (r + 1) / ranks;
      largest_slab = std::max(largest_slab, peridot::discretize_window(problem, slab).disc.num_points());
    }
    const double mean = static_cast<double>(whole.num_points()) / ranks;
    std::printf("%d ranks: largest box %.2f, largest slab %.2f of the mean\n", ranks, largest / mean, largest_slab / mean);
    EXPECT_LE(static_cast<double>(largest), 1.7 * mean) << ranks << " ranks";
    if (ranks > 1) {
      EXPECT_LT(largest, largest_slab) << ranks << " ranks";
    }
  }
}

TEST(LatticeWindows, FileSharesTogetherAreDiscretizesPointsWithTheirPlaces) {
  // A point-file body (block filter), a lattice body and a mesh body with a node set, in 2D.
  const std::filesystem::path dir = peridot::testing::scratch_dir();
  {
    std::ofstream points(dir / "points.txt");
    for (int k = 0; k < 23; ++k) points << 0.0005 + 0.001 * (k % 5) << ' ' << 0.0005 + 0.001 * (k / 5) << " 2e-9 " << (k % 4 == 3 ? 2 : 1) << '\n';
    std::ofstream mesh(dir / "plate.inp");
    mesh << "*NODE\n";
    int id = 1;
    for (int j = 0; j <= 3; ++j)
      for (int i = 0; i <= 4; ++i) mesh << id++ << ", " << 10 + i << ", " << j << ", 0\n";
    mesh << "*ELEMENT, TYPE=CPS4\n";
    id = 1;
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 4; ++i) {
        const int a = 1 + i + 5 * j;
        mesh << id++ << ", " << a << ", " << a + 1 << ", " << a + 6 << ", " << a + 5 << "\n";
      }
    mesh << "*NSET, NSET=left\n1, 6, 11, 16\n";
  }
  const Problem problem = peridot::parse_deck(R"(
discretization: {dimension: 2, plane: stress, thickness: 2 mm, spacing: 1 mm, horizon_factor: 3.015}
materials:
  steel: {model: lps, density: 7800, youngs_modulus: 200 GPa, poisson_ratio: 0.3}
bodies:
  read: {material: steel, points_file: points.txt, block: 1}
  made: {material: steel, shape: {box: {min: [0, 6 mm], max: [8 mm, 9 mm]}}}
  meshed: {material: steel, mesh: {file: plate.inp, scale: 1e-3}}
solver: {num_steps: 1}
)", (dir / "deck.yaml").string(), dir.string());
  const peridot::Discretization whole = peridot::discretize(problem);
  // Each file body's points by place in the body (input id − the body's first input id).
  std::vector<std::uint32_t> first(problem.bodies.size(), UINT32_MAX);
  for (std::size_t i = 0; i < whole.num_points(); ++i)
    first[static_cast<std::size_t>(whole.block[i])] = std::min(first[static_cast<std::size_t>(whole.block[i])], whole.input_id[i]);
  std::map<std::tuple<int, std::uint64_t>, std::tuple<double, double, double>> expected;
  for (std::size_t i = 0; i < whole.num_points(); ++i)
    if (whole.block[i] != 1) expected[{whole.block[i], whole.input_id[i] - first[static_cast<std::size_t>(whole.block[i])]}] = {whole.x(i, 0), whole.x(i, 1), whole.volume[i]};
  ASSERT_EQ(expected.size(), 18u + 12u);  // 23 lines, 5 of block 2; 12 quadrilaterals
  for (int ranks : {1, 2, 3, 4}) {
    std::map<std::tuple<int, std::uint64_t>, std::tuple<double, double, double>> kept;
    for (int r = 0; r < ranks; ++r) {
      const peridot::FilePoints files = peridot::read_file_bodies(problem, r, ranks);
      EXPECT_EQ(files.body_points, (std::vector<std::uint64_t>{18, 0, 12}));
      for (std::size_t k = 0; k < files.disc.num_points(); ++k) {
        EXPECT_EQ(files.place[k] % static_cast<std::uint64_t>(ranks), static_cast<std::uint64_t>(r));
        const bool fresh = kept.emplace(std::tuple{files.disc.block[k], files.place[k]},
                                        std::tuple{files.disc.x(k, 0), files.disc.x(k, 1), files.disc.volume[k]}).second;
        EXPECT_TRUE(fresh) << "a point kept by two ranks";
      }
      // The mesh's node set by place, whole on every rank: the serial set less the body's first input id.
      ASSERT_EQ(files.sets.size(), 1u);
      std::vector<std::uint32_t> serial;
      ASSERT_EQ(whole.mesh_sets.size(), 1u);
      EXPECT_EQ(files.sets[0].name, whole.mesh_sets[0].name);
      EXPECT_EQ(files.sets[0].block, 2);
      for (std::uint32_t id : whole.mesh_sets[0].input_ids) serial.push_back(id - first[2]);
      EXPECT_EQ(files.sets[0].input_ids, serial);
      EXPECT_EQ(serial.size(), 3u);  // the elements of the column at x = 10 mm
    }
    EXPECT_EQ(kept, expected) << ranks << " ranks: the shares are discretize's file points, each once";
  }
}
