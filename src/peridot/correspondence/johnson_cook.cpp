// Johnson–Cook plasticity with an implicit radial return, and Johnson–Cook damage as history (johnson_cook.hpp).
#include "peridot/correspondence/johnson_cook.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "peridot/correspondence/bracketed_root.hpp"
#include "peridot/correspondence/j2_viscoplastic.hpp"
#include "peridot/deck/map_reader.hpp"

// KeySpecs are written with designated initializers that leave the other fields at their defaults on
// purpose; GCC 12 warns about every omitted field regardless.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace peridot::correspondence {

double JohnsonCook::flow_stress(double eqps, double eqps_rate) const {
  const double hardening = yield_stress + hardening_coefficient * std::pow(std::max(eqps, 0.0), hardening_exponent);
  return hardening * (1 + rate_coefficient * log_rate_ratio(eqps_rate, reference_strain_rate));
}

double JohnsonCook::failure_strain(double triaxiality, double eqps_rate, double temperature_rise) const {
  return damage.failure_strain(triaxiality, log_rate_ratio(eqps_rate, reference_strain_rate),
                               thermal.homologous(temperature_rise));
}

Mat3 JohnsonCook::update(const Mat3& tau, const Mat3& d, double dt, History& history) const {
  if (!(dt > 0)) return tau;
  static const double root_two_thirds = std::sqrt(2.0 / 3.0);
  const Mat3 strain_increment = d * dt;
  const double pressure = tau.trace() / 3 + bulk * strain_increment.trace();
  const Mat3 S_trial = deviator(tau) + 2 * shear * deviator(strain_increment);
  const double trial_norm = S_trial.norm();
  const double eqps_old = history.equivalent_plastic_strain;
  const double softening = thermal.factor(history.temperature_rise);

  if (trial_norm <= root_two_thirds * softening * flow_stress(eqps_old, 0)) {  // elastic
    history.equivalent_plastic_strain_rate = 0;
    history.flow_stress = 0;
    return S_trial + pressure * Mat3::Identity();
  }
  // Positive at Δλ = 0 (the trial is outside the static surface of εp_n) and −√(2/3) σ_y < 0 at Δλ = |S^tr|/(2μ):
  // bracketed.
  const auto surface = [&](double dlambda) {
    return softening * flow_stress(eqps_old + root_two_thirds * dlambda, root_two_thirds * dlambda / dt);
  };
  const auto residual = [&](double dlambda) { return trial_norm - 2 * shear * dlambda - root_two_thirds * surface(dlambda); };
  const double upper = trial_norm / (2 * shear);
  // residual(upper) = −√(2/3) G ≤ 0, but at and above melting (G = 0) round-off can leave it a few ulps of
  // |S^tr| above zero: taken as 0, the root is then Δλ = upper (no deviatoric stress).
  const double residual_upper = std::min(residual(upper), 0.0);
  const RootResult root = brent_root(residual, 0.0, upper, residual(0.0), residual_upper, 1e-14 * upper);
  if (!root.converged) return Mat3::Constant(std::numeric_limits<double>::quiet_NaN());
  const double dlambda = root.x;
  const double eqps_increment = root_two_thirds * dlambda;
  const double G = surface(dlambda);
  const Mat3 S_new = (trial_norm - 2 * shear * dlambda) / trial_norm * S_trial;

  history.equivalent_plastic_strain = eqps_old + eqps_increment;
  history.equivalent_plastic_strain_rate = eqps_increment / dt;
  history.flow_stress = G;
  const Mat3 tau_new = S_new + pressure * Mat3::Identity();
  damage.accumulate(history.damage, eqps_increment, tau_new,
                    log_rate_ratio(history.equivalent_plastic_strain_rate, reference_strain_rate),
                    thermal.homologous(history.temperature_rise));
  history.temperature_rise += thermal.heating(G, eqps_increment, density);
  return tau_new;
}

std::vector<KeySpec> JohnsonCook::keys() {
  std::vector<KeySpec> keys = {
      {.key = "strain_hardening_coefficient", .unit = Unit::pressure, .range = non_negative,
       .description = "B (Pa): johnson_cook's σ_y = (A + B εp^n)(1 + C ln ε̇*)(1 − T*^m), A = yield_stress; default 0"},
      {.key = "strain_hardening_exponent", .range = positive, .description = "n (-), johnson_cook; default 1"},
      {.key = "strain_rate_coefficient", .range = non_negative,
       .description = "C (-), johnson_cook; ε̇* = max(ε̇p/ε̇0, 1); default 0 (rate independent)"}};
  // A (yield_stress), ε̇0 and the thermal_softening section mean the same as in j2_viscoplastic: its entries.
  for (const KeySpec& k : J2Viscoplastic::keys())
    if (k.key == "yield_stress" || k.key == "reference_strain_rate" || k.key == "thermal_softening" ||
        k.key == "johnson_cook_damage")
      keys.push_back(k);
  return keys;
}

JohnsonCook JohnsonCook::from_parameters(const Parameters& q, const ElasticConstants& elastic, double density) {
  JohnsonCook law;
  law.bulk = elastic.bulk_modulus;
  law.shear = elastic.shear_modulus;
  law.yield_stress = q.number("yield_stress");
  law.hardening_coefficient = q.number_or("strain_hardening_coefficient", 0);
  law.hardening_exponent = q.number_or("strain_hardening_exponent", 1);
  law.rate_coefficient = q.number_or("strain_rate_coefficient", 0);
  law.reference_strain_rate = q.number_or("reference_strain_rate", 1);
  law.thermal = ThermalSoftening::from_parameters(q);
  law.density = density;
  law.damage = JohnsonCookDamage::from_parameters(q);
  return law;
}

}  // namespace peridot::correspondence
