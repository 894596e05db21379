// J2 viscoplasticity, radial return with implicit rate dependence: Foster, Silling & Chen (2010) eqs 26–61.
#include "peridot/correspondence/j2_viscoplastic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <utility>

#include <fmt/format.h>

#include "peridot/correspondence/bracketed_root.hpp"
#include "peridot/deck/map_reader.hpp"

// KeySpecs are written with designated initializers that leave the other fields at their defaults on
// purpose; GCC 12 warns about every omitted field regardless.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace peridot::correspondence {

double J2Viscoplastic::flow_stress(double eqps, double eqps_rate) const {
  const double g = yield_stress * std::pow(1 + eqps / reference_plastic_strain, 1 / hardening_exponent);
  return g * std::pow(1 + eqps_rate / reference_plastic_strain_rate, 1 / rate_exponent);
}

double J2Viscoplastic::thermal_factor(double temperature_rise) const { return thermal.factor(temperature_rise); }

Mat3 J2Viscoplastic::update(const Mat3& tau, const Mat3& d, double dt, History& history) const {
  if (!(dt > 0)) return tau;
  static const double root_two_thirds = std::sqrt(2.0 / 3.0);
  const Mat3 strain_increment = d * dt;
  const Mat3 deviatoric_increment = deviator(strain_increment);
  const double pressure = tau.trace() / 3 + bulk * strain_increment.trace();  // eq 52
  const Mat3 S_old = deviator(tau);
  const Mat3 S_trial = S_old + 2 * shear * deviatoric_increment;  // eq 49
  const double trial_norm = S_trial.norm();
  const double eqps_old = history.equivalent_plastic_strain;
  const double softening = thermal_factor(history.temperature_rise);

  if (trial_norm <= root_two_thirds * softening * flow_stress(eqps_old, 0)) {  // elastic: eq 50, first case
    history.equivalent_plastic_strain_rate = 0;
    history.flow_stress = 0;
    return S_trial + pressure * Mat3::Identity();
  }

  // Eq 60 projected on Q^tr: positive at Δλ = 0 (the trial is outside the static surface), and equal to
  // −√(2/3) G < 0 at Δλ = |S^tr|/(2μ), so the root is bracketed.
  const auto residual = [&](double dlambda) {
    return trial_norm - 2 * shear * dlambda -
           root_two_thirds * softening * flow_stress(eqps_old, root_two_thirds * dlambda / dt);
  };
  const double upper = trial_norm / (2 * shear);
  // A tolerance on Δλ of 1e-14 |S^tr|/(2μ) is a stress consistency error of 1e-14 |S^tr|.
  // residual(upper) = −√(2/3) G ≤ 0, but at and above melting (G = 0) round-off can leave it a few ulps of
  // |S^tr| above zero: taken as 0, the root is then Δλ = upper (no deviatoric stress).
  const double residual_upper = std::min(residual(upper), 0.0);
  const RootResult root = brent_root(residual, 0.0, upper, residual(0.0), residual_upper, 1e-14 * upper);
  if (!root.converged) return Mat3::Constant(std::numeric_limits<double>::quiet_NaN());
  const double dlambda = root.x;
  const double G = softening * flow_stress(eqps_old, root_two_thirds * dlambda / dt);  // eq 61
  const Mat3 Q_new = S_trial / trial_norm;
  const Mat3 S_new = root_two_thirds * G * Q_new;  // eq 50, radial return

  const double S_old_norm = S_old.norm();
  const Mat3 Q_old = S_old_norm > 0 ? Mat3(S_old / S_old_norm) : Q_new;
  const Mat3 Q_mid = 0.5 * (Q_new + Q_old);  // eq 57
  const double eqps_increment = std::max(
      0.0, root_two_thirds * double_contraction(deviatoric_increment - (S_new - S_old) / (2 * shear), Q_mid));
  history.equivalent_plastic_strain = eqps_old + eqps_increment;  // eq 56
  history.equivalent_plastic_strain_rate = eqps_increment / dt;
  history.flow_stress = G;
  const Mat3 tau_new = S_new + pressure * Mat3::Identity();  // eq 51
  damage.accumulate(history.damage, eqps_increment, tau_new,
                    log_rate_ratio(history.equivalent_plastic_strain_rate, reference_plastic_strain_rate),
                    thermal.homologous(history.temperature_rise));
  history.temperature_rise += thermal.heating(G, eqps_increment, density);
  return tau_new;
}

J2Viscoplastic J2Viscoplastic::aluminium_6061_t6() {
  const double E = 68.9e9, nu = 0.333;
  J2Viscoplastic law;
  law.bulk = E / (3 * (1 - 2 * nu));
  law.shear = E / (2 * (1 + nu));
  law.yield_stress = 276e6;
  law.hardening_exponent = 13.5;
  law.rate_exponent = 44.0;
  law.reference_plastic_strain = 0.001;
  law.reference_plastic_strain_rate = 1000.0;
  return law;
}

