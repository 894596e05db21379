#include "peridot/core/shape.hpp"

#include <algorithm>
#include <limits>

namespace peridot {

namespace {
// Distance along the axis and squared distance from the axis of p, for an axis through c with unit
// direction a. In 2D the axis is z and only the in-plane distance matters.
void axial_coordinates(const Shape& s, Vec3 p, int dimension, double& along, double& r2) {
  Vec3 d = p - s.center;
  if (dimension == 2) {
    along = 0;
    r2 = d.x * d.x + d.y * d.y;
    return;
  }
  along = dot(d, s.axis);
  Vec3 radial = d - along * s.axis;
  r2 = dot(radial, radial);
}
}  // namespace

bool Shape::contains(Vec3 p, int dimension) const {
  switch (kind) {
    case Kind::box:
      return p.x >= lo.x && p.x <= hi.x && (dimension == 1 || (p.y >= lo.y && p.y <= hi.y)) &&
             (dimension <= 2 || (p.z >= lo.z && p.z <= hi.z));
    case Kind::cylinder:
    case Kind::tube: {
      double along, r2;
      axial_coordinates(*this, p, dimension, along, r2);
      if (dimension == 3 && (along < 0 || along > length)) return false;
      if (r2 > radius * radius) return false;
      return kind == Kind::cylinder || r2 >= inner_radius * inner_radius;
    }
    case Kind::sphere: {
      Vec3 d = p - center;
      if (dimension == 2) d.z = 0;
      return dot(d, d) <= radius * radius;
    }
    case Kind::union_of:
      return std::any_of(children.begin(), children.end(),
                         [&](const Shape& c) { return c.contains(p, dimension); });
    case Kind::difference:
      if (children.empty() || !children[0].contains(p, dimension)) return false;
      for (std::size_t k = 1; k < children.size(); ++k)
        if (children[k].contains(p, dimension)) return false;
      return true;
  }
  return false;
}

BoundingBox Shape::bounds(int dimension) const {
  BoundingBox b;
  switch (kind) {
    case Kind::box:
      b = {lo, hi};
      break;
    case Kind::sphere:
      b = {center - Vec3{radius, radius, radius}, center + Vec3{radius, radius, radius}};
      break;
    case Kind::cylinder:
    case Kind::tube: {
      if (dimension == 2) {
        b = {center - Vec3{radius, radius, 0}, center + Vec3{radius, radius, 0}};
        break;
      }
      // Exact box of a cylinder: along each coordinate, the end caps extend radius*sqrt(1 - a_d^2).
      Vec3 top = center + length * axis;
      for (int d = 0; d < 3; ++d) {
        double extent = radius * std::sqrt(std::max(0.0, 1.0 - axis[d] * axis[d]));
        b.lo[d] = std::min(center[d], top[d]) - extent;
        b.hi[d] = std::max(center[d], top[d]) + extent;
      }
      break;
    }
    case Kind::union_of: {
      double inf = std::numeric_limits<double>::infinity();
      b = {{inf, inf, inf}, {-inf, -inf, -inf}};
      for (const Shape& c : children) {
        BoundingBox cb = c.bounds(dimension);
        for (int d = 0; d < 3; ++d) {
          b.lo[d] = std::min(b.lo[d], cb.lo[d]);
          b.hi[d] = std::max(b.hi[d], cb.hi[d]);
        }
      }
      break;
    }
    case Kind::difference:
      b = children.empty() ? BoundingBox{} : children[0].bounds(dimension);
      break;
  }
  if (dimension <= 2) b.lo.z = b.hi.z = 0;
  if (dimension == 1) b.lo.y = b.hi.y = 0;
  return b;
}

}  // namespace peridot
