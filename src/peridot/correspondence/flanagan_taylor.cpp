// Flanagan–Taylor (1987) incremental rotation: docs/algorithms.md §6; Foster et al. (2010) eqs 15–18.
#include "peridot/correspondence/flanagan_taylor.hpp"

#include <cmath>

namespace peridot::correspondence {

Mat3 rotation_increment(const Vec3d& omega, double dt) {
  const Mat3 half_step = (0.5 * dt) * skew(omega);
  // I − ½ΔtΩ has determinant 1 + |½Δt ω|² ≥ 1: always invertible.
  return (Mat3::Identity() - half_step).inverse() * (Mat3::Identity() + half_step);
}

Mat3 flanagan_taylor_update(const Mat3& L, double dt, PolarState& polar) {
  const Mat3 D = 0.5 * (L + L.transpose());
  const Mat3 W = 0.5 * (L - L.transpose());
  const Mat3& V = polar.left_stretch;
  const Mat3 DV = D * V;
  // axial(DV − VD) = axial(DV − (DV)ᵀ) = 2 axial of the skew part of DV; written out as F&T eq 13.
  const Vec3d z(DV(2, 1) - DV(1, 2), DV(0, 2) - DV(2, 0), DV(1, 0) - DV(0, 1));
  const Vec3d w = axial(W);
  // V̇ symmetric requires (Ω − W)V + V(Ω − W) = DV − VD, whose axial vector is (tr V I − V) axial(Ω − W).
  const Mat3 A = V.trace() * Mat3::Identity() - V;
  const Vec3d omega = w + A.inverse() * z;
  const Mat3 Omega = skew(omega);
  polar.rotation = rotation_increment(omega, dt) * polar.rotation;
  polar.left_stretch = V + dt * (L * V - V * Omega);
  return polar.rotation.transpose() * D * polar.rotation;
}

}  // namespace peridot::correspondence
