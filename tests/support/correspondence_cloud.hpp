#pragma once
// A 3D box of points with its bonds and correspondence context, built with the library's own lattice
// generator (geometry/discretize) and neighbour search (neighbor/neighborhood), for the correspondence
// tests. The context points into the cloud, so the cloud lives behind a unique_ptr and never moves.
#include <memory>

#include "peridot/correspondence/kinematics.hpp"
#include "peridot/geometry/discretize.hpp"
#include "peridot/neighbor/neighborhood.hpp"
#include "support/problems.hpp"

namespace peridot::testing {

struct CorrespondenceCloud {
  Discretization disc;
  BondList bonds;
  correspondence::CorrespondenceContext ctx;
  double spacing = 0, horizon = 0;
};

struct CloudSetup {
  int cells[3] = {7, 7, 7};
  double spacing = 1e-3;  ///< m
  double horizon_factor = 3.015;
  double jitter = 0;  ///< fraction of the spacing
  bool partial_volume = false;
  InfluenceKind influence = InfluenceKind::constant;
};

inline std::unique_ptr<CorrespondenceCloud> make_cloud(const CloudSetup& s) {
  BlockSetup b;
  b.dimension = 3;
  b.cells[0] = s.cells[0];
  b.cells[1] = s.cells[1];
  b.cells[2] = s.cells[2];
  b.spacing = s.spacing;
  b.horizon_factor = s.horizon_factor;
  b.jitter = s.jitter;
  b.partial_volume = s.partial_volume;
  b.influence = s.influence;
  const Problem problem = box_problem(b);
  auto cloud = std::make_unique<CorrespondenceCloud>();
  cloud->spacing = s.spacing;
  cloud->horizon = s.horizon_factor * s.spacing;
  cloud->disc = discretize(problem);
  NeighborhoodOptions options;
  options.horizon_of_block = {cloud->horizon};
  options.partial_volume_radius = s.partial_volume ? 0.5 * s.spacing : 0.0;
  options.bond_beyond_horizon = s.partial_volume;
  cloud->bonds = build_neighborhood(cloud->disc, options);
  build_reverse_bonds(cloud->bonds);
  cloud->ctx = correspondence::make_correspondence_context(
      cloud->disc, cloud->bonds, {correspondence::BlockGeometry{cloud->horizon, s.influence}},
      options.partial_volume_radius);
  return cloud;
}

/// Distance from point i to the nearest face of the box [0, n·Δx]³ (m).
inline double distance_to_surface(const CorrespondenceCloud& c, const int cells[3], std::size_t i) {
  double d = 1e300;
  for (int k = 0; k < 3; ++k) d = std::min({d, c.disc.x(i, k), cells[k] * c.spacing - c.disc.x(i, k)});
  return d;
}

}  // namespace peridot::testing
