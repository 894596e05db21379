#pragma once
// Axis-aligned boxes: of a shape, of a rank's points, of what a rank must receive from the others.
#include <cstddef>
#include <limits>
#include <vector>

#include "peridot/core/vec3.hpp"

namespace peridot {

struct BoundingBox {
  Vec3 lo, hi;  ///< the box of no points has lo = +∞ and hi = −∞: it meets nothing
  /// Grown by r on every side; an empty box stays empty.
  BoundingBox widened(double r) const { return {lo - Vec3{r, r, r}, hi + Vec3{r, r, r}}; }
  /// lo x, y, z, hi x, y, z: the form exchanged between ranks and kept in checkpoints.
  std::vector<double> six() const { return {lo.x, lo.y, lo.z, hi.x, hi.y, hi.z}; }
};

/// The box of the n points whose x, y, z lie at coords[stride·k + 0, 1, 2]; empty when n is 0.
inline BoundingBox bounding_box(const double* coords, std::size_t stride, std::size_t n) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  BoundingBox box{{inf, inf, inf}, {-inf, -inf, -inf}};
  for (std::size_t k = 0; k < n; ++k)
    for (int d = 0; d < 3; ++d) {
      const double x = coords[stride * k + static_cast<std::size_t>(d)];
      box.lo[d] = x < box.lo[d] ? x : box.lo[d];
      box.hi[d] = x > box.hi[d] ? x : box.hi[d];
    }
  return box;
}

}  // namespace peridot
