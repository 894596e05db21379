// Material-point driver (homogeneous deformation histories) for the correspondence constitutive laws:
// Foster, Silling & Chen (2010) eqs 14–23 through material_point_step, and the uniaxial test of §10.
#include "peridot/correspondence/material_point_driver.hpp"

#include <cmath>

#include <fmt/format.h>

#include "peridot/core/error.hpp"
#include "peridot/correspondence/hypoelastic.hpp"
#include "peridot/correspondence/j2_viscoplastic.hpp"
#include "peridot/correspondence/johnson_cook.hpp"

namespace peridot::correspondence {

namespace {

/// Advances `from` to F_end over Δt (F_rate = (F_end − F_start)/Δt, exact for a motion linear in time
/// over the step, as the peridynamic mid-step velocity gives).
template <ConstitutiveLaw Law>
MaterialPointSample<Law> advance(const Law& law, const MaterialPointSample<Law>& from, const Mat3& F_end,
                                 double dt) {
  MaterialPointSample<Law> to = from;
  to.time = from.time + dt;
  to.deformation_gradient = F_end;
  const Mat3 F_rate = (F_end - from.deformation_gradient) / dt;
  to.cauchy_stress = material_point_step(law, F_end, F_rate, dt, to.polar, to.unrotated_stress, to.history);
  return to;
}

}  // namespace

template <ConstitutiveLaw Law>
std::vector<MaterialPointSample<Law>> run_prescribed_deformation(const Law& law,
                                                                 const std::function<Mat3(double)>& F_of_t,
                                                                 double dt, int num_steps) {
  std::vector<MaterialPointSample<Law>> samples(1);
  samples.reserve(num_steps + 1);
  samples[0].deformation_gradient = F_of_t(0.0);
  for (int k = 1; k <= num_steps; ++k) samples.push_back(advance(law, samples.back(), F_of_t(k * dt), dt));
  return samples;
}

Mat3 simple_shear_gradient(double gamma) {
  Mat3 F = Mat3::Identity();
  F(0, 1) = gamma;
  return F;
}

template <ConstitutiveLaw Law>
std::vector<MaterialPointSample<Law>> run_simple_shear(const Law& law, double shear_rate, double dt, int num_steps) {
  return run_prescribed_deformation<Law>(
      law, [shear_rate](double t) { return simple_shear_gradient(shear_rate * t); }, dt, num_steps);
}

template <ConstitutiveLaw Law>
std::vector<MaterialPointSample<Law>> run_uniaxial_stress(const Law& law, const UniaxialStressOptions& options) {
  const double dt = options.dt;
  const double tolerance =
      options.lateral_stress_tolerance > 0 ? options.lateral_stress_tolerance : 1e-12 * law.shear_modulus();
  // Log-strain perturbation for the finite-difference Jacobian: large enough that the stress change
  // (~E × 1e-8) dwarfs round-off in σ, small enough that the response is linear across a yield kink
  // only rarely (Newton then simply takes another iteration).
  constexpr double perturbation = 1e-8;
  const double K = law.bulk_modulus(), G = law.shear_modulus();
  const double elastic_poisson = (3 * K - 2 * G) / (2 * (3 * K + G));

  auto gradient = [](double axial, const Eigen::Vector2d& lateral) {
    Mat3 F = Mat3::Zero();
    F(0, 0) = std::exp(axial);
    F(1, 1) = std::exp(lateral(0));
    F(2, 2) = std::exp(lateral(1));
    return F;
  };
  auto lateral_stress = [](const MaterialPointSample<Law>& s) {
    return Eigen::Vector2d(s.cauchy_stress(1, 1), s.cauchy_stress(2, 2));
  };

  std::vector<MaterialPointSample<Law>> samples(1);
  samples.reserve(options.num_steps + 1);
  Eigen::Vector2d lateral = Eigen::Vector2d::Zero(), lateral_previous = Eigen::Vector2d::Zero();
  for (int k = 1; k <= options.num_steps; ++k) {
    const double axial = options.true_strain_rate * dt * k;
    // Initial guess: extrapolate the last increment (elastic contraction on the first step).
    Eigen::Vector2d guess = k == 1 ? Eigen::Vector2d::Constant(-elastic_poisson * axial)
                                   : Eigen::Vector2d(2 * lateral - lateral_previous);
    MaterialPointSample<Law> next = advance(law, samples.back(), gradient(axial, guess), dt);
    Eigen::Vector2d residual = lateral_stress(next);
    int iteration = 0;
    while (residual.cwiseAbs().maxCoeff() > tolerance) {
      if (++iteration > options.max_iterations || !residual.allFinite())
        throw NumericalError(fmt::format(
            "material-point driver: uniaxial stress step {} (t = {:g} s) did not bring the lateral stresses "
            "to zero: |σ22|, |σ33| = {:g}, {:g} Pa after {} iterations (tolerance {:g} Pa)",
            k, k * dt, std::abs(residual(0)), std::abs(residual(1)), options.max_iterations, tolerance));
      Eigen::Matrix2d jacobian;
      for (int c = 0; c < 2; ++c) {
        Eigen::Vector2d shifted = guess;
        shifted(c) += perturbation;
        jacobian.col(c) = (lateral_stress(advance(law, samples.back(), gradient(axial, shifted), dt)) - residual) /
                          perturbation;
      }
      guess -= jacobian.partialPivLu().solve(residual);
      next = advance(law, samples.back(), gradient(axial, guess), dt);
      residual = lateral_stress(next);
    }
    lateral_previous = lateral;
    lateral = guess;
    samples.push_back(next);
  }
  return samples;
}

#define PERIDOT_INSTANTIATE_DRIVER(Law)                                                                     \
  template std::vector<MaterialPointSample<Law>> run_prescribed_deformation<Law>(                           \
      const Law&, const std::function<Mat3(double)>&, double, int);                                         \
  template std::vector<MaterialPointSample<Law>> run_simple_shear<Law>(const Law&, double, double, int);    \
  template std::vector<MaterialPointSample<Law>> run_uniaxial_stress<Law>(const Law&, const UniaxialStressOptions&);

PERIDOT_INSTANTIATE_DRIVER(Hypoelastic)
PERIDOT_INSTANTIATE_DRIVER(J2Viscoplastic)
PERIDOT_INSTANTIATE_DRIVER(JohnsonCook)

}  // namespace peridot::correspondence
