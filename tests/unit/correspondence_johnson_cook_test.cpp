// The Johnson–Cook law (correspondence/johnson_cook.hpp) through the material-point driver, against closed forms:
//  - uniaxial stress, rate independent: elastic up to A, then σ_vm = A + B εp^n at the step's own εp (the return
//    is implicit in εp), and εp = ε − σ/E (σ_vm, not σ11: the driver leaves lateral stresses of 1e-12 μ);
//  - the rate factor 1 + C ln(ε̇p/ε̇0) at 1000 /s, and no factor below ε̇0;
//  - thermal softening with the temperature of the step before, and the heat of the plastic work;
//  - damage D = Σ Δεp/εf at the triaxiality of uniaxial tension (1/3), compression (−1/3) and shear (0), capped at 1;
//  - the deck: johnson_cook runs in a correspondence block and writes plastic strain and temperature; its keys are
//    refused on another law.
// Constants: 6061-T6 as Uintah's JCPlastic6061T6Al.xml gives them (A = 324 MPa, B = 114 MPa, n = 0.42, m = 1.34,
// T_m = 925 K), C raised to 0.02 and ε̇0 = 1 /s so that the rate factor is well above round-off; the damage
// constants are test values of the usual form (D3 < 0: failure strain falling with triaxiality).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "peridot/correspondence/johnson_cook.hpp"
#include "peridot/correspondence/material_point_driver.hpp"
#include "peridot/deck/deck.hpp"
#include "peridot/solvers/simulation.hpp"

