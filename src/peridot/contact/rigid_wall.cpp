// Penalty contact of the points with rigid frictionless planes (rigid_wall.hpp).
#include "peridot/contact/rigid_wall.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "peridot/core/error.hpp"
#include "peridot/materials/models.hpp"
#include "peridot/core/deterministic_sum.hpp"

namespace peridot {

void check_symmetry_walls(const Problem& problem, const Discretization& disc, const std::vector<MaterialParams>& params) {
  std::vector<std::uint8_t> near(disc.num_points(), 0);  // within a horizon of a symmetry wall
  for (const RigidWallSpec& wall : problem.rigid_walls) {
    if (wall.contact != WallContactKind::symmetry) continue;
    const std::string where = fmt::format("rigid_walls.{}: contact: symmetry", wall.name);
    std::size_t nearest = std::numeric_limits<std::size_t>::max();
    double nearest_gap = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < disc.num_points(); ++i) {
      const double gap = dot(disc.x.get(i) - wall.point, wall.normal);
      const std::size_t block = static_cast<std::size_t>(disc.block[i]);
      const MaterialParams& p = params[block];
      const Vec3 x = disc.x.get(i);
      if (gap < 0)
        throw InputError(wall.pos, fmt::format("{}: point {} of body '{}' at ({:g}, {:g}, {:g}) m is behind the plane "
                                               "at t = 0; the bodies must be on its normal's side",
                                               where, disc.input_id[i], problem.bodies[block].name, x.x, x.y, x.z));
      if (gap >= p.horizon) continue;
      if (!is_model<CorrespondenceModel>(p))
        throw InputError(wall.pos, fmt::format("{}: body '{}' ({} model) comes within its horizon of the plane; the "
                                               "symmetry contact is built for correspondence bodies only (use contact: "
                                               "penalty)",
                                               where, problem.bodies[block].name, model_name(p.model)));
      if (near[i])
        throw InputError(wall.pos, fmt::format("{}: point {} at ({:g}, {:g}, {:g}) m is within a horizon of two "
                                               "symmetry walls (corners are not mirrored twice)",
                                               where, disc.input_id[i], x.x, x.y, x.z));
      near[i] = 1;
      if (gap < nearest_gap) nearest_gap = gap, nearest = i;
    }
    if (nearest == std::numeric_limits<std::size_t>::max())
      throw InputError(wall.pos, where + ": no correspondence point is within a horizon of the plane at t = 0; the "
                                         "bodies must touch it from the start (their surface on the plane)");
    const double half_spacing = 0.5 * std::cbrt(disc.volume[nearest]);
    if (std::abs(nearest_gap - half_spacing) > 0.02 * half_spacing) {
      const Vec3 x = disc.x.get(nearest);
      throw InputError(wall.pos, fmt::format(
          "{}: the nearest point, {} at ({:g}, {:g}, {:g}) m, is {:g} m from the plane, not half its spacing "
          "({:g} m): put the plane on the body's surface (half a spacing beyond its outer points), so that the "
          "mirror images continue the body's lattice",
          where, disc.input_id[nearest], x.x, x.y, x.z, nearest_gap, half_spacing));
    }
  }
}

RigidWalls::RigidWalls(const Problem& problem, const ModelContext& model) : model_(&model) {
  for (const RigidWallSpec& s : problem.rigid_walls)
    walls_.push_back({s.name, s.point, s.normal, s.speed, s.stiffness_factor});
  // Σ_j V_j c/ξ over a full family: ∫ 4πξ² (c/ξ) dξ = 2π c δ² in 3D; in 2D, V = h × area and
  // ∫ 2πξ h (c/ξ) dξ = 2π h c δ; in 1D the integral diverges at ξ → 0 and the lattice's sum is
  // 2 A c Σ_{k ≤ δ/Δx} 1/k.
  for (const MaterialParams& p : model.params) {
    const double delta = p.horizon, c = p.stable_micromodulus;
    if (p.dimension == 1) {
      double harmonic = 0;  // point files give no spacing: the nearest neighbours only, then
      const long neighbours = problem.spacing > 0 ? static_cast<long>(std::floor(delta / problem.spacing * (1 + 1e-10))) : 1;
      for (long k = 1; k <= neighbours; ++k) harmonic += 1.0 / static_cast<double>(k);
      point_stiffness_.push_back(2 * problem.area * c * std::max(harmonic, 1.0));
      continue;
    }
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