std::vector<KeySpec> J2Viscoplastic::keys() {
  return {{.key = "yield_stress", .unit = Unit::pressure, .range = positive,
           .description = "Y (Pa), quasi-static yield stress; j2_viscoplastic and johnson_cook (its A; required there)",
           .required = true},
          {.key = "hardening_exponent", .range = positive,
           .description = "n (-): G ∝ (1 + εp/ε0)^(1/n); j2_viscoplastic; omit for no strain hardening"},
          {.key = "reference_plastic_strain", .range = positive,
           .description = "ε0 (-), with hardening_exponent; j2_viscoplastic"},
          {.key = "rate_exponent", .range = positive,
           .description = "m (-): G ∝ (1 + ε̇p/ε̇0)^(1/m); j2_viscoplastic; omit for rate independence"},
          {.key = "reference_strain_rate", .unit = Unit::rate, .range = positive,
           .description = "ε̇0 (1/s): j2_viscoplastic, with rate_exponent; johnson_cook, the rate of ε̇* = ε̇p/ε̇0 (default 1 /s)"},
          {.key = "thermal_softening", .type = ValueType::mapping,
           .description = "adiabatic heating and Johnson–Cook thermal softening (see materials.<name>.thermal_softening); "
                          "j2_viscoplastic and johnson_cook; omit for none"},
          JohnsonCookDamage::key()};
}

std::vector<SectionSpec> J2Viscoplastic::sections() {
  std::vector<KeySpec> thermal = {
      {.key = "specific_heat", .unit = Unit::specific_heat, .range = positive,
       .description = "c (J/(kg K)), specific heat at constant pressure", .required = true},
      {.key = "reference_temperature", .unit = Unit::temperature, .range = positive,
       .description = "T_r (K): the initial temperature, where the thermal factor is 1", .required = true},
      {.key = "melting_temperature", .unit = Unit::temperature, .range = positive,
       .description = "T_m (K): the thermal factor is 0 there; above reference_temperature", .required = true},
      {.key = "exponent", .range = positive, .description = "q (-): thermal factor 1 − T*^q, Johnson–Cook's m",
       .required = true},
      {.key = "taylor_quinney_coefficient", .default_yaml = "0.9", .range = {0, 1, false, false},
       .description = "β (-): share of the plastic work that heats the point"}};
  return {{"materials.<name>.thermal_softening",
           "adiabatic heating and Johnson–Cook thermal softening of constitutive_law: j2_viscoplastic or johnson_cook; "
           "omit for none",
           std::move(thermal)},
          JohnsonCookDamage::section()};
}

void J2Viscoplastic::check(const MapReader& r, const Parameters& q, DeckContext& ctx) {
  // An exponent and its reference value come together: (1 + εp/ε0)^(1/n), (1 + ε̇p/ε̇0)^(1/m).
  for (auto [exponent, reference] : {std::pair<std::string_view, std::string_view>{"hardening_exponent", "reference_plastic_strain"},
                                     {"rate_exponent", "reference_strain_rate"}})
    if (r.present(exponent) != r.present(reference)) {
      std::string_view given = r.present(exponent) ? exponent : reference;
      if (r.given(given))
        ctx.error(r[given].key_pos, r.path_of(given),
                  fmt::format("{} and {} go together; give both or neither", exponent, reference));
    }
  const Parameters::Entry* reference = q.find("thermal_softening.reference_temperature");
  const Parameters::Entry* melting = q.find("thermal_softening.melting_temperature");
  if (reference && melting && !(melting->number > reference->number))
    ctx.error(melting->pos, r.path_of("thermal_softening") + ".melting_temperature",
              fmt::format("melting_temperature ({:g} K) must be above reference_temperature ({:g} K)",
                          melting->number, reference->number));
}

J2Viscoplastic J2Viscoplastic::from_parameters(const Parameters& q, const ElasticConstants& elastic, double density) {
  J2Viscoplastic law;
  law.bulk = elastic.bulk_modulus;
  law.shear = elastic.shear_modulus;
  law.yield_stress = q.number("yield_stress");
  law.hardening_exponent = q.number_or("hardening_exponent", std::numeric_limits<double>::infinity());
  law.rate_exponent = q.number_or("rate_exponent", std::numeric_limits<double>::infinity());
  law.reference_plastic_strain = q.number_or("reference_plastic_strain", 1);
  law.reference_plastic_strain_rate = q.number_or("reference_strain_rate", 1);
  law.thermal = ThermalSoftening::from_parameters(q);
  law.density = density;
  law.damage = JohnsonCookDamage::from_parameters(q);
  return law;
}

}  // namespace peridot::correspondence
