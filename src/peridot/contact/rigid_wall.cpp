// Whether a rigid wall can be a symmetry plane (rigid_wall.hpp).
#include "peridot/contact/rigid_wall.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "peridot/core/error.hpp"
#include "peridot/materials/models.hpp"

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

}  // namespace peridot
