#pragma once
// Johnson–Cook ductile damage, shared by the plastic laws (j2_viscoplastic, johnson_cook; the deck section
// materials.<name>.johnson_cook_damage). Reference: Johnson & Cook, Eng. Fract. Mech. 21 (1985) 31–48.
//   D_{n+1} = min(1, D_n + Δεp/εf),  εf = [D1 + D2 exp(D3 η)][1 + D4 ln ε̇*][1 + D5 T*]
// η = p/σ_vm the stress triaxiality of the step's returned stress (p = tr σ/3, positive in tension),
// ε̇* = max(ε̇p/ε̇0, 1) with the law's reference_strain_rate, T* the homologous temperature of the law's
// thermal softening (0 without it). εf is never below minimum_failure_strain: fits with D1 < 0 and D3 < 0
// (6061-T6's, among others) give εf ≤ 0 beyond some triaxiality in tension (η > 1.35 for 6061-T6), where the
// material carries almost no plastic flow (spall); read literally, such a step would add no damage at all,
// and a point torn apart in hydrostatic tension would never fail.
//
// How D acts (`coupling`), after Tupek, Rimoli & Radovitzky, CMAME 263 (2013) 20–26:
//   influence_function  the weight of every bond i–j in K, F and the force state is degraded,
//                       ω_ij = ω0(|ξ|) (1 − max(D_i, D_j)),
//                       and the bond breaks for good when that reaches 0 (D_i or D_j = 1): a fully damaged
//                       point loses every bond and becomes a free particle. The stress stays the law's
//                       (undamaged) stress. The correspondence force ω P K⁻¹ ξ does not change when every
//                       weight of a family is scaled alike, so a point softens not by its own damage but by
//                       the loss of weight of its neighbours' bonds to it: a crack needs its damage to
//                       cover the bonds that cross it, a band about a horizon wide, whatever Δx is (the
//                       regularisation the paper reports). Why this function: it is symmetric (both ends of
//                       a bond see one weight, so T_i⟨ξ⟩ − T_j⟨−ξ⟩ still conserves momentum) and vanishes
//                       when either end has failed (the paper's limit). The product (1 − D_i)(1 − D_j) has
//                       both properties too, but it weighs a damaged point's bonds to its less damaged
//                       neighbours above its bonds across the band: the F of a point inside the band stops
//                       seeing the band open, its plastic strain stalls short of failure, and in the
//                       notched bar (examples/notched_bar) a ligament of partly damaged points kept carrying
//                       a quarter of the peak load. With the max, every bond of a point at D is weighted at
//                       most 1 − D, those across the band included, and the band fails through.
//   local_stress        the classical local coupling the paper shows to be unstable: the force state uses
//                       (1 − D) σ; no bond breaks. The damage then localises in the softest row of points,
//                       so the damaged band narrows (and the dissipated energy falls) as Δx shrinks.
#include <cmath>
#include <string_view>
#include <vector>

#include "peridot/correspondence/tensor.hpp"
#include "peridot/deck/problem.hpp"
#include "peridot/deck/schema.hpp"

namespace peridot::correspondence {

enum class DamageCoupling { influence_function, local_stress };

struct JohnsonCookDamage {
  bool enabled = false;
  double d1 = 0, d2 = 0, d3 = 0, d4 = 0, d5 = 0;  ///< D1 … D5 (-)
  double minimum_failure_strain = 1e-3;           ///< the floor of εf (-)
  DamageCoupling coupling = DamageCoupling::influence_function;

  /// εf (-) at triaxiality η, ln ε̇* and T* (see above), at least minimum_failure_strain.
  double failure_strain(double triaxiality, double log_rate, double homologous_temperature) const {
    const double fit = (d1 + d2 * std::exp(d3 * triaxiality)) * (1 + d4 * log_rate) * (1 + d5 * homologous_temperature);
    return fit > minimum_failure_strain ? fit : minimum_failure_strain;  // also when the fit is NaN (η = ±∞)
  }
  /// Adds Δεp/εf to `damage` (capped at 1) for a step that returned to the stress τ (its deviator S and
  /// pressure p = tr τ/3) with plastic strain increment Δεp.
  void accumulate(double& damage, double eqps_increment, const Mat3& tau, double log_rate,
                  double homologous_temperature) const {
    if (!enabled || damage >= 1 || !(eqps_increment > 0)) return;
    const double pressure = tau.trace() / 3;
    const double von_mises = std::sqrt(1.5) * deviator(tau).norm();
    const double triaxiality = von_mises > 0 ? pressure / von_mises : 0.0;
    damage = std::min(1.0, damage + eqps_increment / failure_strain(triaxiality, log_rate, homologous_temperature));
  }
  /// Whether D degrades the bonds' influence function (and breaks them at D = 1).
  bool degrades_bonds() const { return enabled && coupling == DamageCoupling::influence_function; }
  /// Whether D scales the point's stress in its force state.
  bool degrades_stress() const { return enabled && coupling == DamageCoupling::local_stress; }

  /// The key `johnson_cook_damage` of the plastic laws and its section.
  static KeySpec key();
  static SectionSpec section();
  /// The section of a material's parameters; off when the material has none.
  static JohnsonCookDamage from_parameters(const Parameters& parameters);
};

/// ln ε̇* = ln max(ε̇p/ε̇0, 1): 0 at and below the reference rate.
inline double log_rate_ratio(double eqps_rate, double reference_rate) {
  return std::log(std::max(eqps_rate / reference_rate, 1.0));
}

}  // namespace peridot::correspondence
