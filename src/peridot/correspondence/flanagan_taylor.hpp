#pragma once
// Incremental rotation of the polar decomposition F = V R (Foster, Silling & Chen 2010, eq 16), following
// Flanagan & Taylor, CMAME 62 (1987) 305 as restated in reference/algorithms.md §1, and the unrotated rate
// of deformation d = Rᵀ D R (eq 18) in which the constitutive laws are written (eqs 19–22).
//   D = ½(L + Lᵀ) (eq 15), W = ½(L − Lᵀ)
//   z = axial(D V − V D),  w = axial(W)
//   ω = w + [tr(V) I − V]⁻¹ z,  Ω = [ω]×                         (F&T eqs 10–13)
//   R_{n+1} = Q R_n,  Q = exp(Δt Ω) = I + (sin θ/|ω|) Ω + ((1 − cos θ)/|ω|²) Ω²,  θ = Δt|ω|
//     — with the PLUS sign on Ω² (algorithms.md §1 sign warning: Ω² = ωωᵀ − |ω|² I, and QᵀQ = I needs +)
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
/// deformation d (1/s).
Mat3 flanagan_taylor_update(const Mat3& L, double dt, PolarState& polar);

/// exp(Δt [ω]×) by Rodrigues' formula (plus sign, see above); I when |ω|² < 1e-30 (rad²/s²).
Mat3 rotation_increment(const Vec3d& omega, double dt);

}  // namespace peridot::correspondence
