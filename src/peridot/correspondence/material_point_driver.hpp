#pragma once
// Material-point driver: one constitutive law alone under a prescribed homogeneous deformation history,
// through exactly the per-point step of the peridynamic model (constitutive.hpp material_point_step:
// eq 14 at mid-step, Flanagan–Taylor eqs 15–18, the law in the unrotated frame eqs 19–22, σ = R τ Rᵀ eq 23).
// It is the exact local answer the peridynamic tests compare against.
//   - prescribed F(t): any history, e.g. simple shear F = I + γ̇ t e₁⊗e₂;
//   - uniaxial stress along x at a constant true (logarithmic) strain rate ε̇: F = diag(e^{ε̇t}, λ₂, λ₃), the
//     lateral stretches found at every step by Newton iteration (finite-difference Jacobian) so that the
//     lateral Cauchy stresses σ₂₂ and σ₃₃ vanish to a tolerance.
// Reference: Foster, Silling & Chen, IJNME 81 (2010) 1242, §10 (the uniaxial test at 8300 /s).
// The templates are instantiated in material_point_driver.cpp for every law of this folder; a new law adds
// one line there.
#include <functional>
#include <vector>

#include "peridot/correspondence/constitutive.hpp"

namespace peridot::correspondence {

/// The state of the material point at one time.
template <ConstitutiveLaw Law>
struct MaterialPointSample {
  double time = 0;                                ///< t (s)
  Mat3 deformation_gradient = Mat3::Identity();   ///< F (-)
  Mat3 cauchy_stress = Mat3::Zero();              ///< σ (Pa)
  Mat3 unrotated_stress = Mat3::Zero();           ///< τ (Pa)
  PolarState polar;                               ///< R, V
  typename Law::History history{};
};

/// Samples at t_k = kΔt, k = 0 … num_steps, for the deformation F(t) (F(0) should be I).
template <ConstitutiveLaw Law>
std::vector<MaterialPointSample<Law>> run_prescribed_deformation(const Law& law,
                                                                 const std::function<Mat3(double)>& F_of_t,
                                                                 double dt, int num_steps);

/// F = I + γ e₁⊗e₂ (x displaced in proportion to y).
Mat3 simple_shear_gradient(double gamma);

/// Simple shear at a constant shear rate γ̇ (1/s).
template <ConstitutiveLaw Law>
std::vector<MaterialPointSample<Law>> run_simple_shear(const Law& law, double shear_rate, double dt, int num_steps);

struct UniaxialStressOptions {
  double true_strain_rate = 0;  ///< ε̇ = d ln(λ₁)/dt (1/s); negative for compression
  double dt = 0;                ///< Δt (s)
  int num_steps = 0;
  double lateral_stress_tolerance = 0;  ///< |σ₂₂|, |σ₃₃| at convergence (Pa); 0: 1e-12 × shear modulus
  int max_iterations = 50;              ///< Newton iterations per step before NumericalError
};

/// Uniaxial stress at a constant true strain rate. Throws NumericalError when the lateral iteration does
/// not converge.
template <ConstitutiveLaw Law>
std::vector<MaterialPointSample<Law>> run_uniaxial_stress(const Law& law, const UniaxialStressOptions& options);

}  // namespace peridot::correspondence
