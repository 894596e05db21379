#pragma once
// The correspondence (non-ordinary state-based) material as a model of the registry: its deck keys, checks,
// page and block constants (Foster, Silling & Chen 2010). It has no bond kernel: its force is a per-point
// tensor gathered over the bonds (correspondence/force.hpp), driven by solvers/correspondence_blocks.hpp,
// which builds the constitutive law of every block from these Params.
#include <limits>
#include <string_view>

#include "peridot/deck/model_schema.hpp"
#include "peridot/materials/model_base.hpp"

namespace peridot {

/// The constitutive law of a correspondence material (correspondence/hypoelastic.hpp, j2_viscoplastic.hpp).
enum class ConstitutiveLawKind { hypoelastic, j2_viscoplastic };

/// Adiabatic heating with Johnson–Cook thermal softening of a j2_viscoplastic law (j2_viscoplastic.hpp):
/// the flow stress is multiplied by 1 − T*^q, T* = (T − T_r)/(T_m − T_r), and T rises by β ΔW_p/(ρ c).
struct ThermalSoftening {
  bool enabled = false;
  double specific_heat = 0;          ///< c (J/(kg K))
  double reference_temperature = 0;  ///< T_r (K), the initial temperature
  double melting_temperature = 0;    ///< T_m (K)
  double exponent = 1;               ///< q (-)
  double taylor_quinney = 0.9;       ///< β (-)
};

struct CorrespondenceModel : ModelBase {
  static constexpr std::string_view name = "correspondence";
  static ModelInfo info();
  static constexpr bool has_bond_kernel = false;

  struct Params {
    ConstitutiveLawKind law = ConstitutiveLawKind::hypoelastic;
    // J2 viscoplasticity (yield_stress is Y).
    double yield_stress = 0;                                              ///< Y (Pa)
    double hardening_exponent = std::numeric_limits<double>::infinity();  ///< n (-); ∞ = no strain hardening
    double reference_plastic_strain = 1;                                  ///< ε0 (-)
    double rate_exponent = std::numeric_limits<double>::infinity();       ///< m (-); ∞ = rate independent
    double reference_strain_rate = 1;                                     ///< ε̇0 (1/s)
    ThermalSoftening thermal;                                             ///< j2_viscoplastic only
    double hourglass_coefficient = 0;                                     ///< C_HG (-)
    double hourglass_viscosity = 0;                                       ///< C_HV (-)
  };
  /// Also sets the block's stable micromodulus and bond dashpot (the stable time step, see the page).
  static Params resolve(const MaterialSpec& spec, const Problem& problem, MaterialParams& block);
  /// What the model cannot do yet, and the keys that only j2_viscoplastic takes or that go together.
  static void check(const MapReader& material, const ModelParameters& parameters, DeckContext& context);
};

namespace correspondence {

/// c_hg = 18 C_HG K/(π δ⁴) (N/m⁶) from C_HG (-), the bulk modulus K (Pa) and the horizon δ (m).
double hourglass_stiffness(double coefficient, double bulk_modulus, double horizon);
/// c_hv = 18 C_HV √(ρK)/(π δ³) (N s/m⁶) from C_HV (-), the density ρ (kg/m³), K (Pa) and δ (m).
double hourglass_damping(double coefficient, double density, double bulk_modulus, double horizon);

}  // namespace correspondence

}  // namespace peridot
