// Material-point driver and the two constitutive laws (Foster, Silling & Chen 2010 §5–10):
//  - hypoelastic: Hooke's law in uniaxial stress (exact in log strain) and in small simple shear;
//  - J2 viscoplastic, rate-independent limit (m → ∞): elastic up to Y, then the hardening law of eq 59;
//  - J2 viscoplastic at 8300 /s (Foster's 6061-T6): the closed form of eqs 58–59 on the plastic branch;
//  - radial return (eq 50) keeps the stress on the yield surface in simple shear with large rotation;
//  - objectivity (eqs 19–23): a rigid rotation after plastic stretching leaves τ and εp unchanged and
//    rotates σ with the body;
//  - adiabatic thermal softening: perfectly plastic, rate independent, thermal exponent 1 has the closed form
//    σ = Y exp(−βY εp/(ρc(T_m − T_r))); the temperature is the heat of the plastic work; off = same bits;
//  - Brent's method on known roots.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>
#include <vector>

#include "peridot/correspondence/bracketed_root.hpp"
#include "peridot/correspondence/hypoelastic.hpp"
#include "peridot/correspondence/j2_viscoplastic.hpp"
#include "peridot/correspondence/material_point_driver.hpp"

namespace peridot {
namespace {

using namespace correspondence;

constexpr double E_al = 68.9e9, nu_al = 0.333;

TEST(CorrBrent, FindsBracketedRootsAndRefusesUnbracketed) {
  int calls = 0;
  auto cubic = [&](double x) { ++calls; return x * x * x - 2 * x - 5; };
  const RootResult r = brent_root(cubic, 2.0, 3.0, cubic(2.0), cubic(3.0), 1e-15);
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(r.x, 2.0945514815423265, 4e-15);
  EXPECT_LT(calls, 15);  // superlinear: bisection alone would need ~50
  // The shape of eq 60 near Δλ = 0: a power 1/44 of the unknown, steep at the origin.
  auto steep = [](double x) { return 1.0 - 3e4 * x - std::pow(1 + 1e6 * x, 1.0 / 44); };
  const RootResult s = brent_root(steep, 0.0, 1.0, steep(0.0), steep(1.0), 1e-18);
  ASSERT_TRUE(s.converged);
  EXPECT_LT(std::abs(steep(s.x)), 1e-12);
  const RootResult none = brent_root(cubic, 3.0, 4.0, cubic(3.0), cubic(4.0), 1e-15);
  EXPECT_FALSE(none.converged);
  EXPECT_TRUE(std::isnan(none.x));
}

TEST(CorrDriver, HypoelasticUniaxialStressMatchesHooke) {
  const Hypoelastic law = Hypoelastic::from_young_poisson(E_al, nu_al);
  UniaxialStressOptions options;
  options.true_strain_rate = 1.0;
  options.dt = 1e-5;
  options.num_steps = 200;  // ε = 2e-3
  const auto samples = run_uniaxial_stress(law, options);
  double worst_axial = 0, worst_lateral = 0, worst_lateral_stress = 0;
  for (const auto& s : samples) {
    const double strain = std::log(s.deformation_gradient(0, 0));
    if (strain == 0) continue;
    // Uniaxial hypoelasticity with R = I integrates to σ = E ln λ₁ and ln λ₂ = ln λ₃ = −ν ln λ₁ exactly.
    worst_axial = std::max(worst_axial, std::abs(s.cauchy_stress(0, 0) / (E_al * strain) - 1));
    worst_lateral = std::max(worst_lateral, std::abs(std::log(s.deformation_gradient(1, 1)) / (-nu_al * strain) - 1));
    worst_lateral_stress = std::max({worst_lateral_stress, std::abs(s.cauchy_stress(1, 1)), std::abs(s.cauchy_stress(2, 2))});
  }
  std::printf("uniaxial Hooke: rel. error σ11 %.2e, lateral strain %.2e, max |σ22|,|σ33| %.2e Pa\n", worst_axial,
              worst_lateral, worst_lateral_stress);
  EXPECT_LT(worst_axial, 1e-8);
  EXPECT_LT(worst_lateral, 1e-8);
  EXPECT_LE(worst_lateral_stress, 1e-12 * law.shear);  // the driver's default tolerance
  EXPECT_NEAR(samples.back().cauchy_stress(0, 0), E_al * 2e-3, 1e-8 * E_al * 2e-3);
}

TEST(CorrDriver, HypoelasticSmallSimpleShearMatchesHooke) {
  const Hypoelastic law = Hypoelastic::from_young_poisson(E_al, nu_al);
  const auto samples = run_simple_shear(law, 1.0, 1e-6, 100);  // γ = 1e-4
  const Mat3& sigma = samples.back().cauchy_stress;
  const double gamma = 1e-4;
  // σ12 = Gγ with corrections of relative order γ² (finite rotation); normal stresses of order Gγ².
  EXPECT_NEAR(sigma(0, 1), law.shear * gamma, 1e-7 * law.shear * gamma);
  EXPECT_NEAR(sigma(1, 0), sigma(0, 1), 1e-12 * law.shear * gamma);
  EXPECT_LT(std::abs(sigma(0, 0)), 1e-3 * law.shear * gamma);
  EXPECT_LT(std::abs(sigma(2, 2)), 1e-9 * law.shear * gamma);
}

J2Viscoplastic rate_independent_6061() {
  J2Viscoplastic law = J2Viscoplastic::aluminium_6061_t6();
  law.rate_exponent = 1e12;  // (1 + ε̇p/ε̇0)^(1/m) − 1 < 1e-14 at the rates below
  return law;
}

/// Axial plastic strain of a uniaxial sample, ε − σ/E: equal to εp in uniaxial stress.
double plastic_strain(const MaterialPointSample<J2Viscoplastic>& s) {
  return std::log(s.deformation_gradient(0, 0)) - s.cauchy_stress(0, 0) / E_al;
}

/// Uniaxial stress at 1 /s true strain rate, with steps of Δt, up to the true strain `final_strain`.
std::vector<MaterialPointSample<J2Viscoplastic>> uniaxial_to(const J2Viscoplastic& law, double final_strain,
                                                             double dt) {
  UniaxialStressOptions options;
  options.true_strain_rate = 1.0;
  options.dt = dt;
  options.num_steps = static_cast<int>(std::lround(final_strain / dt));
  return run_uniaxial_stress(law, options);
}

TEST(CorrDriver, J2RateIndependentLimitYieldsAtYAndFollowsHardeningLaw) {
  const J2Viscoplastic law = rate_independent_6061();
  const double Y = law.yield_stress;
  auto run = [&](double dt) { return uniaxial_to(law, 0.1, dt); };
  const auto samples = run(1e-5);
  bool yielded = false;
  double worst_elastic = 0, worst_lagged = 0, worst_eqps = 0, worst_current = 0;
  for (std::size_t k = 1; k < samples.size(); ++k) {
    const auto& s = samples[k];
    const double sigma = s.cauchy_stress(0, 0), strain = std::log(s.deformation_gradient(0, 0));
    const double eqps = s.history.equivalent_plastic_strain;
    if (eqps == 0) {
      ASSERT_FALSE(yielded) << "elastic step after yield in monotonic loading, step " << k;
      EXPECT_LE(sigma, Y * (1 + 1e-12));
      worst_elastic = std::max(worst_elastic, std::abs(sigma / (E_al * strain) - 1));
      continue;
    }
    if (!yielded) {
      // First plastic step: the surface is that of εp = 0, i.e. Y (eq 59).
      EXPECT_NEAR(sigma, Y, 1e-10 * Y) << "first yield at step " << k;
      EXPECT_NEAR(E_al * std::log(samples[k - 1].deformation_gradient(0, 0)), samples[k - 1].cauchy_stress(0, 0), 1e-6 * Y);
      EXPECT_LE(samples[k - 1].cauchy_stress(0, 0), Y);
      yielded = true;
    }
    // The surface of step k uses εp of step k−1 (eq 37); the stress sits exactly on it (eq 50), and σ11
    // equals the von Mises stress up to the lateral stresses the driver leaves (≤ 1e-12 μ ≈ 0.03 Pa).
    const double lagged = law.flow_stress(samples[k - 1].history.equivalent_plastic_strain, 0);
    worst_lagged = std::max(worst_lagged, std::abs(von_mises(s.cauchy_stress) / lagged - 1));
    EXPECT_NEAR(sigma, lagged, 1e-10 * Y);
    // εp of eq 56 equals the axial plastic strain ε − σ/E of uniaxial stress.
    worst_eqps = std::max(worst_eqps, std::abs(eqps - plastic_strain(s)));
    // Against the closed form Y(1 + εp/ε0)^(1/n) at the current εp: off by the one-step lag.
    worst_current = std::max(worst_current, std::abs(sigma / law.flow_stress(plastic_strain(s), 0) - 1));
  }
  ASSERT_TRUE(yielded);
  const double final_eqps = samples.back().history.equivalent_plastic_strain;
  std::printf("J2 rate-independent: elastic %.2e, on lagged surface %.2e, εp vs ε−σ/E %.2e, vs closed form %.2e; "
              "final εp %.5f, σ %.4f MPa\n",
              worst_elastic, worst_lagged, worst_eqps, worst_current, final_eqps,
              samples.back().cauchy_stress(0, 0) / 1e6);
  EXPECT_LT(worst_elastic, 1e-8);
  EXPECT_LT(worst_lagged, 1e-12);
  EXPECT_LT(worst_eqps, 1e-10);
  EXPECT_NEAR(final_eqps, 0.1 - samples.back().cauchy_stress(0, 0) / E_al, 1e-10);
  // The lag error is first order in Δt: halving Δt halves it.
  const auto half = run(0.5e-5);
  double worst_current_half = 0;
  for (std::size_t k = 1; k < half.size(); ++k)
    if (half[k].history.equivalent_plastic_strain > 0)
      worst_current_half = std::max(worst_current_half,
                                    std::abs(half[k].cauchy_stress(0, 0) / law.flow_stress(plastic_strain(half[k]), 0) - 1));
  std::printf("J2 rate-independent: closed-form error %.3e at Δt = 1e-5 s, %.3e at 5e-6 s\n", worst_current,
              worst_current_half);
  EXPECT_LT(worst_current, 1e-3);
  EXPECT_NEAR(worst_current_half / worst_current, 0.5, 0.05);
}

TEST(CorrDriver, J2RateDependenceAt8300PerSecondMatchesClosedForm) {
  const J2Viscoplastic law = J2Viscoplastic::aluminium_6061_t6();
  const double rate = 8300;  // true strain rate (1/s); Foster's test was at 8300 /s engineering
  UniaxialStressOptions options;
  options.true_strain_rate = rate;
  options.dt = 1e-8;
  options.num_steps = 1205;  // ε = 0.1
  const auto samples = run_uniaxial_stress(law, options);
  double worst = 0;
  std::size_t plastic_steps = 0;
  for (std::size_t k = 1; k < samples.size(); ++k) {
    const auto& s = samples[k];
    if (s.history.equivalent_plastic_strain == 0) continue;
    ++plastic_steps;
    // Eqs 58–59 with εp of the previous step (eq 37) and the plastic strain rate of this step, both taken
    // from the stress–strain history alone (εp = ε − σ/E), not from the law's internal state.
    const double eqps_previous = std::max(0.0, plastic_strain(samples[k - 1]));
    const double eqps_rate = (plastic_strain(s) - eqps_previous) / options.dt;
    const double closed_form = law.yield_stress *
                               std::pow(1 + eqps_previous / law.reference_plastic_strain, 1 / law.hardening_exponent) *
                               std::pow(1 + eqps_rate / law.reference_plastic_strain_rate, 1 / law.rate_exponent);
    worst = std::max(worst, std::abs(s.cauchy_stress(0, 0) / closed_form - 1));
  }
  const auto& last = samples.back();
  const double eqps_rate = last.history.equivalent_plastic_strain_rate;
  // Stress over the quasi-static surface of the same (lagged, eq 37) εp: the rate factor of eq 58.
  const double rate_factor =
      last.cauchy_stress(0, 0) / law.flow_stress(samples[samples.size() - 2].history.equivalent_plastic_strain, 0);
  std::printf("J2 at 8300/s: %zu plastic steps, worst rel. error vs eqs 58-59 %.2e; final ε̇p %.1f /s, "
              "rate factor %.5f (closed form at ε̇p = 8300: %.5f), σ %.2f MPa\n",
              plastic_steps, worst, eqps_rate, rate_factor, std::pow(1 + rate / 1000, 1 / 44.0),
              last.cauchy_stress(0, 0) / 1e6);
  EXPECT_GT(plastic_steps, 1000u);
  EXPECT_LT(worst, 1e-9);
  // Late on the plastic branch hardening is slow, so nearly all the strain rate is plastic:
  // ε̇p = ε̇ − σ̇/E with σ̇/E ≈ (dG/dεp)/E ε̇ ≈ 0.3 % of ε̇ at εp = 0.09.
  EXPECT_NEAR(eqps_rate, rate, 0.01 * rate);
  // The rate factor (1 + ε̇p/ε̇0)^(1/m) at ε̇p ≈ 8300 /s is 1.052: 5 % above the quasi-static stress.
  EXPECT_NEAR(rate_factor, std::pow(1 + eqps_rate / 1000, 1 / 44.0), 1e-9);
  EXPECT_GT(rate_factor, 1.05);
}

TEST(CorrDriver, J2RadialReturnKeepsStressOnYieldSurfaceInSimpleShear) {
  const J2Viscoplastic law = J2Viscoplastic::aluminium_6061_t6();
  const double dt = 1e-6;
  const auto samples = run_simple_shear(law, 1000.0, dt, 1000);  // γ = 1: large rotation
  std::size_t plastic_steps = 0;
  double worst_surface = 0, worst_rotation = 0;
  for (std::size_t k = 1; k < samples.size(); ++k) {
    const auto& s = samples[k];
    const auto& previous = samples[k - 1].history;
    const double vm = von_mises(s.cauchy_stress);
    // σ = R τ Rᵀ does not change the von Mises stress.
    worst_rotation = std::max(worst_rotation, std::abs(vm - von_mises(s.unrotated_stress)) / law.yield_stress);
    EXPECT_GE(s.history.equivalent_plastic_strain, previous.equivalent_plastic_strain);
    if (s.history.flow_stress == 0) {
      EXPECT_LT(vm, law.flow_stress(previous.equivalent_plastic_strain, 0) * (1 + 1e-12)) << "step " << k;
      continue;
    }
    ++plastic_steps;
    // On the surface of eq 61, G(εp_n, √(2/3)Δλ/Δt), never outside it.
    worst_surface = std::max(worst_surface, std::abs(vm / s.history.flow_stress - 1));
    EXPECT_GE(s.history.flow_stress, law.flow_stress(previous.equivalent_plastic_strain, 0));
  }
  const auto& last = samples.back();
  std::printf("J2 simple shear γ = 1: %zu plastic steps, |σ_vm/G − 1| ≤ %.2e, rotation invariance %.2e, "
              "final εp %.4f, σ12 %.2f MPa, R12 %.4f\n",
              plastic_steps, worst_surface, worst_rotation, last.history.equivalent_plastic_strain,
              last.cauchy_stress(0, 1) / 1e6, last.polar.rotation(0, 1));
  EXPECT_GT(plastic_steps, 900u);
  EXPECT_LT(worst_surface, 1e-12);
  EXPECT_LT(worst_rotation, 1e-12);
  // In simple shear εp ≈ γ/√3 once plastic flow dominates (plastic part of γ ≈ γ − τ_y/G).
  EXPECT_NEAR(last.history.equivalent_plastic_strain, (1.0 - last.cauchy_stress(0, 1) / law.shear) / std::sqrt(3.0),
              0.05 / std::sqrt(3.0));
}

TEST(CorrDriver, RigidRotationAfterPlasticStretchRotatesStressOnly) {
  // Two histories: stretch past yield, then (A) hold F, or (B) rotate rigidly. The viscoplastic stress
  // relaxes during the hold (the overstress of eq 58 decays at fixed strain), identically in both: τ and εp
  // must agree, and σ_B = Q σ_A Qᵀ.
  const J2Viscoplastic law = J2Viscoplastic::aluminium_6061_t6();
  const double dt = 1e-7, stretch_rate = 1000;  // 1/s
  const int stretch_steps = 200, rotate_steps = 300;
  const double t1 = stretch_steps * dt;
  const Vec3d axis = Vec3d(2, -1, 1).normalized();
  const double spin = 5e4;  // rad/s: 1.5 rad over the rotation phase
  auto stretch = [&](double t) {
    Mat3 U = Mat3::Identity();
    U(0, 0) = 1 + stretch_rate * std::min(t, t1);  // uniaxial strain to 2 %, well past yield
    return U;
  };
  auto rotation = [&](double t) { return Mat3(Eigen::AngleAxisd(spin * std::max(0.0, t - t1), axis).toRotationMatrix()); };
  const int steps = stretch_steps + rotate_steps;
  const auto held = run_prescribed_deformation(law, stretch, dt, steps);
  const auto rotated = run_prescribed_deformation(law, [&](double t) { return Mat3(rotation(t) * stretch(t)); }, dt, steps);
  const auto& a = held.back();
  const auto& b = rotated.back();
  ASSERT_GT(held[stretch_steps].history.equivalent_plastic_strain, 0.005);
  const Mat3 Q = rotation(steps * dt);
  const double tau_difference = (b.unrotated_stress - a.unrotated_stress).cwiseAbs().maxCoeff();
  const double sigma_error = (b.cauchy_stress - Q * a.cauchy_stress * Q.transpose()).cwiseAbs().maxCoeff();
  std::printf("rotation after plastic stretch: εp %.6f (held) vs %.6f (rotated), relaxation during the hold "
              "%.2f MPa; max |τ_B − τ_A| %.2e Pa, max |σ_B − Qσ_AQᵀ| %.2e Pa\n",
              a.history.equivalent_plastic_strain, b.history.equivalent_plastic_strain,
              (held[stretch_steps].cauchy_stress(0, 0) - a.cauchy_stress(0, 0)) / 1e6, tau_difference, sigma_error);
  EXPECT_NEAR(b.history.equivalent_plastic_strain, a.history.equivalent_plastic_strain, 1e-14);
  // Round-off relative to the stress (σ₁₁ ≈ 1.6 GPa, mostly pressure).
  const double scale = a.cauchy_stress.cwiseAbs().maxCoeff();
  EXPECT_LT(tau_difference, 1e-13 * scale);
  EXPECT_LT(sigma_error, 1e-13 * scale);
}

// Perfectly plastic (n = ∞), rate independent (m = ∞), thermal exponent q = 1: dT = β σ dεp/(ρc) with
// σ = Y(1 − T*) integrates to σ = Y exp(−a εp), T* = 1 − exp(−a εp), a = βY/(ρc(T_m − T_r)). A small
// specific heat makes a ≈ 1.5 so that the softening is 26 % by εp = 0.2; the explicit temperature lags one
// step, a first-order error.
TEST(CorrDriver, J2AdiabaticThermalSofteningMatchesClosedForm) {
  J2Viscoplastic law = rate_independent_6061();
  law.hardening_exponent = std::numeric_limits<double>::infinity();
  law.thermal = {.enabled = true, .specific_heat = 100, .reference_temperature = 294, .melting_temperature = 925,
                 .exponent = 1, .taylor_quinney = 0.9};
  law.density = 2700;
  const double Y = law.yield_stress;
  const double a = law.thermal.taylor_quinney * Y /
                   (law.density * law.thermal.specific_heat *
                    (law.thermal.melting_temperature - law.thermal.reference_temperature));
  auto run = [&](double dt) { return uniaxial_to(law, 0.2, dt); };
  auto worst_error = [&](const auto& samples) {
    double worst_stress = 0, worst_heat = 0, plastic_work = 0;
    for (std::size_t k = 1; k < samples.size(); ++k) {
      const auto& s = samples[k];
      const double eqps = s.history.equivalent_plastic_strain;
      if (eqps == 0) continue;
      worst_stress = std::max(worst_stress, std::abs(s.cauchy_stress(0, 0) / (Y * std::exp(-a * eqps)) - 1));
      // The temperature is the heat of the plastic work done so far, W_p = ∫ σ dεp (trapezoidal).
      const auto& before = samples[k - 1];
      plastic_work += 0.5 * (s.cauchy_stress(0, 0) + before.cauchy_stress(0, 0)) *
                      (eqps - before.history.equivalent_plastic_strain);
      const double heat = law.thermal.taylor_quinney * plastic_work / (law.density * law.thermal.specific_heat);
      worst_heat = std::max(worst_heat, std::abs(s.history.temperature_rise / heat - 1));
    }
    return std::pair{worst_stress, worst_heat};
  };
  const auto samples = run(1e-5);
  const auto [stress, heat] = worst_error(samples);
  const auto [stress_half, heat_half] = worst_error(run(0.5e-5));
  const auto& last = samples.back();
  std::printf("J2 thermal softening: final εp %.4f, σ/Y %.4f (closed form %.4f), ΔT %.1f K; closed-form error "
              "%.2e at Δt = 1e-5 s, %.2e at 5e-6 s; heat vs plastic work %.2e, %.2e\n",
              last.history.equivalent_plastic_strain, last.cauchy_stress(0, 0) / Y,
              std::exp(-a * last.history.equivalent_plastic_strain), last.history.temperature_rise, stress, stress_half,
              heat, heat_half);
  EXPECT_LT(last.cauchy_stress(0, 0) / Y, 0.78);  // the softening is really exercised
  EXPECT_LT(stress, 1e-3);
  EXPECT_NEAR(stress_half / stress, 0.5, 0.05);  // first order: the lagged temperature
  EXPECT_LT(heat, 1e-3);
  EXPECT_LT(heat_half, heat);
  // The homologous temperature is clamped: at and above melting the flow stress is 0, never negative.
  EXPECT_EQ(law.thermal_factor(0), 1.0);
  EXPECT_EQ(law.thermal_factor(631), 0.0);
  EXPECT_EQ(law.thermal_factor(2000), 0.0);
  EXPECT_EQ(law.thermal_factor(-10), 1.0);
}

TEST(CorrDriver, J2WithoutThermalSofteningIsUnchangedAndStaysAtReferenceTemperature) {
  const J2Viscoplastic plain = J2Viscoplastic::aluminium_6061_t6();
  J2Viscoplastic hot = plain;
  hot.thermal = {.enabled = true, .specific_heat = 896, .reference_temperature = 294, .melting_temperature = 925,
                 .exponent = 1.34, .taylor_quinney = 0.9};
  hot.density = 2700;
  UniaxialStressOptions options;
  options.true_strain_rate = 8300;
  options.dt = 1e-8;
  options.num_steps = 2000;
  const auto a = run_uniaxial_stress(plain, options), b = run_uniaxial_stress(hot, options);
  // Off: no temperature, and the stress of the elastic steps (before any heating) is the same bits.
  EXPECT_EQ(a.back().history.temperature_rise, 0.0);
  for (std::size_t k = 0; k < a.size() && b[k].history.equivalent_plastic_strain == 0; ++k)
    EXPECT_EQ(a[k].cauchy_stress(0, 0), b[k].cauchy_stress(0, 0));
  // On: Foster's aluminium at 8300 /s to ε = 0.166 heats by β W_p/(ρc) ≈ 17 K and softens by ~1 %.
  const double softening = b.back().cauchy_stress(0, 0) / a.back().cauchy_stress(0, 0);
  std::printf("J2 at 8300 /s to ε = %.3f: ΔT %.2f K, stress ratio hot/plain %.5f\n",
              std::log(b.back().deformation_gradient(0, 0)), b.back().history.temperature_rise, softening);
  EXPECT_GT(b.back().history.temperature_rise, 10);
  EXPECT_LT(b.back().history.temperature_rise, 30);
  EXPECT_LT(softening, 1);
  EXPECT_GT(softening, 0.97);
}

}  // namespace
}  // namespace peridot
