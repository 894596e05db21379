#pragma once
// Strains read off a solved displacement field: least-squares slopes of a displacement component
// against a coordinate over a chosen set of points.
#include <cstddef>

#include "peridot/solvers/simulation.hpp"

namespace peridot::testing {

/// Slope of u_component against x_along over the points whose reference position `select` accepts.
template <class Select>
double displacement_slope(const Simulation& sim, int along, int component, Select&& select) {
  const Discretization& disc = sim.discretization();
  double sx = 0, sy = 0, sxx = 0, sxy = 0, count = 0;
  for (std::size_t i = 0; i < disc.num_points(); ++i) {
    if (!select(disc.x.get(i))) continue;
    const double x = disc.x(i, along), y = sim.state().u(i, component);
    sx += x, sy += y, sxx += x * x, sxy += x * y, count += 1;
  }
  return (count * sxy - sx * sy) / (count * sxx - sx * sx);
}

}  // namespace peridot::testing
