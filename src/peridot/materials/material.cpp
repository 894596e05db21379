#include "peridot/materials/material.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>


namespace peridot {

double planar_bulk_modulus(const ElasticConstants& c, PlaneKind plane) {
  const double K = c.bulk_modulus, G = c.shear_modulus;
  return plane == PlaneKind::stress ? 9 * K * G / (3 * K + 4 * G) : K + G / 3;
}

double influence_moment(InfluenceKind kind, double horizon, int p) {
  const double scale = std::pow(horizon, p + 1);
  switch (kind) {
    case InfluenceKind::constant: return scale / (p + 1);
    case InfluenceKind::inverse_distance: return scale / p;
    case InfluenceKind::gaussian: {
      // I_p = ∫₀¹ x^p e^{−x²} dx by the recurrence I_p = −1/(2e) + (p − 1)/2 · I_{p−2}.
      double even = std::sqrt(std::numbers::pi) / 2 * std::erf(1.0), odd = (1 - std::exp(-1.0)) / 2;
      double value = p % 2 == 0 ? even : odd;
      for (int q = p % 2 + 2; q <= p; q += 2) value = -0.5 * std::exp(-1.0) + (q - 1) / 2.0 * value;
      return scale * value;
    }
  }
  return 0;
}

double bond_based_micromodulus(const ElasticConstants& c, double horizon, InfluenceKind influence,
                               const Problem& problem) {
  if (problem.dimension == 3) return 9 * c.bulk_modulus / (2 * std::numbers::pi * influence_moment(influence, horizon, 3));
  if (problem.dimension == 1) return c.youngs_modulus / (problem.area * influence_moment(influence, horizon, 1));
  return 4 * planar_bulk_modulus(c, problem.plane) /
         (std::numbers::pi * problem.thickness * influence_moment(influence, horizon, 2));
}

// The work to break every bond crossing a unit crack area, with the bond-based micromodulus c0 of the
// material's K and influence function (for LPS too, as is usual):
// 3D: G0 = (π c0 s0²/2) ∫₀^δ ω ξ⁴ dξ  (ω = 1: s0 = √(5G0/(9Kδ)));
// 2D: G0 = h c0 s0² ∫₀^δ ω ξ³ dξ      (ω = 1: s0 = √(πG0/(3K′δ)));
// 1D: G0 = (A c0 s0²/2) ∫₀^δ ω ξ² dξ  (ω = 1: s0 = √(3G0/(Eδ))).
double critical_stretch_from_energy(double fracture_energy, const MaterialSpec& spec, double horizon,
                                    const Problem& problem) {
  const double c0 = bond_based_micromodulus(spec.elastic, horizon, spec.influence, problem);
  if (problem.dimension == 3)
    return std::sqrt(2 * fracture_energy / (std::numbers::pi * c0 * influence_moment(spec.influence, horizon, 4)));
  if (problem.dimension == 1)
    return std::sqrt(2 * fracture_energy / (problem.area * c0 * influence_moment(spec.influence, horizon, 2)));
  return std::sqrt(fracture_energy / (problem.thickness * c0 * influence_moment(spec.influence, horizon, 3)));
}

}  // namespace peridot
