// J2 viscoplasticity, radial return with implicit rate dependence: Foster, Silling & Chen (2010) eqs 26–61.
#include "peridot/correspondence/j2_viscoplastic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "peridot/correspondence/bracketed_root.hpp"

namespace peridot::correspondence {

double J2Viscoplastic::flow_stress(double eqps, double eqps_rate) const {
  const double g = yield_stress * std::pow(1 + eqps / reference_plastic_strain, 1 / hardening_exponent);
  return g * std::pow(1 + eqps_rate / reference_plastic_strain_rate, 1 / rate_exponent);
}

double J2Viscoplastic::thermal_factor(double temperature_rise) const {
  if (!thermal.enabled) return 1;
  const double homologous =
      std::clamp(temperature_rise / (thermal.melting_temperature - thermal.reference_temperature), 0.0, 1.0);
  return 1 - std::pow(homologous, thermal.exponent);
}

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
  const RootResult root = brent_root(residual, 0.0, upper, residual(0.0), residual(upper), 1e-14 * upper);
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
  if (thermal.enabled)
    history.temperature_rise +=
        thermal.taylor_quinney * G * eqps_increment / (density * thermal.specific_heat);
  return S_new + pressure * Mat3::Identity();  // eq 51
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

}  // namespace peridot::correspondence