namespace peridot {
namespace {

using namespace correspondence;

constexpr double E_al = 68.9e9, nu_al = 0.33;

JohnsonCook aluminium(double rate_coefficient = 0) {
  JohnsonCook law;
  law.bulk = E_al / (3 * (1 - 2 * nu_al));
  law.shear = E_al / (2 * (1 + nu_al));
  law.yield_stress = 324e6;
  law.hardening_coefficient = 114e6;
  law.hardening_exponent = 0.42;
  law.rate_coefficient = rate_coefficient;
  law.reference_strain_rate = 1;
  law.density = 2700;
  return law;
}

std::vector<MaterialPointSample<JohnsonCook>> uniaxial(const JohnsonCook& law, double rate, double final_strain,
                                                       double dt) {
  UniaxialStressOptions options;
  options.true_strain_rate = rate;
  options.dt = dt;
  options.num_steps = static_cast<int>(std::lround(std::abs(final_strain / rate) / dt));
  return run_uniaxial_stress(law, options);
}

double hardening(const JohnsonCook& law, double eqps) {
  return law.yield_stress + law.hardening_coefficient * std::pow(eqps, law.hardening_exponent);
}

TEST(JohnsonCook, RateIndependentUniaxialStressFollowsTheHardeningLawAtEachStep) {
  const JohnsonCook law = aluminium();
  const auto samples = uniaxial(law, 1.0, 0.1, 1e-5);
  bool yielded = false;
  double worst_elastic = 0, worst_surface = 0, worst_eqps = 0;
  for (std::size_t k = 1; k < samples.size(); ++k) {
    const auto& s = samples[k];
    const double sigma = s.cauchy_stress(0, 0), strain = std::log(s.deformation_gradient(0, 0));
    const double eqps = s.history.equivalent_plastic_strain;
    if (eqps == 0) {
      ASSERT_FALSE(yielded) << "elastic step after yield in monotonic loading, step " << k;
      EXPECT_LE(sigma, law.yield_stress * (1 + 1e-12));
      worst_elastic = std::max(worst_elastic, std::abs(sigma / (E_al * strain) - 1));
      continue;
    }
    yielded = true;
    worst_surface = std::max(worst_surface, std::abs(von_mises(s.cauchy_stress) / hardening(law, eqps) - 1));
    worst_eqps = std::max(worst_eqps, std::abs(eqps - (strain - sigma / E_al)));
  }
  ASSERT_TRUE(yielded);
  std::printf("JC rate independent: elastic %.2e, σ vs A + B εp^n %.2e, εp vs ε − σ/E %.2e; final εp %.5f, σ %.2f MPa\n",
              worst_elastic, worst_surface, worst_eqps, samples.back().history.equivalent_plastic_strain,
              samples.back().cauchy_stress(0, 0) / 1e6);
  EXPECT_LT(worst_elastic, 1e-8);
  EXPECT_LT(worst_surface, 1e-12);  // the end state's own surface: no lag
  EXPECT_LT(worst_eqps, 1e-10);
  EXPECT_GT(samples.back().cauchy_stress(0, 0), 1.1 * law.yield_stress);  // hardening exercised
}

TEST(JohnsonCook, RateFactorIsOnePlusCLogOfTheRateAboveTheReferenceAndOneBelow) {
  const JohnsonCook law = aluminium(0.02);
  const auto fast = uniaxial(law, 1000.0, 0.1, 1e-8);
  double worst = 0;
  for (std::size_t k = 1; k < fast.size(); ++k) {
    const auto& h = fast[k].history;
    if (h.equivalent_plastic_strain == 0) continue;
    const double closed = hardening(law, h.equivalent_plastic_strain) *
                          (1 + 0.02 * std::log(std::max(h.equivalent_plastic_strain_rate, 1.0)));
    worst = std::max(worst, std::abs(von_mises(fast[k].cauchy_stress) / closed - 1));
  }
  const auto& last = fast.back().history;
  const double factor = fast.back().cauchy_stress(0, 0) / hardening(law, last.equivalent_plastic_strain);
  std::printf("JC at 1000 /s: σ vs (A + B εp^n)(1 + C ln ε̇*) %.2e; final ε̇p %.1f /s, rate factor %.5f\n", worst,
              last.equivalent_plastic_strain_rate, factor);
  // Brent's tolerance on Δλ (1e-14 |S^tr|/2μ) times the residual's slope, whose rate term C σ_y/Δλ is large for the
  // small Δλ of a 10 ns step: up to ~1e-10 of σ_y.
  EXPECT_LT(worst, 1e-10);
  EXPECT_NEAR(last.equivalent_plastic_strain_rate, 1000, 10);  // late on, nearly all the strain rate is plastic
  EXPECT_NEAR(factor, 1 + 0.02 * std::log(1000.0), 2e-4);
  // Below ε̇0 the factor is 1: the quasi-static curve, never below A.
  const auto slow = uniaxial(law, 0.5, 0.02, 1e-4);
  for (const auto& s : slow) {
    if (s.history.equivalent_plastic_strain > 0) {
      EXPECT_NEAR(von_mises(s.cauchy_stress), hardening(law, s.history.equivalent_plastic_strain), 1e-12 * law.yield_stress);
    }
  }
}

// Simple shear at a constant rate γ̇ = 2000 /s: once plastic, every step's von Mises stress is the rate-dependent
// flow stress (A + B εp^n)(1 + C ln(ε̇p/ε̇0)) at that step's own εp and ε̇p (the return is implicit in both), to the
// root solver's tolerance; the plastic strain rate approaches γ̇/√3, the equivalent rate of simple shear.
TEST(JohnsonCook, ShearAtConstantRateFollowsTheRateDependentFlowStress) {
  const JohnsonCook law = aluminium(0.02);
  const double shear_rate = 2000.0;
  const auto samples = run_simple_shear(law, shear_rate, 1e-7, 2000);  // γ = 0.4
  double worst = 0;
  std::size_t plastic = 0;
  for (std::size_t k = 1; k < samples.size(); ++k) {
    const auto& h = samples[k].history;
    if (h.equivalent_plastic_strain == samples[k - 1].history.equivalent_plastic_strain) continue;
    ++plastic;
    const double expected = law.flow_stress(h.equivalent_plastic_strain, h.equivalent_plastic_strain_rate);
    worst = std::max(worst, std::abs(von_mises(samples[k].cauchy_stress) / expected - 1));
  }
  const auto& last = samples.back().history;
  std::printf("JC shear at %g /s: %zu plastic steps, σ_vm vs σ_y(εp, ε̇p) within %.2e; final εp %.4f at ε̇p %.1f /s "
              "(γ̇/√3 = %.1f), σ_vm %.2f MPa\n",
              shear_rate, plastic, worst, last.equivalent_plastic_strain, last.equivalent_plastic_strain_rate,
              shear_rate / std::sqrt(3.0), von_mises(samples.back().cauchy_stress) / 1e6);
  EXPECT_GT(plastic, 1000u);
  EXPECT_LT(worst, 1e-9);
  EXPECT_NEAR(last.equivalent_plastic_strain_rate, shear_rate / std::sqrt(3.0), 0.02 * shear_rate / std::sqrt(3.0));
}

TEST(JohnsonCook, ThermalSofteningUsesTheTemperatureOfTheStepBeforeAndHeatsByThePlasticWork) {
  JohnsonCook law = aluminium();
  law.thermal = {.enabled = true, .specific_heat = 896, .reference_temperature = 294, .melting_temperature = 925,
                 .exponent = 1.34, .taylor_quinney = 0.9};
  const auto samples = uniaxial(law, 1.0, 0.5, 1e-4);
  double worst_stress = 0, worst_heat = 0;
  for (std::size_t k = 1; k < samples.size(); ++k) {
    const auto& h = samples[k].history;
    const auto& before = samples[k - 1].history;
    if (h.equivalent_plastic_strain == 0) continue;
    const double closed = hardening(law, h.equivalent_plastic_strain) * law.thermal.factor(before.temperature_rise);
    worst_stress = std::max(worst_stress, std::abs(von_mises(samples[k].cauchy_stress) / closed - 1));
    const double heat = 0.9 * h.flow_stress * (h.equivalent_plastic_strain - before.equivalent_plastic_strain) / (2700 * 896);
    worst_heat = std::max(worst_heat, std::abs((h.temperature_rise - before.temperature_rise) - heat) / heat);
  }
  const auto& last = samples.back();
  std::printf("JC thermal: σ vs (A + B εp^n)Θ(T_n) %.2e, heat vs β σ_y Δεp/(ρc) %.2e; at εp %.3f: ΔT %.1f K, Θ %.4f\n",
              worst_stress, worst_heat, last.history.equivalent_plastic_strain, last.history.temperature_rise,
              law.thermal.factor(last.history.temperature_rise));
  EXPECT_LT(worst_stress, 1e-12);
  EXPECT_LT(worst_heat, 1e-12);
  EXPECT_GT(last.history.temperature_rise, 50);  // the softening is exercised
  EXPECT_LT(law.thermal.factor(last.history.temperature_rise), 0.95);
}

TEST(JohnsonCook, DamageIsThePlasticStrainOverTheFailureStrainOfTheTriaxiality) {
  JohnsonCook law = aluminium();
  law.damage = {.enabled = true, .d1 = -0.77, .d2 = 1.45, .d3 = -0.47, .d4 = 0.0, .d5 = 0.0};
  // Rate independent and isothermal: εf is constant at a constant triaxiality, so D = εp/εf exactly.
  auto check = [&](const char* name, const auto& samples, double triaxiality) {
    const double failure = law.failure_strain(triaxiality, 0, 0);
    double worst = 0;
    for (const auto& s : samples)
      if (s.history.equivalent_plastic_strain > 0 && s.history.damage < 1)
        worst = std::max(worst, std::abs(s.history.damage - s.history.equivalent_plastic_strain / failure));
    const auto& h = samples.back().history;
    std::printf("JC damage, %s (η = %+.3f): εf %.4f, |D − εp/εf| ≤ %.2e, final εp %.4f, D %.4f\n", name, triaxiality,
                failure, worst, h.equivalent_plastic_strain, h.damage);
    EXPECT_LT(worst, 1e-9) << name;
    EXPECT_GT(h.damage, 0.1) << name;
    return failure;
  };
  const double tension = check("uniaxial tension", uniaxial(law, 1.0, 0.2, 1e-4), 1.0 / 3);
  const double compression = check("uniaxial compression", uniaxial(law, -1.0, -0.2, 1e-4), -1.0 / 3);
  const double shear = check("simple shear", run_simple_shear(law, 1.0, 1e-4, 3000), 0.0);
  EXPECT_LT(tension, shear);  // D3 < 0: the failure strain falls as the triaxiality rises
  EXPECT_LT(shear, compression);
  // Past εf the damage stays at 1.
  const auto far = uniaxial(law, 1.0, 0.8, 1e-4);
  EXPECT_EQ(far.back().history.damage, 1.0);
  // Rate dependence of εf (D4): D is the sum of Δεp/εf(η, ε̇p) over the steps.
  law.damage.d4 = 0.05;
  law.rate_coefficient = 0.02;
  const auto fast = uniaxial(law, 1000.0, 0.1, 1e-8);
  double sum = 0;
  for (std::size_t k = 1; k < fast.size(); ++k) {
    const auto& h = fast[k].history;
    const double increment = h.equivalent_plastic_strain - fast[k - 1].history.equivalent_plastic_strain;
    if (increment > 0) sum += increment / law.failure_strain(1.0 / 3, h.equivalent_plastic_strain_rate, 0);
  }
  EXPECT_NEAR(fast.back().history.damage, sum, 1e-9 * sum);
}

TEST(JohnsonCook, RunsInADeckAndItsKeysBelongToIt) {
  const std::string deck = R"deck(discretization: {dimension: 3, spacing: 1 mm, horizon_factor: 3.015}
materials:
  al:
    model: correspondence
    density: 2.7 g/cm^3
    youngs_modulus: 68.9 GPa
    poisson_ratio: 0.33
    constitutive_law: johnson_cook
    yield_stress: 324 MPa
    strain_hardening_coefficient: 114 MPa
    strain_hardening_exponent: 0.42
    strain_rate_coefficient: 0.002
    thermal_softening: {specific_heat: 896, reference_temperature: 294 K, melting_temperature: 925 K, exponent: 1.34}
bodies:
  cube: {material: al, shape: {box: {min: [0, 0, 0], max: [0.006, 0.006, 0.006]}}}
initial_conditions:
  - {velocity: {x: "30*sin(1000*y)", y: "-20*cos(800*z)", z: "1e6*x*y"}}
solver: {num_steps: 120}
output: {progress: false}
)deck";
  Simulation sim(parse_deck(deck, "jc.yaml", "."));
  sim.initialize();
  while (sim.state().step < sim.total_steps()) sim.step();
  sim.prepare_outputs(true, true);
  const State& s = sim.state();
  double largest_eqps = 0, hottest = 0;
  for (std::size_t i = 0; i < sim.num_owned(); ++i) {
    largest_eqps = std::max(largest_eqps, s.history.plastic_strain[i]);
    hottest = std::max(hottest, s.point_outputs.at("temperature")[i]);
  }
  std::printf("JC deck: largest εp %.4f, hottest %.2f K\n", largest_eqps, hottest);
  EXPECT_GT(largest_eqps, 1e-3);
  EXPECT_GT(hottest, 294.0);
  EXPECT_GT(sim.totals().dissipated_energy, 0);
  // A Johnson–Cook key on the J2 law is named as the other law's.
  std::string j2 = deck;
  j2.replace(j2.find("constitutive_law: johnson_cook"), 30, "constitutive_law: j2_viscoplastic");
  try {
    parse_deck(j2, "jc.yaml", ".");
    Simulation refused(parse_deck(j2, "jc.yaml", "."));
    ADD_FAILURE() << "a johnson_cook key on j2_viscoplastic was accepted";
  } catch (const InputError& e) {
    std::string all;
    for (const Diagnostic& d : e.diagnostics()) all += d.str() + "\n";
    EXPECT_NE(all.find("strain_hardening_coefficient is a parameter of constitutive_law: johnson_cook, not of "
                       "j2_viscoplastic"),
              std::string::npos)
        << all;
  }
}

}  // namespace
}  // namespace peridot
