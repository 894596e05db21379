#pragma once
// Resolved per-block material parameters and the influence function. The kernels (pmb.hpp, lps.hpp)
// are tiny functors that say what a bond force and a bond energy are; the bond loops that call them
// live in solvers/internal_force.cpp.
#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>

#include "peridot/deck/problem.hpp"

namespace peridot {

/// Everything a kernel needs about one block, in SI units, computed once at set-up.
struct MaterialParams {
  ModelKind model = ModelKind::pmb;
  InfluenceKind influence = InfluenceKind::constant;
  int dimension = 3;
  double density = 0;  ///< ρ (kg/m³)
  double horizon = 0;  ///< δ (m)
  ElasticConstants elastic;
  /// PMB micromodulus c0 (N/m⁶ in 3D): bond micromodulus c(ξ) = c0 ω(ξ).
  double micromodulus = 0;
  /// LPS: t = (ω/m)[α_v θ ξ + α_d (e − θξ/n)], θ = (n/m) Σ ω ξ e V, n = dilatation_factor (3 or 2).
  double alpha_volumetric = 0;
  double alpha_deviatoric = 0;
  double dilatation_factor = 3;
  double inverse_dilatation_factor = 1.0 / 3;  ///< 1/n: the bond loops multiply, never divide
  /// Bond fails when its stretch exceeds this; +∞ without damage.
  double critical_stretch = std::numeric_limits<double>::infinity();
  /// lps_plastic (Mitchell): a point yields when ‖t^d‖ > k σ_Y, σ_Y = σ_y + H ε̄p, with
  /// k² = c Σ ω² ξ² V / m² and c the calibration constant (lps_plastic.hpp).
  double yield_stress = 0;
  double hardening_modulus = 0;
  double yield_calibration = 0;
  /// lps_viscoelastic: λ_i, τ_b and, for the current Δt, ε = exp(−Δt/τ_b) and β = 1 − (τ_b/Δt)(1 − ε)
  /// (set_time_step; Δt = 0 gives ε = 1, β = 0: no time passes).
  double relaxing_fraction = 0;
  double relaxation_time = 0;
  double viscous_decay = 1;
  double viscous_ramp = 0;
  /// correspondence: the law and its J2 parameters (as in MaterialSpec), and the hourglass coefficient C_HG.
  ConstitutiveLawKind constitutive_law = ConstitutiveLawKind::hypoelastic;
  double hardening_exponent = std::numeric_limits<double>::infinity();
  double reference_plastic_strain = 1;
  double rate_exponent = std::numeric_limits<double>::infinity();
  double reference_strain_rate = 1;
  ThermalSofteningSpec thermal_softening;
  double hourglass_coefficient = 0;
  double hourglass_viscosity = 0;  ///< C_HV (-), viscous hourglass damping
  /// Constant PMB micromodulus of the same bulk response (18K/(πδ⁴) in 3D, 12K′/(πhδ³) in 2D), used by
  /// the Silling–Askari stable time step estimate for every model.
  double stable_micromodulus = 0;
  /// Bond dashpot of the same sums (N s/m⁶): the correspondence model's hourglass damping c_hv, 0 for every
  /// other model. It shortens the stable time step (stable_time_step in solvers/internal_force.hpp).
  double stable_damping = 0;
};

/// What a kernel may read besides its bond: per-point fields indexed by the point, per-bond history by
/// the bond of that point's family (the partner's bond through BondList::reverse). Pointers the models
/// of a problem do not need are null.
struct KernelFields {
  const double* theta = nullptr;        ///< θ
  const double* inverse_m = nullptr;    ///< 1/m
  const double* yield_scale = nullptr;  ///< r of this step's return map (lps_plastic)
  const double* deviatoric_moment = nullptr;  ///< q of this step (lps_plastic)
  const double* released_extension = nullptr; ///< ρ of this step: what θ lost to bonds broken now (lps_plastic)
  const double* bond0 = nullptr;        ///< MaterialHistory::bond[0]
  const double* bond1 = nullptr;        ///< MaterialHistory::bond[1]
};

/// Sets the Δt-dependent constants of every block (lps_viscoelastic's ε and β).
void set_time_step(std::vector<MaterialParams>& params, double dt);

/// Builds the block parameters from the deck. Throws InputError when the fracture energy cannot give a
/// critical stretch (non-positive result).
MaterialParams resolve_material(const MaterialSpec& spec, double horizon, const Problem& problem);

/// The 2D bulk modulus K′ = λ′ + G of the in-plane problem: plane strain K + G/3, plane stress
/// 9KG/(3K + 4G) = E/(2(1 − ν)). (docs/algorithms.md §3)
double planar_bulk_modulus(const ElasticConstants& c, PlaneKind plane);

/// ω(ξ) = 1, δ/ξ or exp(−ξ²/δ²) for a kind fixed at compile time: what a vectorised bond loop calls (a
/// run-time switch, with its call to exp, keeps a loop scalar).
template <InfluenceKind Kind>
inline double influence_of(double xi, double horizon) {
  if constexpr (Kind == InfluenceKind::inverse_distance) return horizon / xi;
  else if constexpr (Kind == InfluenceKind::gaussian) return std::exp(-(xi * xi) / (horizon * horizon));
  else return 1.0;
}

/// Runs f(std::integral_constant<InfluenceKind, kind>) for a kind known only at run time.
template <class F>
decltype(auto) with_influence(InfluenceKind kind, F&& f) {
  using K = InfluenceKind;
  switch (kind) {
    case K::inverse_distance: return f(std::integral_constant<K, K::inverse_distance>{});
    case K::gaussian: return f(std::integral_constant<K, K::gaussian>{});
    case K::constant: break;
  }
  return f(std::integral_constant<K, K::constant>{});
}

/// ω(ξ) for a kind known only at run time.
inline double influence(InfluenceKind kind, double xi, double horizon) {
  return with_influence(kind, [&](auto k) { return influence_of<k.value>(xi, horizon); });
}

/// ∫₀^δ ω(ξ) ξ^p dξ in closed form, for the calibration of the constants (p = 2, 3, 4).
double influence_moment(InfluenceKind kind, double horizon, int p);

}  // namespace peridot
