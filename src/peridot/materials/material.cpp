#include "peridot/materials/material.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "peridot/correspondence/force.hpp"
#include "peridot/materials/lps.hpp"
#include "peridot/materials/lps_plastic.hpp"
#include "peridot/materials/pmb.hpp"

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

void set_time_step(std::vector<MaterialParams>& params, double dt) {
  for (MaterialParams& p : params) {
    if (p.model != ModelKind::lps_viscoelastic) continue;
    const double x = dt / p.relaxation_time;
    p.viscous_decay = std::exp(-x);
    // β = 1 − (1 − ε)/x, written with expm1 so that a small Δt/τ_b keeps its digits.
    p.viscous_ramp = dt > 0 ? 1 + std::expm1(-x) / x : 0.0;
  }
}

namespace {

// PMB micromodulus c0 of a bond-based model with the same response to isotropic strain (see pmb.hpp).
double bond_based_micromodulus(const ElasticConstants& c, double horizon, InfluenceKind influence,
                               const Problem& problem) {
  if (problem.dimension == 3) return 9 * c.bulk_modulus / (2 * std::numbers::pi * influence_moment(influence, horizon, 3));
  return 4 * planar_bulk_modulus(c, problem.plane) /
         (std::numbers::pi * problem.thickness * influence_moment(influence, horizon, 2));
}

// Critical stretch from the fracture energy: the work to break every bond crossing a unit crack area.
// 3D: G0 = (π c0 s0²/2) ∫₀^δ ω ξ⁴ dξ  (ω = 1: s0 = √(5G0/(9Kδ)));
// 2D: G0 = h c0 s0² ∫₀^δ ω ξ³ dξ      (ω = 1: s0 = √(πG0/(3K′δ))).
// For LPS the bond-based micromodulus of the same K is used, as is usual.
double critical_stretch_from_energy(double fracture_energy, double c0, double horizon, InfluenceKind influence,
                                    const Problem& problem) {
  if (problem.dimension == 3)
    return std::sqrt(2 * fracture_energy / (std::numbers::pi * c0 * influence_moment(influence, horizon, 4)));
  return std::sqrt(fracture_energy / (problem.thickness * c0 * influence_moment(influence, horizon, 3)));
}

// Stable time step of a correspondence block (docs/models/correspondence.md): the Silling–Askari bound of the
// PMB solid with the same P-wave modulus M = K + 4G/3 (a PMB solid, ν = 1/4, has M = 1.8K), but never less
// stiff than the PMB solid of the same K, plus the hourglass bond stiffness c_hg = 18 C_HG K/(πδ⁴) (force.hpp):
//   c = 18 [max(K, M/1.8) + C_HG K] / (π δ⁴).
double correspondence_stable_micromodulus(const MaterialSpec& spec, double horizon) {
  const double K = spec.elastic.bulk_modulus, M = K + 4 * spec.elastic.shear_modulus / 3;
  return 18 * (std::max(K, M / 1.8) + spec.hourglass_coefficient * K) / (std::numbers::pi * std::pow(horizon, 4));
}

}  // namespace

MaterialParams resolve_material(const MaterialSpec& spec, double horizon, const Problem& problem) {
  MaterialParams p;
  p.model = spec.model;
  p.influence = spec.influence;
  p.dimension = problem.dimension;
  p.density = spec.density;
  p.horizon = horizon;
  p.elastic = spec.elastic;
  const double c0 = bond_based_micromodulus(spec.elastic, horizon, spec.influence, problem);
  p.stable_micromodulus = bond_based_micromodulus(spec.elastic, horizon, InfluenceKind::constant, problem);
  switch (spec.model) {
    case ModelKind::pmb:
      p.micromodulus = c0;
      break;
    case ModelKind::lps:
    case ModelKind::lps_plastic:
    case ModelKind::lps_viscoelastic:
      if (problem.dimension == 3) {
        p.dilatation_factor = 3;
        p.inverse_dilatation_factor = 1.0 / 3;
        p.alpha_volumetric = 3 * spec.elastic.bulk_modulus;
        p.alpha_deviatoric = 15 * spec.elastic.shear_modulus;
      } else {
        p.dilatation_factor = 2;
        p.inverse_dilatation_factor = 0.5;
        p.alpha_volumetric = 2 * planar_bulk_modulus(spec.elastic, problem.plane);
        p.alpha_deviatoric = 8 * spec.elastic.shear_modulus;
      }
      break;
    case ModelKind::correspondence:
      p.stable_micromodulus = correspondence_stable_micromodulus(spec, horizon);
      p.yield_stress = spec.yield_stress;
      p.constitutive_law = spec.constitutive_law;
      p.hardening_exponent = spec.hardening_exponent;
      p.reference_plastic_strain = spec.reference_plastic_strain;
      p.rate_exponent = spec.rate_exponent;
      p.reference_strain_rate = spec.reference_strain_rate;
      p.thermal_softening = spec.thermal_softening;
      p.hourglass_coefficient = spec.hourglass_coefficient;
      p.hourglass_viscosity = spec.hourglass_viscosity;
      p.stable_damping = correspondence::hourglass_damping(spec.hourglass_viscosity, spec.density,
                                                           spec.elastic.bulk_modulus, horizon);
      break;
  }
  if (spec.model == ModelKind::lps_plastic) {
    p.yield_stress = spec.yield_stress;
    p.hardening_modulus = spec.hardening_modulus;
    p.yield_calibration = plastic_yield_calibration(problem.dimension, problem.plane);
  }
  if (spec.model == ModelKind::lps_viscoelastic) {
    p.relaxing_fraction = spec.relaxing_fraction;
    p.relaxation_time = spec.relaxation_time;
  }
  if (spec.damage.enabled) {
    if (spec.damage.critical_stretch) p.critical_stretch = *spec.damage.critical_stretch;
    else if (spec.damage.fracture_energy)
      p.critical_stretch = critical_stretch_from_energy(*spec.damage.fracture_energy, c0, horizon, spec.influence, problem);
    if (!(p.critical_stretch > 0))
      throw InputError(spec.pos, "materials." + spec.name + ": the critical stretch must be positive");
  }
  return p;
}

}  // namespace peridot
