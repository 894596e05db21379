#pragma once
// Small fixed-size vector used for geometry and set-up code (never stored per point: point fields are
// structure-of-arrays, see state/points.hpp).
#include <array>
#include <cmath>

namespace peridot {

struct Vec3 {
  double x = 0, y = 0, z = 0;
  constexpr double operator[](int d) const { return d == 0 ? x : (d == 1 ? y : z); }
  constexpr double& operator[](int d) { return d == 0 ? x : (d == 1 ? y : z); }
};

constexpr Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
constexpr Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
constexpr Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
constexpr double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(Vec3 a) { return std::sqrt(dot(a, a)); }

}  // namespace peridot
