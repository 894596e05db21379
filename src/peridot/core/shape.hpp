#pragma once
// Solid shapes that bodies, node sets and probes are made of. A shape is a small tree: primitives
// (box, cylinder, tube, sphere) combined by union and difference. In 2D the z coordinate is ignored:
// box → rectangle, cylinder and sphere → disc, tube → annulus (the axis must then be z).
#include <string>
#include <vector>

#include "peridot/core/bounding_box.hpp"
#include "peridot/core/vec3.hpp"

namespace peridot {

struct Shape {
  enum class Kind { box, cylinder, tube, sphere, union_of, difference };
  Kind kind = Kind::box;
  // box: lo, hi (m)
  Vec3 lo, hi;
  // cylinder / tube: base centre, unit axis, length (m); sphere: centre
  Vec3 center;
  Vec3 axis{0, 0, 1};
  double length = 0;
  double radius = 0;        ///< cylinder, sphere, tube outer radius (m)
  double inner_radius = 0;  ///< tube only (m)
  /// union_of: any child; difference: children[0] minus every later child
  std::vector<Shape> children;

  bool contains(Vec3 p, int dimension) const;
  BoundingBox bounds(int dimension) const;
};

}  // namespace peridot
