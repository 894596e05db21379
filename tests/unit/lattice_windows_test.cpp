// The boxes of the lattice that ranks make their points in (geometry/discretize.hpp): the recursive bisection
// tiles the lattice extent, balances the bodies' sites, and the windows together make exactly the points of
// discretize(), bit for bit.
#include "peridot/geometry/discretize.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <tuple>
#include <vector>

#include "peridot/deck/deck.hpp"

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
  ASSERT_TRUE(peridot::generated_by_window(problem));
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
    if (ranks > 1) EXPECT_LT(largest, largest_slab) << ranks << " ranks";
  }
}
