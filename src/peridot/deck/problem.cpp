#include "peridot/deck/problem.hpp"

namespace peridot {

const MaterialSpec& Problem::material_of(const BodySpec& body) const {
  for (const MaterialSpec& material : materials)
    if (material.name == body.material) return material;
  PERIDOT_REQUIRE(false, "body '" + body.name + "' refers to undefined material '" + body.material + "'");
}

}  // namespace peridot
