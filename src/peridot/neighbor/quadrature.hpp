#pragma once
// The isotropic bond quadrature (discretization.quadrature: isotropic; docs/algorithms.md §19).
//
// The one-point quadrature weighs a bond by its neighbour's volume V_j. Under a homogeneous strain every
// ordinary model's stiffness is a fourth moment of the family, Σ ω ξᵖ n⊗n⊗n⊗n V (pmb p = 1, the lps family
// p = 2). On the cubic (square) lattice that sum has cubic symmetry, not isotropy: at δ = 3.015Δx in 3D its
// n_x⁴ : n_x²n_y² ratio is 2.50 where the continuum's is 3, so the interior of the lattice is a slightly
// anisotropic solid whatever δ, and a peridynamic solution does not converge to classical elasticity as δ → 0 at
// a fixed δ/Δx (it stalls at the error of that anisotropy). A lattice of cubic symmetry has one fourth-order
// anisotropy invariant, A(n) = Σ_d n_d⁴ − c (c = 3/5 in 3D, 3/4 in 2D: its mean over directions is zero), so
// one direction weight corrects it:
//     V_j → V_j · s (1 + a A(n)),
// a chosen so that the family's fourth moment is isotropic and s so that it equals the continuum integral
// ∫ ω ξᵖ n_x⁴ dV over the ball (the lps family normalises by its weighted volume m, which cancels s; pmb's
// micromodulus is the continuum's and needs it). The interior operator then reproduces quadratic displacement
// fields exactly, which is second-order consistency with the Navier operator.
#include <cmath>

#include "peridot/deck/problem.hpp"

namespace peridot {

struct IsotropicQuadrature {
  bool on = false;
  double anisotropy = 0;  ///< a
  double scale = 1;       ///< s
  double offset = 0;      ///< c: the mean of Σ_d n_d⁴ over directions (1 in 1D, where A vanishes)
};

/// The weight s (1 + a A(n)) of a bond along d = (d0, d1, d2) of length xi (> 0); 1 when off.
inline double quadrature_weight(const IsotropicQuadrature& q, double d0, double d1, double d2, double xi) {
  if (!q.on) return 1.0;
  const double inv2 = 1.0 / (xi * xi);
  const double n0 = d0 * d0 * inv2, n1 = d1 * d1 * inv2, n2 = d2 * d2 * inv2;
  return q.scale * (1.0 + q.anisotropy * (n0 * n0 + n1 * n1 + n2 * n2 - q.offset));
}

/// What the fit needs of a block: the lattice, its horizon and influence, the partial volumes of the deck,
/// and the power p of ξ in the model's stiffness moment.
struct QuadratureLattice {
  int dimension = 3;
  double spacing = 0;          ///< Δx (m)
  double horizon = 0;          ///< δ (m)
  InfluenceKind influence = InfluenceKind::constant;
  double partial_volume_radius = 0;  ///< r = Δx/2 with partial volumes, else 0
  bool bond_beyond_horizon = false;  ///< partial_volume: extended
  int moment_power = 2;              ///< p
};

/// a, s and c for the family of an interior lattice point (the offsets k Δx within the horizon, as the neighbour
/// search bonds them, weighed by ω, the partial-volume factor and ξᵖ).
IsotropicQuadrature fit_isotropic_quadrature(const QuadratureLattice& lattice);

}  // namespace peridot
