// The closed-form creep and recovery of a Prony solid (tests/support/prony_creep.hpp, docs/algorithms.md §11)
// against a direct numerical evaluation of the hereditary integral τ(t) = ∫ μ(t − s) dγ(s): the strain is
// sought piecewise linear in time (plus the jumps at load and release), each step's slope chosen so that the
// integral over the whole history, in closed form per interval, gives the applied stress. No recursion and
// nothing of the closed form enters it. The reference must agree before the viscoelastic validations use it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "support/prony_creep.hpp"

namespace peridot {
namespace {

using testing::PronySeries;

/// γ at t = kΔt, k = 0 … n, for a stress τ0 applied at t = 0 and removed at t₁ = k₁Δt (γ after the jumps).
std::vector<double> convolved_strain(const PronySeries& p, double tau0, int k1, int n, double dt) {
  struct Jump { double t, size; };
  struct Ramp { double a, b, slope; };
  std::vector<Jump> jumps;
  std::vector<Ramp> ramps;
  auto stress_of_history = [&](double t) {
    double s = 0;
    for (const Jump& j : jumps) s += p.relaxation(t - j.t) * j.size;
    for (const Ramp& r : ramps) s += r.slope * p.relaxation_integral(t, r.a, r.b);
    return s;
  };
  std::vector<double> gamma(n + 1);
  jumps.push_back({0.0, tau0 / p.relaxation(0)});
  gamma[0] = jumps.back().size;
  for (int k = 1; k <= n; ++k) {
    const double a = (k - 1) * dt, b = k * dt;
    const double applied = k < k1 ? tau0 : 0.0;
    if (k == k1) {  // the ramp up to t₁ still carries τ0 at t₁⁻; then the release jump
      const double slope = (tau0 - stress_of_history(b)) / p.relaxation_integral(b, a, b);
      ramps.push_back({a, b, slope});
      gamma[k] = gamma[k - 1] + slope * dt;
      jumps.push_back({b, (0.0 - stress_of_history(b)) / p.relaxation(0)});
      gamma[k] += jumps.back().size;
      continue;
    }
    const double slope = (applied - stress_of_history(b)) / p.relaxation_integral(b, a, b);
    ramps.push_back({a, b, slope});
    gamma[k] = gamma[k - 1] + slope * dt;
  }
  return gamma;
}

/// Largest |closed form − convolution| over the grid, relative to the largest strain.
double creep_recovery_difference(const PronySeries& p, double t1, int k1, int n) {
  const double tau0 = 1e3, dt = t1 / k1;
  const testing::CreepCompliance J = testing::creep_compliance(p);
  const std::vector<double> numeric = convolved_strain(p, tau0, k1, n, dt);
  double worst = 0, scale = 0;
  for (int k = 0; k <= n; ++k) {
    const double t = k * dt;
    const double exact = tau0 * (J(t) - (k >= k1 ? J(t - t1) : 0.0));
    worst = std::max(worst, std::abs(exact - numeric[k]));
    scale = std::max(scale, std::abs(exact));
  }
  return worst / scale;
}

TEST(PronyCreep, ComplianceStartsGlassyEndsRelaxedAndInvertsTheRelaxationModulus) {
  const PronySeries p{1e9, {2e9, 3e9, 5e8}, {0.1, 1.0, 10.0}};
  const testing::CreepCompliance J = testing::creep_compliance(p);
  ASSERT_EQ(J.rate.size(), 3u);
  EXPECT_NEAR(J(0), 1 / p.relaxation(0), 1e-12 / p.relaxation(0));
  EXPECT_NEAR(J(1e4), 1 / p.equilibrium, 1e-12 / p.equilibrium);
  for (double rate : J.rate) EXPECT_LT(rate, 0);
  // Retardation is slower than relaxation: every rate lies between −λ_max and 0, and J grows monotonically.
  for (double t = 0; t < 50; t += 0.5) EXPECT_LT(J(t), J(t + 0.5));
}

TEST(PronyCreep, ClosedFormMatchesTheConvolutionIntegral) {
  // Three terms over two decades; creep for 2 s, then recovery for 6 s; Δt = 1 ms.
  const PronySeries p{1e9, {2e9, 3e9, 5e8}, {0.1, 1.0, 10.0}};
  const double coarse = creep_recovery_difference(p, 2.0, 1000, 4000);
  const double fine = creep_recovery_difference(p, 2.0, 2000, 8000);
  std::printf("three-term Prony solid: max |closed form − convolution| / max γ = %.3e (Δt = 2 ms), %.3e (1 ms)\n",
              coarse, fine);
  EXPECT_LT(fine, 1e-6);
  EXPECT_GT(coarse / fine, 3.5);  // second order in Δt: the difference is the quadrature's, not the formula's
}

TEST(PronyCreep, EpoxyOfMadenciOterkusTable1) {
  // E(t) of the epoxy (Guojun 2007, the paper's Table 1, MPa) as shear moduli with ν = 0.3: μ = E/(2(1 + ν)).
  // Its times span 1e-4 s to 3e12 s. The paper's history: load at t = 0, released at 5 ms, observed to 10 ms.
  const std::vector<double> E = {200, 800, 1500, 1000, 1100, 2700, 2900, 2500, 900, 950, 600, 120, 180, 200, 250};
  const std::vector<double> tau = {1e-4, 1e-3, 1e-2, 1, 10, 100, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e11, 3e12};
  PronySeries p;
  const double shear = 1e6 / (2 * 1.3);
  p.equilibrium = 700 * shear;
  for (double e : E) p.moduli.push_back(e * shear);
  p.times = tau;
  const double coarse = creep_recovery_difference(p, 5e-3, 500, 1000);
  const double fine = creep_recovery_difference(p, 5e-3, 1000, 2000);
  std::printf("epoxy Prony solid: max |closed form − convolution| / max γ = %.3e (Δt = 10 µs), %.3e (5 µs)\n",
              coarse, fine);
  EXPECT_LT(fine, 1e-5);
  EXPECT_GT(coarse / fine, 3.5);
}

}  // namespace
}  // namespace peridot
