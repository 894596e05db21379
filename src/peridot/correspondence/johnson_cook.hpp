#pragma once
// Johnson–Cook plasticity, and the Johnson–Cook damage it accumulates, in the unrotated frame.
// References: Johnson & Cook, 7th Int. Symp. Ballistics (1983) 541–547 (flow stress); Johnson & Cook, Eng. Fract.
// Mech. 21 (1985) 31–48 (failure strain); Tupek, Rimoli & Radovitzky, CMAME 263 (2013) 20–26 (their use in
// correspondence peridynamics).
//   flow stress      σ_y(εp, ε̇p, T) = (A + B εp^n)(1 + C ln ε̇*)(1 − T*^m),  ε̇* = max(ε̇p/ε̇0, 1)
//                    (the rate factor is 1 at and below ε̇0: A is the quasi-static yield stress, never undercut)
//   deviatoric trial S^tr = S_n + 2μ Δe,  Δe = dev(d) Δt
//   yield check      |S^tr| ≥ √(2/3) σ_y(εp_n, 0, T_n)
//   return           |S^tr| − 2μ Δλ − √(2/3) σ_y(εp_n + √(2/3) Δλ, √(2/3) Δλ/Δt, T_n) = 0, solved for
//                    Δλ ∈ [0, |S^tr|/(2μ)] by Brent's method (bracketed_root.hpp): implicit in the plastic
//                    strain and its rate, so the returned stress is on the surface of the step's end state;
//   radial return    S_{n+1} = (|S^tr| − 2μ Δλ) S^tr/|S^tr|,  Δεp = √(2/3) Δλ
//   pressure         p_{n+1} = p_n + K tr(d) Δt,  τ = S + p I
//   heating          T as the thermal_softening section says (thermal_softening.hpp), explicit in T.
// Damage (the section johnson_cook_damage): D_{n+1} = D_n + Δεp/εf at the step's returned stress, rate and
// temperature (johnson_cook_damage.hpp, which also says how D acts).
#include <string_view>
#include <vector>

#include "peridot/correspondence/constitutive.hpp"
#include "peridot/correspondence/johnson_cook_damage.hpp"
#include "peridot/correspondence/thermal_softening.hpp"
#include "peridot/deck/problem.hpp"
#include "peridot/deck/schema.hpp"

namespace peridot {
class DeckContext;
class MapReader;
}  // namespace peridot

namespace peridot::correspondence {

struct JohnsonCook {
  /// constitutive_law: johnson_cook: its keys (yield_stress, reference_strain_rate and thermal_softening are
  /// shared with j2_viscoplastic), and the law from a material's parameters (correspondence/laws.hpp).
  static constexpr std::string_view name = "johnson_cook";
  static std::vector<KeySpec> keys();
  static JohnsonCook from_parameters(const Parameters& parameters, const ElasticConstants& elastic, double density);

  double bulk = 0;                    ///< K (Pa)
  double shear = 0;                   ///< μ (Pa)
  double yield_stress = 0;            ///< A (Pa)
  double hardening_coefficient = 0;   ///< B (Pa)
  double hardening_exponent = 1;      ///< n (-)
  double rate_coefficient = 0;        ///< C (-)
  double reference_strain_rate = 1;   ///< ε̇0 (1/s)
  ThermalSoftening thermal;           ///< T* and the heating; its exponent is Johnson–Cook's m
  double density = 0;                 ///< ρ (kg/m³), for the heating
  JohnsonCookDamage damage;           ///< off unless the material has johnson_cook_damage

  struct History {
    double equivalent_plastic_strain = 0;       ///< εp (-)
    double equivalent_plastic_strain_rate = 0;  ///< ε̇p of the last step (1/s)
    double flow_stress = 0;                     ///< σ_y of the last plastic step, 0 if elastic (Pa)
    double temperature_rise = 0;                ///< T − T_r (K), adiabatic; 0 without thermal softening
    double damage = 0;                          ///< D (-), 0 … 1
  };

  /// (A + B εp^n)(1 + C ln ε̇*) (Pa), without the thermal factor.
  double flow_stress(double eqps, double eqps_rate) const;
  /// εf (-) at triaxiality η, plastic strain rate and temperature rise.
  double failure_strain(double triaxiality, double eqps_rate, double temperature_rise) const;

  Mat3 update(const Mat3& tau, const Mat3& d, double dt, History& history) const;
  double bulk_modulus() const { return bulk; }
  double shear_modulus() const { return shear; }
};

static_assert(ConstitutiveLaw<JohnsonCook>);

}  // namespace peridot::correspondence
