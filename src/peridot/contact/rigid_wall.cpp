// Penalty contact of the points with rigid frictionless planes (rigid_wall.hpp).
#include "peridot/contact/rigid_wall.hpp"

#include <cmath>
#include <numbers>

#include "peridot/solvers/simulation.hpp"

namespace peridot {

RigidWalls::RigidWalls(const Problem& problem, const ModelContext& model) : model_(&model) {
  for (const RigidWallSpec& s : problem.rigid_walls)
    walls_.push_back({s.name, s.point, s.normal, s.speed, s.stiffness_factor});
  // Σ_j V_j c/ξ over a full family: ∫ 4πξ² (c/ξ) dξ = 2π c δ² in 3D; in 2D, V = h × area and
  // ∫ 2πξ h (c/ξ) dξ = 2π h c δ.
  for (const MaterialParams& p : model.params) {
    const double delta = p.horizon, c = p.stable_micromodulus;
    point_stiffness_.push_back(p.dimension == 3 ? 2 * std::numbers::pi * c * delta * delta
                                                : 2 * std::numbers::pi * problem.thickness * c * delta);
  }
}

double RigidWalls::pressure(const RigidWall& wall, Vec3 origin, const Discretization& disc, const VectorField& u,
                            std::size_t i) const {
  const double gap = dot(disc.x.get(i) + u.get(i) - origin, wall.normal);
  return gap < 0 ? -gap * wall.stiffness_factor * point_stiffness_[static_cast<std::size_t>(disc.block[i])] : 0.0;
}

void RigidWalls::compute(const VectorField& u, double t, VectorField& b) {
  const Discretization& disc = *model_->disc;
  const std::size_t n = disc.num_points();
  if (b.size() != n) b.resize(n);
  double* bp = b.data();
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < 3 * n; ++k) bp[k] = 0;
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    const RigidWall& wall = walls_[w];
    const Vec3 origin = wall.point + (wall.speed * t) * wall.normal;
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      const double q = pressure(wall, origin, disc, u, i);
      if (q == 0) continue;
      for (int d = 0; d < 3; ++d) bp[3 * i + d] += q * wall.normal[d];
    }
  }
}

Vec3 RigidWalls::force_on_wall(std::size_t w, const Discretization& disc, const VectorField& u, double t) const {
  const RigidWall& wall = walls_[w];
  const Vec3 origin = wall.point + (wall.speed * t) * wall.normal;
  const double total = deterministic_sum(disc.num_points(), [&](std::size_t i) {
    return pressure(wall, origin, disc, u, i) * disc.volume[i];
  });
  return (-total) * wall.normal;
}

}  // namespace peridot
