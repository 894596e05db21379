#pragma once
// J2 (von Mises) viscoplasticity with power-law strain hardening and rate dependence, in the unrotated
// frame. Reference: Foster, Silling & Chen, "Viscoplasticity using peridynamics", IJNME 81 (2010) 1242, §5–9.
//   flow stress        G(εp, ε̇p) = Y (1 + εp/ε0)^(1/n) (1 + ε̇p/ε̇0)^(1/m)          (eqs 58, 59)
//   deviatoric trial   S^tr = S_n + 2μ Δe,  Δe = dev(d) Δt                             (eqs 30, 49)
//   yield check        |S^tr| ≥ √(2/3) G(εp_n, 0)  (the smallest surface any Δλ ≥ 0 can give)
//   implicit rate      |S^tr| − 2μ Δλ − √(2/3) G(εp_n, √(2/3) Δλ/Δt) = 0                (eqs 48, 60)
//                      solved for Δλ ∈ [0, |S^tr|/(2μ)] by Brent's method (bracketed_root.hpp). This is
//                      eq 60 with Δe and S_{t−Δt} projected on the return direction Q^tr = S^tr/|S^tr|,
//                      (2μΔe + S_n) : Q^tr = |S^tr|, which puts the returned stress exactly on the surface.
//   radial return      S_{n+1} = √(2/3) G_t Q^tr                                          (eq 50, 61)
//   pressure           p_{n+1} = p_n + K tr(d) Δt,  τ = S + p I                           (eqs 51, 52)
//   plastic strain     εp_{n+1} = εp_n + √(2/3) (Δe − (S_{n+1} − S_n)/(2μ)) : Q_mid,
//                      Q_mid = (Q_{n+1} + Q_n)/2                                          (eqs 56, 57)
//                      (Q_n = Q_{n+1} when S_n = 0; the increment is floored at 0 so that a step that
//                      reverses the stress direction can never reduce εp.)
// The yield surface of step n+1 is evaluated at εp_n (eq 37, backward implicit in the rate only).
// Foster's 6061-T6 aluminium: E = 68.9 GPa, ν = 0.333, Y = 276 MPa, n = 13.5, m = 44, ε0 = 0.001,
// ε̇0 = 1000 /s (§10). m = ∞ gives the rate-independent law.
//
// Optional adiabatic thermal softening (not in Foster et al., who follow Warren & Tabbara in dropping the
// temperature of Camacho & Ortiz): the flow stress is multiplied by the Johnson–Cook thermal factor
//   Θ(T) = 1 − T*^q,  T* = (T − T_r)/(T_m − T_r) clamped to [0, 1],
// and the point heats by the plastic work it dissipates, with no conduction (an impact is over long before
// heat diffuses a horizon: aluminium's diffusivity 7e-5 m²/s moves heat ~0.06 mm in 50 µs):
//   ΔT_{n+1} = ΔT_n + β G_t Δεp / (ρ c)        (S : Δe^p = G_t Δεp for the radial return)
// β the Taylor–Quinney coefficient. Θ uses T_n (explicit in temperature, as in explicit impact codes),
// so the return mapping of a step is unchanged apart from the constant factor.
//
// Optional Johnson–Cook damage (johnson_cook_damage.hpp): D += Δεp/εf at the returned stress, with the
// temperature of the step before.
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

struct J2Viscoplastic {
  /// constitutive_law: j2_viscoplastic: its keys (required ones only with this law), the thermal_softening
  /// section, the checks across keys, and the law from a material's parameters (correspondence/laws.hpp).
  static constexpr std::string_view name = "j2_viscoplastic";
  static std::vector<KeySpec> keys();
  static std::vector<SectionSpec> sections();
  static void check(const MapReader& material, const Parameters& parameters, DeckContext& context);
  static J2Viscoplastic from_parameters(const Parameters& parameters, const ElasticConstants& elastic,
                                        double density);

  double bulk = 0;                           ///< K (Pa)
  double shear = 0;                          ///< μ (Pa)
  double yield_stress = 0;                   ///< Y, quasi-static yield stress (Pa)
  double hardening_exponent = 1;             ///< n (-)
  double rate_exponent = 1;                  ///< m (-); +∞: rate independent
  double reference_plastic_strain = 1;       ///< ε0 (-)
  double reference_plastic_strain_rate = 1;  ///< ε̇0 (1/s)

  /// Adiabatic heating and Johnson–Cook thermal softening (above); off when
  /// `thermal.enabled` is false. The heating needs the density.
  ThermalSoftening thermal;
  double density = 0;  ///< ρ (kg/m³)
  /// Johnson–Cook damage (johnson_cook_damage.hpp), its ε̇* with ε̇0 = reference_plastic_strain_rate; off
  /// unless the material has johnson_cook_damage.
  JohnsonCookDamage damage;

  struct History {
    double equivalent_plastic_strain = 0;       ///< εp (-)
    double equivalent_plastic_strain_rate = 0;  ///< ε̇p of the last step (1/s)
    double flow_stress = 0;                     ///< G_t of the last plastic step, 0 if elastic (Pa)
    double temperature_rise = 0;                ///< T − T_r (K), adiabatic; 0 without thermal softening
    double damage = 0;                          ///< D (-), 0 … 1; 0 without johnson_cook_damage
  };

  /// G(εp, ε̇p) (Pa), eqs 58–59, without the thermal factor.
  double flow_stress(double eqps, double eqps_rate) const;
  /// Θ(T_r + ΔT) (-): 1 without thermal softening.
  double thermal_factor(double temperature_rise) const;

  Mat3 update(const Mat3& tau, const Mat3& d, double dt, History& history) const;
  double bulk_modulus() const { return bulk; }
  double shear_modulus() const { return shear; }

  /// Foster et al. (2010) §10 fit to 6061-T6 (Song, Chen & Frew 2002).
  static J2Viscoplastic aluminium_6061_t6();
};

static_assert(ConstitutiveLaw<J2Viscoplastic>);

}  // namespace peridot::correspondence
