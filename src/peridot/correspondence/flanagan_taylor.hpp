#pragma once
// Incremental rotation of the polar decomposition F = V R (Foster, Silling & Chen 2010, eq 16), following
// Flanagan & Taylor, CMAME 62 (1987) 305 as restated in docs/algorithms.md §6, and the unrotated rate
// of deformation d = Rᵀ D R (eq 18) in which the constitutive laws are written (eqs 19–22).
//   D = ½(L + Lᵀ) (eq 15), W = ½(L − Lᵀ)
//   z = axial(D V − V D),  w = axial(W)
//   ω = w + [tr(V) I − V]⁻¹ z,  Ω = [ω]×                         (F&T eqs 10–13)
//   R_{n+1} = Q R_n,  Q = (I − ½Δt Ω)⁻¹ (I + ½Δt Ω)   (Hughes–Winget / Cayley, F&T eq 39 family)
//     Q is orthogonal for any Δt. Of the two increments docs/algorithms.md §6 allows, the Cayley form is chosen
//     because it inverts the mid-step velocity gradient of kinematics.hpp: for a rigid rotation from R_n
//     to R_{n+1}, L = (2/Δt)(Q − I)(Q + I)⁻¹ exactly, and the Cayley map of Δt L returns Q, so a rigid
//     rotation is recovered to round-off whatever its rate or step (the exponential map would be off by
//     2 tan(θ/2) − θ per step). The Rodrigues form and its printed sign (see the warning there) are not used.
//   V_{n+1} = V_n + Δt (L V_n − V_n Ω)                            (F&T steps 4–5, forward Euler)
//   d = R_{n+1}ᵀ D R_{n+1}                                         (eq 18)
#include "peridot/correspondence/tensor.hpp"

namespace peridot::correspondence {

/// Rotation R and left stretch V of one point; both start as I.
struct PolarState {
  Mat3 rotation = Mat3::Identity();
  Mat3 left_stretch = Mat3::Identity();
};

/// Advances R and V over one step with velocity gradient L (1/s) and returns the unrotated rate of
/// deformation d (1/s). V is integrated explicitly; once strain increments far beyond those of a stable step
/// have made it lose positive definiteness (tr V I − V singular), ω and d are not finite.
Mat3 flanagan_taylor_update(const Mat3& L, double dt, PolarState& polar);

/// Q = (I − ½Δt [ω]×)⁻¹ (I + ½Δt [ω]×), ω in rad/s.
Mat3 rotation_increment(const Vec3d& omega, double dt);

}  // namespace peridot::correspondence
