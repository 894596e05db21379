#pragma once
// Second-order tensors of the correspondence models: Eigen 3×3 matrices for the arithmetic of one point,
// and TensorField, nine doubles per point (row-major), for the per-point arrays (structure of arrays:
// one contiguous array per tensor field, docs/design.md "Data layout").
// Conventions used throughout src/peridot/correspondence (Foster, Silling & Chen 2010, IJNME 81:1242):
//   A : B = A_ij B_ij,  |A| = √(A : A) (their footnote to eq 32),  dev A = A − ⅓ tr(A) I (eqs 26, 30),
//   [a]× b = a × b, axial([a]×) = a (docs/algorithms.md §1, notation).
#include <cmath>
#include <cstddef>
#include <vector>

#include <Eigen/Dense>

namespace peridot::correspondence {

using Mat3 = Eigen::Matrix3d;
using Vec3d = Eigen::Vector3d;

inline Mat3 deviator(const Mat3& a) { return a - (a.trace() / 3.0) * Mat3::Identity(); }

/// A : B
inline double double_contraction(const Mat3& a, const Mat3& b) { return (a.array() * b.array()).sum(); }

/// [a]×, the skew matrix with [a]× v = a × v.
inline Mat3 skew(const Vec3d& a) {
  Mat3 s;
  s << 0, -a(2), a(1),  //
      a(2), 0, -a(0),   //
      -a(1), a(0), 0;
  return s;
}

/// axial(S) = (S₃₂, S₁₃, S₂₁): the vector s with S = [s]× when S is skew.
inline Vec3d axial(const Mat3& s) { return {s(2, 1), s(0, 2), s(1, 0)}; }

/// von Mises equivalent stress √(3/2) |dev σ| (Pa): equals the axial stress G in uniaxial tension (eq 29).
inline double von_mises(const Mat3& sigma) { return std::sqrt(1.5) * deviator(sigma).norm(); }

/// One 3×3 tensor per point, stored row-major as nine contiguous doubles.
class TensorField {
 public:
  TensorField() = default;
  explicit TensorField(std::size_t n) : data_(9 * n, 0.0) {}
  void assign(std::size_t n, const Mat3& value) {
    data_.resize(9 * n);
    for (std::size_t i = 0; i < n; ++i) set(i, value);
  }
  std::size_t size() const { return data_.size() / 9; }
  Mat3 get(std::size_t i) const {
    Mat3 a;
    const double* p = data_.data() + 9 * i;
    a << p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8];
    return a;
  }
  void set(std::size_t i, const Mat3& a) {
    double* p = data_.data() + 9 * i;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) p[3 * r + c] = a(r, c);
  }
  double operator()(std::size_t i, int r, int c) const { return data_[9 * i + 3 * r + c]; }
  const double* data() const { return data_.data(); }
  double* data() { return data_.data(); }

 private:
  std::vector<double> data_;
};

}  // namespace peridot::correspondence
